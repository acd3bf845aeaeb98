// The one place that reads and writes the model. Every edit is one
// model.set("design", next) + model.save_changes(), recorded for undo.
// State shared by every view of one model (history, current layer, tool, picked
// object) lives in a per-widget session, so a second view shows the same thing.
// anywidget hands each render() a new model proxy, so the session is keyed by the
// widget's `_session_id` trait (the proxy itself only where the trait is missing).
import { History } from "./history.js";
import { emptyDesign } from "./design-edit.js";

const byId = new Map();
const byProxy = new WeakMap();

export function session(model) {
  const id = model.get("_session_id");
  const [map, key] = typeof id === "string" && id ? [byId, id] : [byProxy, model];
  let s = map.get(key);
  if (!s) {
    s = { history: new History(), layer: 0, tool: "select", picked: null, bus: new EventTarget() };
    map.set(key, s);
  }
  return s;
}

/** Updates shared UI state (layer, tool, picked) and tells every view. */
export function setUi(model, patch) {
  const s = session(model);
  Object.assign(s, patch);
  s.bus.dispatchEvent(new Event("ui"));
}

/** The design as the model holds it, with defaults for anything missing. Do not mutate. */
export function readDesign(model) {
  const d = model.get("design");
  if (!d || typeof d !== "object") return emptyDesign();
  const base = emptyDesign();
  return { ...base, ...d, canvas: validCanvas(d.canvas) || base.canvas, layers: Array.isArray(d.layers) ? d.layers : [] };
}

const validCanvas = (c) => (Array.isArray(c) && c[0] > 0 && c[1] > 0 ? [Number(c[0]), Number(c[1])] : null);

/** The index of the current layer, clamped to the design. */
export function currentLayer(model) {
  const n = readDesign(model).layers.length;
  const s = session(model);
  return Math.max(0, Math.min(s.layer, n - 1));
}

/** Sends one finished edit to Python; `before`: the design an undo returns to (the model's
 * unless given: a live drag's kernel changed the model's design along the way). */
export function commit(model, next, before = model.get("design")) {
  const s = session(model);
  s.history.record(before);
  model.set("design", next);
  model.save_changes();
}

export function undo(model) {
  const prev = session(model).history.undo(model.get("design"));
  if (!prev) return false;
  model.set("design", prev);
  model.save_changes();
  return true;
}

export function redo(model) {
  const next = session(model).history.redo(model.get("design"));
  if (!next) return false;
  model.set("design", next);
  model.save_changes();
  return true;
}

/** Subscribes to model events ("change:design", "msg:custom", ...) until `signal` aborts. */
export function onModel(model, events, fn, signal) {
  for (const ev of events) {
    model.on(ev, fn);
    signal.addEventListener("abort", () => model.off(ev, fn), { once: true });
  }
}

/** Reads a list trait defensively. */
export const list = (model, name) => {
  const v = model.get(name);
  return Array.isArray(v) ? v : [];
};
