// Mark sprites: each `marks` entry is decoded once (Image from its data URL), then
// rasterised into an ImageBitmap at a power-of-two size near the size marks are drawn
// at, so drawing is one drawImage per mark. A bigger size is made only when the marks
// grow past the current one (the scale grows as a layout fills its container).

const MIN_PX = 8;
const MAX_PX = 512;

export const sizeBucket = (px) => Math.min(MAX_PX, Math.max(MIN_PX, 2 ** Math.ceil(Math.log2(Math.max(1, px)))));

export class MarkBitmaps {
  constructor(onReady) {
    this.onReady = onReady;
    this.entries = []; // per marks index: {src, aspect, img, bitmap, px, pending}
    this.target = MIN_PX;
  }

  /** Takes the `marks` trait; keeps decoded entries whose src did not change. */
  update(marks) {
    const old = new Map(this.entries.map((e) => [e.src, e]));
    this.entries = marks.map((m) => {
      const src = m && typeof m.src === "string" ? m.src : "";
      const aspect = m && m.aspect > 0 ? Number(m.aspect) : 1;
      const kept = old.get(src);
      if (kept && kept.aspect === aspect) return kept;
      const e = { src, aspect, img: null, bitmap: null, px: 0, pending: false };
      if (src.startsWith("data:image/")) this.decode(e);
      return e;
    });
  }

  /** The sprite for marks index k, or null while it is loading. */
  get(k) {
    const e = this.entries[k];
    return e ? e.bitmap : null;
  }

  /** Marks are about to be drawn up to `px` device pixels across. */
  need(px) {
    const bucket = sizeBucket(px);
    if (bucket <= this.target) return;
    this.target = bucket;
    for (const e of this.entries) if (e.img) this.rasterise(e);
  }

  async decode(e) {
    const img = new Image();
    img.src = e.src;
    try {
      await img.decode();
    } catch {
      return; // a broken image stays a plain coloured ellipse
    }
    e.img = img;
    this.rasterise(e);
  }

  async rasterise(e) {
    if (e.pending || e.px >= this.target) return;
    const px = this.target;
    e.pending = true;
    const w = Math.max(1, Math.round(e.aspect >= 1 ? px : px * e.aspect));
    const h = Math.max(1, Math.round(e.aspect >= 1 ? px / e.aspect : px));
    const canvas = typeof OffscreenCanvas !== "undefined" ? new OffscreenCanvas(w, h) : document.createElement("canvas");
    canvas.width = w;
    canvas.height = h;
    const ctx = canvas.getContext("2d");
    ctx.imageSmoothingQuality = "high";
    ctx.drawImage(e.img, 0, 0, w, h);
    try {
      const bitmap = await createImageBitmap(canvas);
      if (e.bitmap && e.bitmap.close) e.bitmap.close();
      e.bitmap = bitmap;
      e.px = px;
    } finally {
      e.pending = false;
    }
    this.onReady();
    if (e.px < this.target) this.rasterise(e);
  }

  dispose() {
    for (const e of this.entries) if (e.bitmap && e.bitmap.close) e.bitmap.close();
    this.entries = [];
  }
}
