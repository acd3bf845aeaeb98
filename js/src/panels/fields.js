// Data fields of the bound DataFrame, draggable (HTML5 drag and drop) onto the current
// layer's channels; or click a field, then a channel (click-to-pick). A channel's x clears it.
import { h, replaceChildren } from "../dom.js";
import { CHANNELS, setEncoding } from "../design-edit.js";
import { list } from "../model-sync.js";

const MIME = "application/x-unitopia-field";

export function createFieldsPanel(view) {
  const { model } = view;
  let picked = null;
  const fieldList = h("div", { class: "ut-field-list" });
  const channels = h("div", { class: "ut-channels" });
  const el = h("section", { class: "ut-panel ut-fields" },
    h("header", {}, h("h3", { text: "Data fields" })), fieldList,
    h("p", { class: "ut-hint", text: "Drag a field onto a channel, or click a field, then a channel." }), channels);

  const names = () => new Set(list(model, "fields").map((f) => String(f.name)));
  const bind = (channel, value) => view.commit(setEncoding(view.design(), view.layer(), channel, value));

  function chip(f) {
    const name = String(f.name);
    return h("span", {
      class: `ut-field${picked === name ? " ut-picked" : ""}`, role: "button", tabindex: "0", draggable: "true",
      dataset: { field: name, type: String(f.type || "") }, title: `${name} (${f.type})`,
      ondragstart: (ev) => {
        ev.dataTransfer.setData(MIME, name);
        ev.dataTransfer.setData("text/plain", name);
        ev.dataTransfer.effectAllowed = "copy";
      },
      onclick: () => {
        picked = picked === name ? null : name;
        update();
      },
      onkeydown: (ev) => (ev.key === "Enter" || ev.key === " ") && (ev.preventDefault(), ev.target.click()),
    }, h("span", { class: "ut-field-name", text: name }), h("small", { class: "ut-field-type", text: typeLabel(f.type) }));
  }

  function slot(channel, value) {
    const bound = value != null && !(channel === "margin" && typeof value === "number");
    const shown = bound ? String(value) : channel === "margin" ? `${value ?? 0}` : "\u2014";
    const el = h("div", {
      class: `ut-channel${bound ? " ut-bound" : ""}${picked ? " ut-target" : ""}`, dataset: { channel }, tabindex: "0",
      ondragover: (ev) => {
        ev.preventDefault();
        ev.dataTransfer.dropEffect = "copy";
        el.classList.add("ut-over");
      },
      ondragleave: () => el.classList.remove("ut-over"),
      ondrop: (ev) => {
        ev.preventDefault();
        el.classList.remove("ut-over");
        const name = ev.dataTransfer.getData(MIME) || ev.dataTransfer.getData("text/plain");
        if (names().has(name)) bind(channel, name);
      },
      onclick: () => {
        if (!picked) return;
        const name = picked;
        picked = null;
        bind(channel, name);
      },
    },
    h("span", { class: "ut-channel-name", text: channel }),
    h("span", { class: "ut-channel-value", text: shown }),
    bound && h("button", { type: "button", class: "ut-btn ut-icon", dataset: { clear: channel }, title: `Clear ${channel}`, "aria-label": `Clear ${channel}`,
      onclick: (ev) => (ev.stopPropagation(), bind(channel, null)) }, "\u2715"),
    channel === "color" && colorInput(value));
    return el;
  }

  function colorInput(value) {
    const literal = typeof value === "string" && /^#[0-9a-f]{6}$/i.test(value) ? value : "#4e79a7";
    return h("input", { type: "color", value: literal, title: "A fixed colour", "aria-label": "A fixed colour", onclick: (ev) => ev.stopPropagation(),
      onchange: (ev) => bind("color", ev.target.value) });
  }

  function update() {
    const fields = list(model, "fields");
    if (picked && !fields.some((f) => String(f.name) === picked)) picked = null;
    replaceChildren(fieldList, fields.length ? fields.map(chip) : h("p", { class: "ut-hint", text: "No data bound." }));
    const layer = view.design().layers[view.layer()];
    const enc = (layer && layer.encodings) || {};
    replaceChildren(channels, layer ? CHANNELS.map((c) => slot(c, enc[c])) : []);
  }

  return { el, update };
}

const typeLabel = (t) => ({ numeric: "123", categorical: "abc", datetime: "date" })[t] || String(t || "");
