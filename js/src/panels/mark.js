// Marks: each layer's mark as Python rendered it (from `marks`, shown through <img>
// with a data URL, never as markup); for the current layer, replace it with a shape,
// an uploaded SVG ({"kind": "svg", "svg": text}: Python sanitises it) or PNG/JPEG
// ({"kind": "image", "image": dataURL}), or a sketch from the pad.
import { h, replaceChildren } from "../dom.js";
import { setLayerProps } from "../design-edit.js";
import { list } from "../model-sync.js";
import { createSketchPad } from "./sketch-pad.js";

const SHAPES = ["circle", "square", "triangle", "star"];

export function createMarkPanel(view) {
  const { model } = view;
  const gallery = h("div", { class: "ut-mark-gallery" });
  const setMark = (mark) => view.commit(setLayerProps(view.design(), view.layer(), { mark }));
  const shape = h("select", { dataset: { setting: "mark-shape" }, "aria-label": "Mark shape", onchange: (ev) => ev.target.value && setMark({ kind: "shape", name: ev.target.value }) },
    h("option", { value: "", text: "shape\u2026" }), SHAPES.map((s) => h("option", { value: s, text: s })));
  const upload = h("input", {
    type: "file", accept: ".svg,.png,.jpg,.jpeg,image/svg+xml,image/png,image/jpeg", dataset: { role: "mark-upload" }, "aria-label": "Upload a mark (SVG or PNG)",
    onchange: async (ev) => {
      const file = ev.target.files && ev.target.files[0];
      ev.target.value = "";
      if (file) setMark(await markFromFile(file));
    },
  });
  const pad = createSketchPad((mark) => setMark(mark));
  pad.el.hidden = true;
  const drawBtn = h("button", { type: "button", class: "ut-btn ut-small", dataset: { action: "sketch-mark" }, "aria-expanded": "false",
    onclick: () => {
      pad.el.hidden = !pad.el.hidden;
      drawBtn.setAttribute("aria-expanded", String(!pad.el.hidden));
    } }, "Draw\u2026");
  const el = h("section", { class: "ut-panel ut-marks" }, h("header", {}, h("h3", { text: "Marks" })), gallery,
    h("div", { class: "ut-mark-tools" }, shape, h("label", { class: "ut-btn ut-small ut-upload" }, "Upload\u2026", upload), drawBtn), pad.el);

  function update() {
    const design = view.design();
    const marks = list(model, "marks");
    const current = view.layer();
    replaceChildren(gallery, design.layers.map((layer, i) => {
      const entry = marks.find((m) => m && m.layer === layer.name);
      const src = entry && typeof entry.src === "string" && entry.src.startsWith("data:image/") ? entry.src : null;
      return h("button", { type: "button", class: `ut-mark${i === current ? " ut-current" : ""}`, dataset: { layer: String(i) }, title: String(layer.name), onclick: () => view.setLayer(i) },
        src ? h("img", { src, alt: `mark of ${layer.name}`, draggable: false }) : h("span", { class: "ut-mark-empty", text: "?" }),
        h("span", { class: "ut-mark-label", text: `${layer.name} \u00b7 ${describe(layer.mark)}` }));
    }));
    shape.value = "";
  }

  return { el, update };
}

function describe(mark) {
  if (!mark || typeof mark !== "object") return "default";
  return mark.kind === "shape" ? String(mark.name) : String(mark.kind);
}

/** An uploaded file -> a mark spec. SVG text goes to Python as text; rasters as data URLs. */
export async function markFromFile(file) {
  const isSvg = file.type === "image/svg+xml" || /\.svg$/i.test(file.name);
  if (isSvg) return { kind: "svg", svg: await file.text() };
  const dataUrl = await new Promise((resolve, reject) => {
    const reader = new FileReader();
    reader.onload = () => resolve(String(reader.result));
    reader.onerror = () => reject(reader.error);
    reader.readAsDataURL(file);
  });
  return { kind: "image", image: dataUrl };
}
