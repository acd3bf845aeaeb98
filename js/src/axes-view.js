// The axes of x= and y= beside the marks: the `axes_image` trait ({"src": data URL, "x",
// "y", "width", "height"} in canvas px, the box the image covers relative to the canvas's
// top-left corner, reaching past the canvas where the axes stand outside it) drawn through
// an <img>, never as markup, at the chart's scale. The stage keeps a margin as wide as
// the part past the canvas (so the stage wrap does not clip it), on paper like the
// canvas, under the containers and marks.
import { h } from "./dom.js";

export function createAxes(model, stage) {
  const img = h("img", { class: "ut-axes", dataset: { role: "axes" }, alt: "axes", draggable: false });
  const paper = h("div", { class: "ut-axes-paper" });

  /** The trait's box [x, y, w, h] in canvas px and its source, or null. */
  const trait = () => {
    const a = model.get("axes_image");
    const box = a ? [a.x, a.y, a.width, a.height].map(Number) : [];
    const ok = a && typeof a.src === "string" && a.src.startsWith("data:image/") && box.every(Number.isFinite) && box[2] > 0 && box[3] > 0;
    return ok ? { src: a.src, box } : null;
  };

  /** Sets the stage's margin for the trait on a canvas of `size` [W, H] px. */
  function update([W, H]) {
    const a = trait();
    const m = a ? [-a.box[0], -a.box[1], a.box[0] + a.box[2] - W, a.box[1] + a.box[3] - H].map((v) => Math.max(0, Math.ceil(v))) : [0, 0, 0, 0];
    if (!a) {   // no axes: neither is in the stage
      img.remove();
      paper.remove();
    } else if (img.parentNode !== stage.el) {
      stage.el.prepend(paper);
      stage.bg.after(img); // over a background image, under the containers and marks
    }
    if (a && img.getAttribute("src") !== a.src) img.src = a.src;
    stage.margin = m;
  }

  /** Places the image and the paper under it at the stage's scale. */
  function place() {
    const a = trait();
    if (!a) return;
    const k = stage.scale;
    const [l, t, r, b] = stage.margin;
    Object.assign(img.style, { left: `${a.box[0] * k}px`, top: `${a.box[1] * k}px`, width: `${a.box[2] * k}px`, height: `${a.box[3] * k}px` });
    Object.assign(paper.style, { left: `${-l * k}px`, top: `${-t * k}px`, width: `${(stage.size[0] + l + r) * k}px`, height: `${(stage.size[1] + t + b) * k}px` });
  }
  return { img, update, place };
}
