// The drawing surface: a background <img> and three stacked canvases (containers,
// marks, overlay of emitters/forces/handles) inside one element that takes the
// pointer events (data-role="stage"). The logical size is design.canvas; the stage
// takes the cell's width at the canvas's aspect ratio (no taller than most of the
// window) and draws at devicePixelRatio. A margin (canvas px: left, top, right, bottom)
// leaves room around the canvas for what is drawn past it (the axes).
import { h, listen } from "./dom.js";

export function createStage(signal) {
  const bg = h("img", { class: "ut-bg", alt: "", draggable: false, hidden: true });
  const scene = h("canvas", { class: "ut-canvas" });
  const marks = h("canvas", { class: "ut-canvas" });
  const over = h("canvas", { class: "ut-canvas" });
  const tooltip = h("div", { class: "ut-tooltip", role: "tooltip", hidden: true });
  const el = h("div", { class: "ut-stage", dataset: { role: "stage" }, tabindex: "-1" }, bg, scene, marks, over, tooltip);
  const wrap = h("div", { class: "ut-stage-wrap" }, el);
  const stage = {
    el, wrap, bg, tooltip,
    canvases: { scene, marks, over },
    size: [0, 0], // set by the first layout()
    margin: [0, 0, 0, 0], // canvas px left, top, right, bottom: room outside the canvas
    scale: 1,
    dpr: 1,
    onResize: () => {},
  };

  let shownMargin = "";
  /** Sizes the canvases for a logical size and the margin; returns true when anything changed. */
  stage.layout = (size) => {
    const [W, H] = size;
    const [l, t, r, b] = stage.margin;
    const avail = wrap.clientWidth || W + l + r;
    const tall = Math.max(240, 0.85 * (window.innerHeight || H + t + b)); // the whole stage stays in view
    const scale = Math.min(avail / (W + l + r), tall / (H + t + b));
    const dpr = window.devicePixelRatio || 1;
    const margin = `${t * scale}px ${r * scale}px ${b * scale}px ${l * scale}px`;
    if (scale === stage.scale && dpr === stage.dpr && W === stage.size[0] && H === stage.size[1] && margin === shownMargin) return false;
    Object.assign(stage, { size: [W, H], scale, dpr });
    el.style.width = `${W * scale}px`;
    el.style.height = `${H * scale}px`;
    el.style.margin = shownMargin = margin;
    for (const c of [scene, marks, over]) {
      c.width = Math.max(1, Math.round(W * scale * dpr));
      c.height = Math.max(1, Math.round(H * scale * dpr));
    }
    return true;
  };

  /** Canvas pixels per backing-store pixel factor: logical px -> device px. */
  stage.k = () => stage.scale * stage.dpr;

  /** A 2D context with the logical-px transform set and the canvas cleared. */
  stage.begin = (name) => {
    const c = stage.canvases[name];
    const ctx = c.getContext("2d");
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.globalAlpha = 1;
    ctx.globalCompositeOperation = "source-over";
    ctx.clearRect(0, 0, c.width, c.height);
    const k = stage.k();
    ctx.setTransform(k, 0, 0, k, 0, 0);
    return ctx;
  };

  /** Pointer event -> canvas px [x, y]. */
  stage.toCanvas = (ev) => {
    const r = el.getBoundingClientRect();
    const x = ev.clientX - r.left - el.clientLeft;
    const y = ev.clientY - r.top - el.clientTop;
    return [(x * stage.size[0]) / (el.clientWidth || 1), (y * stage.size[1]) / (el.clientHeight || 1)];
  };

  /** Shows text near canvas point p (textContent only). */
  stage.showTooltip = (text, p) => {
    tooltip.textContent = text;
    tooltip.hidden = false;
    const x = p[0] * stage.scale;
    const y = p[1] * stage.scale;
    const left = x + 14 + tooltip.offsetWidth > el.clientWidth ? x - 14 - tooltip.offsetWidth : x + 14;
    tooltip.style.left = `${Math.max(0, left)}px`;
    tooltip.style.top = `${Math.max(0, y + 14)}px`;
  };
  stage.hideTooltip = () => void (tooltip.hidden = true);

  if (typeof ResizeObserver !== "undefined") {
    const ro = new ResizeObserver(() => stage.onResize());
    ro.observe(wrap);
    signal.addEventListener("abort", () => ro.disconnect(), { once: true });
  }
  // devicePixelRatio changes (zoom, moving the window to another screen) re-layout too.
  listen(window, "resize", () => stage.onResize(), signal);
  return stage;
}
