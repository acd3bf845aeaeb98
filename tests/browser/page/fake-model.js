// A fake anywidget model for driving the built widget in a plain page.
// window.unitopia.mount(state, {views}) mounts the widget; window.fake is the model:
//   fake.push(name, value)  a trait change from "Python" (no save recorded)
//   fake.message(msg)       a custom message from "Python"
//   fake.saves              one entry per save_changes(): {keys, design, selected_units}
//   fake.sent               custom messages the widget sent
//   fake.playPython(opts)   answers as the kernel would (see playPython below)
import widget from "/static/widget.js";

const clone = (v) => (v === undefined ? undefined : JSON.parse(JSON.stringify(v)));

export class FakeModel {
  constructor(state) {
    this.state = state;
    this.handlers = new Map();
    this.saves = [];
    this.sent = [];
    this.dirty = new Set();
  }
  get(name) {
    return this.state[name];
  }
  set(name, value) {
    this.state[name] = value;
    this.dirty.add(name);
    this.emit(`change:${name}`, value);
  }
  save_changes() {
    this.saves.push({ keys: [...this.dirty], design: clone(this.state.design), selected_units: clone(this.state.selected_units) });
    this.dirty.clear();
  }
  on(event, fn) {
    if (!this.handlers.has(event)) this.handlers.set(event, new Set());
    this.handlers.get(event).add(fn);
  }
  off(event, fn) {
    if (this.handlers.has(event)) this.handlers.get(event).delete(fn);
  }
  send(msg) {
    this.sent.push(clone(msg));
    if (this.python) this.python(msg);
  }
  /**
   * Plays the Python side: each saved design gets `marks` entries, one per (layer, mark)
   * with "mark": k, drawn from the mark's shape (a square for other kinds); an icon query
   * is answered with the names in opts.icons that contain it (at most 30); Run sets
   * status "running"; dismiss-error clears the error.
   */
  playPython({ icons = [] } = {}) {
    const render = () => this.push("marks", marksFor(this.state.design));
    this.python = (msg) => {
      if (msg.type === "icons") {
        const names = icons.filter((n) => n.includes(msg.query)).slice(0, 30);
        setTimeout(() => this.message({ type: "icons", query: msg.query, names }), 10);
      } else if (msg.type === "run") setTimeout(() => this.push("status", "running"), 10);
      else if (msg.type === "dismiss-error") setTimeout(() => this.push("error", ""), 10);
    };
    this.on("change:design", () => setTimeout(render, 0));
    render();
  }
  emit(event, ...args) {
    for (const fn of [...(this.handlers.get(event) || [])]) fn(...args);
  }
  push(name, value) {
    this.state[name] = value;
    this.emit(`change:${name}`, value);
  }
  message(msg, buffers = []) {
    this.emit("msg:custom", msg, buffers);
  }
  listenerCount() {
    let n = 0;
    for (const set of this.handlers.values()) n += set.size;
    return n;
  }
}

/** float32 rows -> DataView, optionally at a byte offset inside a larger buffer. */
export function f32(rows, offset = 0) {
  const flat = new Float32Array(rows.flat());
  const buf = new ArrayBuffer(offset + flat.byteLength);
  new Uint8Array(buf, offset).set(new Uint8Array(flat.buffer));
  return new DataView(buf, offset, flat.byteLength);
}

export function u8(rows) {
  return new DataView(new Uint8Array(rows.flat()).buffer);
}

const COLORS = ["#e15759", "#4e79a7", "#59a14f", "#f28e2b", "#b07aa1"];

/** `marks` entries for a design as Python would send them: one per (layer, mark). */
export function marksFor(design) {
  return design.layers.flatMap((l) => (l.marks || [l.mark]).map((m, k) => ({
    layer: l.name, mark: k, aspect: 1,
    src: svgMark(m && m.kind === "shape" && SHAPES[m.name] ? m.name : "square", COLORS[k % COLORS.length]),
  })));
}

const SHAPES = {
  circle: (c) => `<circle cx="50" cy="50" r="48" fill="${c}"/>`,
  square: (c) => `<rect x="0" y="0" width="100" height="100" fill="${c}"/>`,
  triangle: (c) => `<polygon fill="${c}" points="50,4 98,96 2,96"/>`,
  star: (c) => `<polygon fill="${c}" points="50,2 61,38 98,38 68,60 79,96 50,74 21,96 32,60 2,38 39,38"/>`,
};

export function svgMark(shape = "circle", color = "#e15759") {
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100" viewBox="0 0 100 100">${SHAPES[shape](color)}</svg>`;
  return `data:image/svg+xml;base64,${btoa(svg)}`;
}

export function defaultState() {
  return {
    design: {
      schema: "unitopia-design", version: 2, canvas: [800, 500], background: null, seed: 0,
      legend: { visible: true, position: "right" },
      layers: [{
        name: "layer-1", rows: null, marks: [{ kind: "shape", name: "circle" }], mark_keys: null,
        encodings: { size: null, width: null, height: null, color: null, shape: null, margin: 0.0, order: null },
        container: null, emitter: null, forces: [], boundary: "closed", fill: null,
        orientation: null, rotate: false, blocks: [], iterations: 600,
      }],
    },
    marks: [{ layer: "layer-1", mark: 0, src: svgMark("circle"), aspect: 1 }],
    fields: [{ name: "Duration", type: "numeric" }, { name: "Task", type: "categorical" }],
    units: new DataView(new ArrayBuffer(0)),
    colors: new DataView(new ArrayBuffer(0)),
    titles: [],
    frame: new DataView(new ArrayBuffer(0)),
    frame_count: 0,
    status: "idle",
    stale: false,
    legend_image: {},
    axes_image: {},
    progress: {},
    error: "",
    selected_units: [],
  };
}

const views = [];
let mounted = 0;

/** A new proxy of `model` per call, as anywidget gives initialize() and each render(). */
function proxy(model) {
  const bound = (name) => (...args) => model[name](...args);   // a test may swap fake.send
  return { get: bound("get"), set: bound("set"), save_changes: bound("save_changes"), send: bound("send"), on: bound("on"), off: bound("off") };
}

function mount(state = {}, { views: count = 1 } = {}) {
  unmount();
  mounted += 1;   // each mount is a new widget: its own session
  const model = new FakeModel({ ...defaultState(), _session_id: `widget-${mounted}`, ...state });
  window.fake = model;
  widget.initialize({ model: proxy(model) });
  const app = document.getElementById("app");
  for (let i = 0; i < count; i++) {
    const el = document.createElement("div");
    el.className = "view";
    app.append(el);
    const controller = new AbortController();
    widget.render({ model: proxy(model), el, signal: controller.signal });
    views.push({ el, controller });
  }
  return model.listenerCount();
}

function unmount() {
  while (views.length) {
    const v = views.pop();
    v.controller.abort();
    v.el.remove();
  }
}

window.unitopia = { mount, unmount, f32, u8, svgMark, marksFor, defaultState, FakeModel, views };
window.unitopiaReady = true;
