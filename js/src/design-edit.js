// Pure edits of the design JSON (docs/protocol.md). Each takes a design and returns a
// new one; the input is never mutated, so the old one can go on the undo stack.
import { translatePathData } from "./pathdata.js";

export const CHANNELS = ["size", "width", "height", "color", "shape", "margin", "order", "x", "y"];

export const clone = (value) => (value == null ? value : JSON.parse(JSON.stringify(value)));

export function emptyDesign() {
  return { schema: "unitopia-design", version: 4, canvas: [800, 500], background: null, seed: 0, layers: [] };
}

export function newLayer(name, mark = { kind: "shape", name: "circle" }) {
  return {
    name,
    rows: null,
    marks: [clone(mark)],
    mark_keys: null,
    encodings: { size: null, width: null, height: null, color: null, shape: null, margin: 0.0, order: null, x: null, y: null },
    container: null,
    emitter: null,
    forces: [],
    boundary: "closed",
    fill: null,
    orientation: null,
    rotate: false,
    blocks: [],
    iterations: 600,
    footprint: "silhouette",
    margin_of: "median",
    x_scale: "linear",
    y_scale: "linear",
    arrange: "free",
  };
}

/** A layer name not used yet: base, base-2, base-3, ... */
export function uniqueName(design, base) {
  const used = new Set(design.layers.map((l) => l.name));
  if (!used.has(base)) return base;
  let k = 2;
  while (used.has(`${base}-${k}`)) k++;
  return `${base}-${k}`;
}

/** Returns a copy of the design with layer i replaced by fn(copy of layer i). */
export function updateLayer(design, i, fn) {
  const next = clone(design);
  const layer = next.layers[i];
  if (!layer) return next;
  next.layers[i] = fn(layer) || layer;
  return next;
}

export const setLayerProps = (design, i, props) => updateLayer(design, i, (l) => Object.assign(l, props));

export function addLayer(design) {
  const next = clone(design);
  const last = next.layers[next.layers.length - 1];
  const layer = newLayer(uniqueName(next, `layer-${next.layers.length + 1}`));
  if (last) layer.marks = layerMarks(last);
  next.layers.push(layer);
  return next;
}

export function duplicateLayer(design, i) {
  const next = clone(design);
  const copy = clone(next.layers[i]);
  copy.name = uniqueName(next, `${copy.name}-copy`);
  next.layers.splice(i + 1, 0, copy);
  return next;
}

/** Deletes layer i (never the last one) and removes it from every other layer's blocks. */
export function deleteLayer(design, i) {
  const next = clone(design);
  if (next.layers.length <= 1 || !next.layers[i]) return next;
  const [gone] = next.layers.splice(i, 1);
  for (const l of next.layers) l.blocks = (l.blocks || []).filter((b) => b !== gone.name);
  return next;
}

/** Moves layer i by delta places in the drawing order. */
export function moveLayer(design, i, delta) {
  const next = clone(design);
  const j = i + delta;
  if (j < 0 || j >= next.layers.length) return next;
  const [layer] = next.layers.splice(i, 1);
  next.layers.splice(j, 0, layer);
  return next;
}

/** Renames layer i, keeping other layers' blocks pointing at it. */
export function renameLayer(design, i, name) {
  const next = clone(design);
  const old = next.layers[i] && next.layers[i].name;
  if (!old || !name || next.layers.some((l, k) => k !== i && l.name === name)) return next;
  next.layers[i].name = name;
  for (const l of next.layers) l.blocks = (l.blocks || []).map((b) => (b === old ? name : b));
  return next;
}

/**
 * Binds a field (or null) to a channel of layer i. Only that channel changes: a binding
 * Python cannot combine with the others is refused there, and its error is shown.
 */
export function setEncoding(design, i, channel, value) {
  return updateLayer(design, i, (l) => {
    const enc = { ...newLayer("").encodings, ...(l.encodings || {}) };
    enc[channel] = value == null ? (channel === "margin" ? 0.0 : null) : value;
    l.encodings = enc;
  });
}

/** A layer's marks: its `marks` list, or version 1's single `mark`, or a circle. */
export function layerMarks(layer) {
  if (layer && Array.isArray(layer.marks) && layer.marks.length) return clone(layer.marks);
  if (layer && layer.mark && typeof layer.mark === "object") return [clone(layer.mark)];
  return [{ kind: "shape", name: "circle" }];
}

export const setContainer = (design, i, container) =>
  updateLayer(design, i, (l) => void (l.container = container && { cuts: [], ...container }));

/** Appends an eraser cut to layer i's container (the whole canvas when it has none). */
export function addCut(design, i, cut) {
  return updateLayer(design, i, (l) => {
    const c = l.container || { kind: "canvas" };
    c.cuts = [...(c.cuts || []), cut];
    l.container = c;
  });
}

export const setEmitter = (design, i, emitter) => updateLayer(design, i, (l) => void (l.emitter = emitter));

export const addPointForce = (design, i, x, y, strength = 1.0) =>
  updateLayer(design, i, (l) => void (l.forces = [...(l.forces || []), { kind: "point", x, y, strength }]));

/** Sets the one direction force of layer i, replacing any previous one (point forces stay). */
export function setDirectionForce(design, i, angle, strength = 1.0) {
  return updateLayer(design, i, (l) => {
    const old = (l.forces || []).find((f) => f.kind === "direction");
    const forces = (l.forces || []).filter((f) => f.kind !== "direction");
    forces.push({ kind: "direction", angle, strength: old ? old.strength : strength });
    l.forces = forces;
  });
}

export const removeForce = (design, i, k) =>
  updateLayer(design, i, (l) => void (l.forces = l.forces.filter((_, j) => j !== k)));

/** Moves a container by (dx, dy), cuts included; `canvas` sizes an image without a box. */
export function translateContainer(c, dx, dy, canvas = [800, 500]) {
  if (!c) return c;
  const out = clone(c);
  const mv = (p) => [p[0] + dx, p[1] + dy];
  if (out.kind === "rect") Object.assign(out, { x: c.x + dx, y: c.y + dy });
  else if (out.kind === "ellipse") Object.assign(out, { cx: c.cx + dx, cy: c.cy + dy });
  else if (out.kind === "polygon") out.points = c.points.map(mv);
  else if (out.kind === "path") out.d = translatePathData(c.d, dx, dy);
  else if (out.kind === "image") {
    const [x, y, w, h] = c.box || [0, 0, canvas[0], canvas[1]];
    out.box = [x + dx, y + dy, w, h];
  }
  if (out.cuts) out.cuts = out.cuts.map((cut) => ({ ...cut, points: cut.points.map(mv) }));
  return out;
}
