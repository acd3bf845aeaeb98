// Decoded images by data URL (background, image containers), loaded once each.
// The URL only ever goes into Image.src: an <img> cannot run scripts.

export class ImageCache {
  constructor(onLoad) {
    this.onLoad = onLoad;
    this.entries = new Map();
  }

  /** The decoded image, or null while loading (onLoad fires when it arrives). */
  get(src) {
    if (typeof src !== "string" || !src.startsWith("data:image/")) return null;
    let e = this.entries.get(src);
    if (!e) {
      const img = new Image();
      e = { img, ready: false };
      this.entries.set(src, e);
      img.onload = () => {
        e.ready = true;
        this.onLoad();
      };
      img.src = src;
    }
    return e.ready ? e.img : null;
  }

  /** Forgets images whose URL is not in `keep`. */
  prune(keep) {
    for (const src of this.entries.keys()) if (!keep.has(src)) this.entries.delete(src);
  }
}
