// Settings of the current layer: boundary, fill, orientation, arrange, the x/y scales
// (once x or y is bound), rotate, margin,
// iterations, one mark for k units (count, per, rounding, partial), blocks (checkboxes of
// the other layers) and the emitter's options.
import { h, replaceChildren, row } from "../dom.js";
import { setEncoding, setLayerProps, updateLayer } from "../design-edit.js";

const num = (v) => (v === "" || v == null || !Number.isFinite(Number(v)) ? null : Number(v));

export function createSettingsPanel(view) {
  const body = h("div", { class: "ut-settings-body" });
  const title = h("h3", { text: "Layer settings" });
  const el = h("section", { class: "ut-panel ut-settings" }, h("header", {}, title), body);
  const set = (props) => view.commit(setLayerProps(view.design(), view.layer(), props));

  function select(setting, options, value, onchange) {
    const s = h("select", { dataset: { setting }, onchange: (ev) => onchange(ev.target.value) },
      options.map(([v, label]) => h("option", { value: v, text: label })));
    s.value = value;
    return s;
  }
  const input = (setting, props, onchange) => h("input", { dataset: { setting }, ...props, onchange: (ev) => onchange(ev.target) });

  function update() {
    const design = view.design();
    const i = view.layer();
    const layer = design.layers[i];
    if (!layer) return replaceChildren(body, h("p", { class: "ut-hint", text: "No layer." }));
    title.textContent = `Layer settings: ${layer.name}`;
    const orient = layer.orientation;
    // orientation: null, "to_center", "along_emitter", degrees, "random" or ["random", lo, hi]
    const orientKind = typeof orient === "number" ? "angle" : Array.isArray(orient) ? "random" : orient || "none";
    const [lo, hi] = Array.isArray(orient) ? orient.slice(1) : [-180, 180];
    const range = (from, to) => set({ orientation: from === -180 && to === 180 ? "random" : ["random", from, to] });
    const margin = layer.encodings?.margin;
    const rows = [
      row("boundary", select("boundary", [["closed", "closed (fill)"], ["open", "open (bound only)"]], layer.boundary || "closed", (v) => set({ boundary: v }))),
      row("fill", input("fill", { type: "number", min: "0.05", max: "1", step: "0.05", value: layer.fill ?? "", placeholder: "auto" }, (t) => set({ fill: num(t.value) }))),
      row("orientation", select("orientation", [["none", "none"], ["to_center", "to centre"], ["along_emitter", "along emitter"], ["angle", "angle\u2026"], ["random", "random angles\u2026"]], orientKind, (v) =>
        set({ orientation: v === "none" ? null : v === "angle" ? 0 : v }))),
      orientKind === "angle" && row("angle", input("angle", { type: "number", step: "5", value: orient }, (t) => set({ orientation: num(t.value) ?? 0 }))),
      orientKind === "random" && row("angles from", input("random_lo", { type: "number", step: "5", value: lo }, (t) => range(num(t.value) ?? -180, hi))),
      orientKind === "random" && row("angles to", input("random_hi", { type: "number", step: "5", value: hi }, (t) => range(lo, num(t.value) ?? 180))),
      row("arrange", select("arrange", [["free", "free (packed)"], ["grid", "grid (rows and columns)"]], layer.arrange || "free", (v) => set({ arrange: v }))),
      ...["x", "y"].map((c) => layer.encodings?.[c] != null && row(`${c} scale`,
        select(`${c}_scale`, [["linear", "linear"], ["log", "log"]], layer[`${c}_scale`] || "linear", (v) => set({ [`${c}_scale`]: v })))),
      row("rotate", input("rotate", { type: "checkbox", checked: !!layer.rotate }, (t) => set({ rotate: t.checked }))),
      row("margin", input("margin", { type: "number", min: "0", step: "0.01", value: typeof margin === "number" ? margin : "", placeholder: typeof margin === "string" ? `field ${margin}` : "0" },
        (t) => view.commit(setEncoding(view.design(), i, "margin", num(t.value) ?? 0)))),
      row("iterations", input("iterations", { type: "number", min: "1", step: "50", value: layer.iterations ?? 600 }, (t) => set({ iterations: Math.max(1, Math.round(num(t.value) ?? 600)) }))),
      tallyRows(layer),
      blocksRow(design, i, layer),
      emitterRows(layer, i),
    ];
    replaceChildren(body, rows);
  }

  // count= (a numeric field: each row stands for that many units) and per= (one mark for
  // k units of one category), with the rounding of a group's remainder or a partial mark
  function tallyRows(layer) {
    const numeric = (view.model.get("fields") || []).filter((f) => f.type === "numeric").map((f) => String(f.name));
    const counts = [["", "1 per row"], ...numeric.map((n) => [n, n])];
    if (layer.count != null && !numeric.includes(String(layer.count))) counts.push([String(layer.count), String(layer.count)]);
    const per = layer.per ?? null;
    return h("fieldset", { class: "ut-tally" }, h("legend", { text: "one mark for k units" }),
      row("count", select("count", counts, layer.count ?? "", (v) => set({ count: v === "" ? null : v }))),
      row("per", input("per", { type: "number", min: "0", step: "any", value: per ?? "", placeholder: "1 unit" }, (t) => {
        const k = num(t.value);
        set({ per: k != null && k > 0 ? k : null });
      })),
      per != null && row("rounding", select("rounding", [["largest-remainder", "largest remainder"], ["floor", "floor"], ["ceil", "ceil"], ["nearest", "nearest"]], layer.rounding || "largest-remainder", (v) => set({ rounding: v }))),
      per != null && row("partial", input("partial", { type: "checkbox", checked: !!layer.partial }, (t) => set({ partial: t.checked }))));
  }
  function blocksRow(design, i, layer) {
    const others = design.layers.filter((_, k) => k !== i);
    if (!others.length) return null;
    const boxes = others.map((o) =>
      h("label", { class: "ut-check" },
        h("input", { type: "checkbox", dataset: { block: String(o.name) }, checked: (layer.blocks || []).includes(o.name),
          onchange: (ev) => {
            const blocks = new Set(layer.blocks || []);
            ev.target.checked ? blocks.add(o.name) : blocks.delete(o.name);
            set({ blocks: design.layers.map((l) => l.name).filter((n) => blocks.has(n)) });
          } }),
        String(o.name)));
    return h("fieldset", { class: "ut-blocks" }, h("legend", { text: "blocks (obstacles)" }), boxes);
  }

  function emitterRows(layer, i) {
    const e = layer.emitter;
    if (!e) return null;
    const setE = (props) => view.commit(updateLayer(view.design(), i, (l) => void Object.assign(l.emitter, props)));
    return h("fieldset", { class: "ut-emitter" }, h("legend", { text: `${e.kind} emitter` }),
      row("speed", input("emitter-speed", { type: "number", min: "0", step: "0.1", value: e.speed ?? 1 }, (t) => setE({ speed: num(t.value) ?? 1 }))),
      e.kind === "curve" && row("direction", select("emitter-direction", [["along", "along"], ["normal", "normal"]], typeof e.direction === "string" ? e.direction : "along", (v) => setE({ direction: v }))),
      e.kind === "curve" && row("mode", select("emitter-mode", [["free", "free"], ["line", "line (1D)"], ["band", "band (2D)"]], e.mode || "free", (v) => setE({ mode: v }))));
  }

  return { el, update };
}
