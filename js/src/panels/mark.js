// Marks: the current layer's mark set (design layer "marks"), each shown as Python
// rendered it (the `marks` entry with its layer and "mark": k, through <img> with a data
// URL, never as markup), with buttons to reorder and remove it. New marks come from a
// shape, an upload (SVG as text, Python sanitises it; PNG/JPEG as a data URL), the
// sketch pad, or an icon name looked up by the kernel (icon-search.js).
import { h, replaceChildren } from "../dom.js";
import { layerMarks } from "../design-edit.js";
import { addMark, describeMark, moveMark, removeMark } from "../mark-set.js";
import { list } from "../model-sync.js";
import { createSketchPad } from "./sketch-pad.js";
import { createIconSearch } from "./icon-search.js";

const SHAPES = ["circle", "square", "triangle", "star"];

export function createMarkPanel(view) {
  const { model } = view;
  const title = h("h3", { text: "Marks" });
  const items = h("ol", { class: "ut-mark-list" });
  const edit = (fn) => view.commit(fn(view.design(), view.layer()));
  const add = (mark) => edit((d, i) => addMark(d, i, mark));
  const shape = h("select", { dataset: { setting: "mark-shape" }, "aria-label": "Add a shape mark", onchange: (ev) => ev.target.value && add({ kind: "shape", name: ev.target.value }) },
    h("option", { value: "", text: "+ shape\u2026" }), SHAPES.map((s) => h("option", { value: s, text: s })));
  const upload = h("input", {
    type: "file", accept: ".svg,.png,.jpg,.jpeg,image/svg+xml,image/png,image/jpeg", dataset: { role: "mark-upload" }, "aria-label": "Upload a mark (SVG or PNG)",
    onchange: async (ev) => {
      const file = ev.target.files && ev.target.files[0];
      ev.target.value = "";
      if (file) add(await markFromFile(file));
    },
  });
  const pad = createSketchPad(add);
  pad.el.hidden = true;
  const drawBtn = h("button", { type: "button", class: "ut-btn ut-small", dataset: { action: "sketch-mark" }, "aria-expanded": "false",
    onclick: () => {
      pad.el.hidden = !pad.el.hidden;
      drawBtn.setAttribute("aria-expanded", String(!pad.el.hidden));
    } }, "Draw\u2026");
  const icons = createIconSearch(model, view.signal, (name) => add({ kind: "icon", name }));
  const el = h("section", { class: "ut-panel ut-marks" }, h("header", {}, title), items,
    h("div", { class: "ut-mark-tools" }, shape, h("label", { class: "ut-btn ut-small ut-upload" }, "+ upload\u2026", upload), drawBtn),
    icons.el, pad.el);

  function item(layer, mark, k, n, entries) {
    const entry = entries.find((m) => m && m.layer === layer.name && (Number(m.mark) || 0) === k);
    const key = Array.isArray(layer.mark_keys) && layer.mark_keys.length === n ? layer.mark_keys[k] : undefined;
    const label = key === undefined ? describeMark(mark) : `${describeMark(mark)} = ${key}`; // the category it draws
    const src = entry && typeof entry.src === "string" && entry.src.startsWith("data:image/") ? entry.src : null;
    const btn = (act, label, text, fn, disabled) =>
      h("button", { type: "button", class: "ut-btn ut-icon", dataset: { markAction: act }, title: label, "aria-label": label, disabled, onclick: fn }, text);
    return h("li", { class: "ut-mark", dataset: { mark: String(k), kind: String(mark && mark.kind) } },
      src ? h("img", { src, alt: `mark ${k + 1}`, draggable: false }) : h("span", { class: "ut-mark-empty", text: "?" }),
      h("span", { class: "ut-mark-label", text: label, title: label }),
      btn("up", "Move up", "\u2191", () => edit((d, i) => moveMark(d, i, k, -1)), k === 0),
      btn("down", "Move down", "\u2193", () => edit((d, i) => moveMark(d, i, k, 1)), k === n - 1),
      btn("remove", "Remove this mark", "\u2715", () => edit((d, i) => removeMark(d, i, k)), n <= 1));
  }

  function update() {
    const layer = view.design().layers[view.layer()];
    shape.value = "";
    if (!layer) return replaceChildren(items, h("li", { class: "ut-hint", text: "No layer." }));
    title.textContent = `Marks: ${layer.name}`;
    const marks = layerMarks(layer);
    const entries = list(model, "marks");
    replaceChildren(items, marks.map((m, k) => item(layer, m, k, marks.length, entries)));
  }

  return { el, update };
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
