// Layers: add (data-action="add-layer"), pick the current one, rename, reorder,
// duplicate, delete. Drawing order is list order.
import { h, replaceChildren } from "../dom.js";
import * as edit from "../design-edit.js";
import { layerColor } from "../shapes.js";

export function createLayersPanel(view) {
  const list = h("ol", { class: "ut-layer-list" });
  const add = h("button", {
    type: "button", class: "ut-btn ut-small", dataset: { action: "add-layer" }, title: "Add a layer", "aria-label": "Add a layer",
    onclick: () => {
      const next = edit.addLayer(view.design());
      view.commit(next);
      view.setLayer(next.layers.length - 1);
    },
  }, "+ layer");
  const el = h("section", { class: "ut-panel ut-layers" }, h("header", {}, h("h3", { text: "Layers" }), add), list);

  function rowFor(layer, i, current, n) {
    const name = h("input", {
      class: "ut-layer-name", value: String(layer.name), "aria-label": "Layer name", spellcheck: false,
      onfocus: () => view.setLayer(i),
      onchange: (ev) => {
        const v = ev.target.value.trim();
        if (v && v !== layer.name) view.commit(edit.renameLayer(view.design(), i, v));
        else ev.target.value = layer.name;
      },
      onkeydown: (ev) => ev.key === "Enter" && ev.target.blur(),
    });
    const btn = (act, label, text, fn, disabled = false) =>
      h("button", { type: "button", class: "ut-btn ut-icon", dataset: { layerAction: act }, title: label, "aria-label": label, disabled, onclick: (ev) => (ev.stopPropagation(), fn()) }, text);
    return h(
      "li",
      { class: `ut-layer${i === current ? " ut-current" : ""}`, dataset: { layer: String(i) }, onclick: () => view.setLayer(i) },
      h("span", { class: "ut-swatch", style: { background: layerColor(i) } }),
      name,
      btn("up", "Move up (drawn earlier)", "\u2191", () => move(i, -1), i === 0),
      btn("down", "Move down (drawn later)", "\u2193", () => move(i, 1), i === n - 1),
      btn("duplicate", "Duplicate", "\u229e", () => {
        view.commit(edit.duplicateLayer(view.design(), i));
        view.setLayer(i + 1);
      }),
      btn("delete", "Delete", "\u2715", () => {
        view.commit(edit.deleteLayer(view.design(), i));
        view.setLayer(Math.max(0, Math.min(i, n - 2)));
      }, n <= 1),
    );
  }

  function move(i, delta) {
    view.commit(edit.moveLayer(view.design(), i, delta));
    view.setLayer(i + delta);
  }

  // Rows are rebuilt only when the layers change, so focusing a name field (which makes
  // its layer current) does not replace the field being typed into.
  let shown = null;
  function update() {
    const design = view.design();
    const current = view.layer();
    const key = JSON.stringify(design.layers.map((l) => l.name));
    if (key !== shown) {
      shown = key;
      replaceChildren(list, design.layers.map((l, i) => rowFor(l, i, current, design.layers.length)));
    }
    [...list.children].forEach((li, i) => li.classList.toggle("ut-current", i === current));
  }

  return { el, update };
}
