// src/history.js
var History = class {
  constructor(limit = 100) {
    this.limit = limit;
    this.past = [];
    this.future = [];
  }
  /** Records `before`, the design as it was before an edit; clears the redo stack. */
  record(before) {
    const snap = JSON.stringify(before);
    if (this.past[this.past.length - 1] !== snap) this.past.push(snap);
    if (this.past.length > this.limit) this.past.shift();
    this.future = [];
  }
  get canUndo() {
    return this.past.length > 0;
  }
  get canRedo() {
    return this.future.length > 0;
  }
  /** Returns the design to restore, given the current one; null when nothing to undo. */
  undo(current) {
    if (!this.past.length) return null;
    this.future.push(JSON.stringify(current));
    return JSON.parse(this.past.pop());
  }
  /** Returns the design to restore, given the current one; null when nothing to redo. */
  redo(current) {
    if (!this.future.length) return null;
    this.past.push(JSON.stringify(current));
    return JSON.parse(this.future.pop());
  }
};

// src/pathdata.js
var ARGS = { M: 2, L: 2, T: 2, H: 1, V: 1, C: 6, S: 4, Q: 4, A: 7, Z: 0 };
var TOKEN = /([MLHVCSQTAZmlhvcsqtaz])|(-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)/g;
function translatePathData(d, dx, dy) {
  const out = [];
  let cmd = null;
  let args = [];
  let first = true;
  const flush = () => {
    if (!cmd) return;
    const upper = cmd.toUpperCase();
    const n = ARGS[upper];
    if (n === 0) return void out.push(cmd);
    for (let k = 0; k + n <= args.length; k += n) {
      const a = args.slice(k, k + n);
      const absolute = cmd === upper || first && cmd === "m" && k === 0;
      if (absolute) shift(upper, a, dx, dy);
      out.push(k === 0 ? cmd : "", ...a.map(fmt));
      first = false;
    }
  };
  for (const m of String(d).matchAll(TOKEN)) {
    if (m[1]) {
      flush();
      cmd = m[1];
      args = [];
    } else {
      args.push(Number(m[2]));
    }
  }
  flush();
  return out.filter((t) => t !== "").join(" ");
}
function shift(upper, a, dx, dy) {
  if (upper === "H") a[0] += dx;
  else if (upper === "V") a[0] += dy;
  else if (upper === "A") {
    a[5] += dx;
    a[6] += dy;
  } else {
    for (let j = 0; j < a.length; j += 2) {
      a[j] += dx;
      a[j + 1] += dy;
    }
  }
}
var fmt = (v) => String(Math.round(v * 1e3) / 1e3);

// src/design-edit.js
var CHANNELS = ["size", "width", "height", "color", "shape", "margin", "order", "x", "y"];
var clone = (value) => value == null ? value : JSON.parse(JSON.stringify(value));
function emptyDesign() {
  return { schema: "unitopia-design", version: 4, canvas: [800, 500], background: null, seed: 0, layers: [] };
}
function newLayer(name, mark = { kind: "shape", name: "circle" }) {
  return {
    name,
    rows: null,
    marks: [clone(mark)],
    mark_keys: null,
    encodings: { size: null, width: null, height: null, color: null, shape: null, margin: 0, order: null, x: null, y: null },
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
    arrange: "free"
  };
}
function uniqueName(design, base) {
  const used = new Set(design.layers.map((l) => l.name));
  if (!used.has(base)) return base;
  let k = 2;
  while (used.has(`${base}-${k}`)) k++;
  return `${base}-${k}`;
}
function updateLayer(design, i, fn) {
  const next = clone(design);
  const layer = next.layers[i];
  if (!layer) return next;
  next.layers[i] = fn(layer) || layer;
  return next;
}
var setLayerProps = (design, i, props) => updateLayer(design, i, (l) => Object.assign(l, props));
function addLayer(design) {
  const next = clone(design);
  const last = next.layers[next.layers.length - 1];
  const layer = newLayer(uniqueName(next, `layer-${next.layers.length + 1}`));
  if (last) layer.marks = layerMarks(last);
  next.layers.push(layer);
  return next;
}
function duplicateLayer(design, i) {
  const next = clone(design);
  const copy = clone(next.layers[i]);
  copy.name = uniqueName(next, `${copy.name}-copy`);
  next.layers.splice(i + 1, 0, copy);
  return next;
}
function deleteLayer(design, i) {
  const next = clone(design);
  if (next.layers.length <= 1 || !next.layers[i]) return next;
  const [gone] = next.layers.splice(i, 1);
  for (const l of next.layers) l.blocks = (l.blocks || []).filter((b) => b !== gone.name);
  return next;
}
function moveLayer(design, i, delta) {
  const next = clone(design);
  const j = i + delta;
  if (j < 0 || j >= next.layers.length) return next;
  const [layer] = next.layers.splice(i, 1);
  next.layers.splice(j, 0, layer);
  return next;
}
function renameLayer(design, i, name) {
  const next = clone(design);
  const old = next.layers[i] && next.layers[i].name;
  if (!old || !name || next.layers.some((l, k) => k !== i && l.name === name)) return next;
  next.layers[i].name = name;
  for (const l of next.layers) l.blocks = (l.blocks || []).map((b) => b === old ? name : b);
  return next;
}
function setEncoding(design, i, channel, value) {
  return updateLayer(design, i, (l) => {
    const enc = { ...newLayer("").encodings, ...l.encodings || {} };
    enc[channel] = value == null ? channel === "margin" ? 0 : null : value;
    l.encodings = enc;
  });
}
function layerMarks(layer) {
  if (layer && Array.isArray(layer.marks) && layer.marks.length) return clone(layer.marks);
  if (layer && layer.mark && typeof layer.mark === "object") return [clone(layer.mark)];
  return [{ kind: "shape", name: "circle" }];
}
var setContainer = (design, i, container) => updateLayer(design, i, (l) => void (l.container = container && { cuts: [], ...container }));
function addCut(design, i, cut) {
  return updateLayer(design, i, (l) => {
    const c = l.container || { kind: "canvas" };
    c.cuts = [...c.cuts || [], cut];
    l.container = c;
  });
}
var setEmitter = (design, i, emitter) => updateLayer(design, i, (l) => void (l.emitter = emitter));
var addPointForce = (design, i, x, y, strength = 1) => updateLayer(design, i, (l) => void (l.forces = [...l.forces || [], { kind: "point", x, y, strength }]));
function setDirectionForce(design, i, angle, strength = 1) {
  return updateLayer(design, i, (l) => {
    const old = (l.forces || []).find((f) => f.kind === "direction");
    const forces = (l.forces || []).filter((f) => f.kind !== "direction");
    forces.push({ kind: "direction", angle, strength: old ? old.strength : strength });
    l.forces = forces;
  });
}
var removeForce = (design, i, k) => updateLayer(design, i, (l) => void (l.forces = l.forces.filter((_, j) => j !== k)));
function translateContainer(c, dx, dy, canvas = [800, 500]) {
  if (!c) return c;
  const out = clone(c);
  const mv = (p) => [p[0] + dx, p[1] + dy];
  if (out.kind === "rect") Object.assign(out, { x: c.x + dx, y: c.y + dy });
  else if (out.kind === "ellipse") Object.assign(out, { cx: c.cx + dx, cy: c.cy + dy });
  else if (out.kind === "polygon") out.points = c.points.map(mv);
  else if (out.kind === "path") out.d = translatePathData(c.d, dx, dy);
  else if (out.kind === "image") {
    const [x, y, w, h2] = c.box || [0, 0, canvas[0], canvas[1]];
    out.box = [x + dx, y + dy, w, h2];
  }
  if (out.cuts) out.cuts = out.cuts.map((cut) => ({ ...cut, points: cut.points.map(mv) }));
  return out;
}

// src/model-sync.js
var byId = /* @__PURE__ */ new Map();
var byProxy = /* @__PURE__ */ new WeakMap();
function session(model) {
  const id = model.get("_session_id");
  const [map, key] = typeof id === "string" && id ? [byId, id] : [byProxy, model];
  let s = map.get(key);
  if (!s) {
    s = { history: new History(), layer: 0, tool: "select", picked: null, bus: new EventTarget() };
    map.set(key, s);
  }
  return s;
}
function setUi(model, patch) {
  const s = session(model);
  Object.assign(s, patch);
  s.bus.dispatchEvent(new Event("ui"));
}
function readDesign(model) {
  const d = model.get("design");
  if (!d || typeof d !== "object") return emptyDesign();
  const base = emptyDesign();
  return { ...base, ...d, canvas: validCanvas(d.canvas) || base.canvas, layers: Array.isArray(d.layers) ? d.layers : [] };
}
var validCanvas = (c) => Array.isArray(c) && c[0] > 0 && c[1] > 0 ? [Number(c[0]), Number(c[1])] : null;
function currentLayer(model) {
  const n = readDesign(model).layers.length;
  const s = session(model);
  return Math.max(0, Math.min(s.layer, n - 1));
}
function commit(model, next, before = model.get("design")) {
  const s = session(model);
  s.history.record(before);
  model.set("design", next);
  model.save_changes();
}
function undo(model) {
  const prev = session(model).history.undo(model.get("design"));
  if (!prev) return false;
  model.set("design", prev);
  model.save_changes();
  return true;
}
function redo(model) {
  const next = session(model).history.redo(model.get("design"));
  if (!next) return false;
  model.set("design", next);
  model.save_changes();
  return true;
}
function onModel(model, events, fn, signal) {
  for (const ev of events) {
    model.on(ev, fn);
    signal.addEventListener("abort", () => model.off(ev, fn), { once: true });
  }
}
var list = (model, name) => {
  const v = model.get(name);
  return Array.isArray(v) ? v : [];
};

// src/dom.js
function h(tag, props = {}, ...children) {
  const el = document.createElement(tag);
  for (const [key, value] of Object.entries(props)) {
    if (value == null || value === false) continue;
    if (key === "class") el.className = value;
    else if (key === "text") el.textContent = String(value);
    else if (key === "dataset") Object.assign(el.dataset, value);
    else if (key === "style") Object.assign(el.style, value);
    else if (key.startsWith("on") && typeof value === "function") el.addEventListener(key.slice(2), value);
    else if (key in el && typeof value !== "string") el[key] = value;
    else el.setAttribute(key, value === true ? "" : String(value));
  }
  for (const child of children.flat()) {
    if (child == null || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return el;
}
function replaceChildren(el, ...children) {
  el.replaceChildren(...children.flat().filter((c) => c != null && c !== false));
}
var row = (label, control, extra = {}) => h("label", { class: "ut-row", ...extra }, h("span", { class: "ut-label", text: label }), control);
function listen(target, type, fn, signal, options = {}) {
  target.addEventListener(type, fn, { ...options, signal });
}

// src/stage.js
function createStage(signal) {
  const bg = h("img", { class: "ut-bg", alt: "", draggable: false, hidden: true });
  const scene = h("canvas", { class: "ut-canvas" });
  const marks = h("canvas", { class: "ut-canvas" });
  const over = h("canvas", { class: "ut-canvas" });
  const tooltip = h("div", { class: "ut-tooltip", role: "tooltip", hidden: true });
  const el = h("div", { class: "ut-stage", dataset: { role: "stage" }, tabindex: "-1" }, bg, scene, marks, over, tooltip);
  const wrap = h("div", { class: "ut-stage-wrap" }, el);
  const stage = {
    el,
    wrap,
    bg,
    tooltip,
    canvases: { scene, marks, over },
    size: [0, 0],
    // set by the first layout()
    margin: [0, 0, 0, 0],
    // canvas px left, top, right, bottom: room outside the canvas
    scale: 1,
    dpr: 1,
    onResize: () => {
    }
  };
  let shownMargin = "";
  stage.layout = (size) => {
    const [W, H] = size;
    const [l, t, r, b] = stage.margin;
    const avail = wrap.clientWidth || W + l + r;
    const tall = Math.max(240, 0.85 * (window.innerHeight || H + t + b));
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
  stage.k = () => stage.scale * stage.dpr;
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
  stage.toCanvas = (ev) => {
    const r = el.getBoundingClientRect();
    const x = ev.clientX - r.left - el.clientLeft;
    const y = ev.clientY - r.top - el.clientTop;
    return [x * stage.size[0] / (el.clientWidth || 1), y * stage.size[1] / (el.clientHeight || 1)];
  };
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
  listen(window, "resize", () => stage.onResize(), signal);
  return stage;
}

// src/images.js
var ImageCache = class {
  constructor(onLoad) {
    this.onLoad = onLoad;
    this.entries = /* @__PURE__ */ new Map();
  }
  /** The decoded image, or null while loading (onLoad fires when it arrives). */
  get(src) {
    if (typeof src !== "string" || !src.startsWith("data:image/")) return null;
    let e = this.entries.get(src);
    if (!e) {
      const img = new Image();
      e = { img, ready: false };
      this.entries.set(src, e);
      img.onload = () => {
        e.ready = true;
        this.onLoad();
      };
      img.src = src;
    }
    return e.ready ? e.img : null;
  }
  /** Forgets images whose URL is not in `keep`. */
  prune(keep) {
    for (const src of this.entries.keys()) if (!keep.has(src)) this.entries.delete(src);
  }
};

// src/bitmaps.js
var MIN_PX = 8;
var MAX_PX = 512;
var sizeBucket = (px) => Math.min(MAX_PX, Math.max(MIN_PX, 2 ** Math.ceil(Math.log2(Math.max(1, px)))));
var MarkBitmaps = class {
  constructor(onReady) {
    this.onReady = onReady;
    this.entries = [];
    this.target = MIN_PX;
  }
  /** Takes the `marks` trait; keeps decoded entries whose src did not change. */
  update(marks) {
    const old = new Map(this.entries.map((e) => [e.src, e]));
    this.entries = marks.map((m) => {
      const src = m && typeof m.src === "string" ? m.src : "";
      const aspect = m && m.aspect > 0 ? Number(m.aspect) : 1;
      const kept = old.get(src);
      if (kept && kept.aspect === aspect) return kept;
      const e = { src, aspect, img: null, bitmap: null, px: 0, pending: false };
      if (src.startsWith("data:image/")) this.decode(e);
      return e;
    });
  }
  /** The sprite for marks index k, or null while it is loading. */
  get(k) {
    const e = this.entries[k];
    return e ? e.bitmap : null;
  }
  /** Marks are about to be drawn up to `px` device pixels across. */
  need(px) {
    const bucket = sizeBucket(px);
    if (bucket <= this.target) return;
    this.target = bucket;
    for (const e of this.entries) if (e.img) this.rasterise(e);
  }
  async decode(e) {
    const img = new Image();
    img.src = e.src;
    try {
      await img.decode();
    } catch {
      return;
    }
    e.img = img;
    this.rasterise(e);
  }
  async rasterise(e) {
    if (e.pending || e.px >= this.target) return;
    const px = this.target;
    e.pending = true;
    const w = Math.max(1, Math.round(e.aspect >= 1 ? px : px * e.aspect));
    const h2 = Math.max(1, Math.round(e.aspect >= 1 ? px / e.aspect : px));
    const canvas = typeof OffscreenCanvas !== "undefined" ? new OffscreenCanvas(w, h2) : document.createElement("canvas");
    canvas.width = w;
    canvas.height = h2;
    const ctx = canvas.getContext("2d");
    ctx.imageSmoothingQuality = "high";
    ctx.drawImage(e.img, 0, 0, w, h2);
    try {
      const bitmap = await createImageBitmap(canvas);
      if (e.bitmap && e.bitmap.close) e.bitmap.close();
      e.bitmap = bitmap;
      e.px = px;
    } finally {
      e.pending = false;
    }
    this.onReady();
    if (e.px < this.target) this.rasterise(e);
  }
  dispose() {
    for (const e of this.entries) if (e.bitmap && e.bitmap.close) e.bitmap.close();
    this.entries = [];
  }
};

// src/frames.js
function asBytes(value) {
  if (!value) return null;
  if (value instanceof DataView || ArrayBuffer.isView(value)) {
    return { buffer: value.buffer, offset: value.byteOffset, length: value.byteLength };
  }
  if (value instanceof ArrayBuffer) return { buffer: value, offset: 0, length: value.byteLength };
  return null;
}
function decodeFloat32(value, cols = 4) {
  const b = asBytes(value);
  if (!b || b.length < 4 * cols) return null;
  const count = Math.floor(b.length / (4 * cols)) * cols;
  if (b.offset % 4 === 0) return new Float32Array(b.buffer, b.offset, count);
  return new Float32Array(b.buffer.slice(b.offset, b.offset + count * 4));
}
function decodeUint8(value) {
  const b = asBytes(value);
  if (!b || !b.length) return null;
  return new Uint8Array(b.buffer, b.offset, b.length);
}
function sameFrame(a, b) {
  if (!a || !b) return a === b;
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}
function angleDelta(a, b) {
  return ((b - a) % 360 + 540) % 360 - 180;
}
function lerpFrame(out, from, to, alpha) {
  for (let i = 0; i < to.length; i += 4) {
    out[i] = from[i] + (to[i] - from[i]) * alpha;
    out[i + 1] = from[i + 1] + (to[i + 1] - from[i + 1]) * alpha;
    out[i + 2] = from[i + 2] === to[i + 2] ? to[i + 2] : from[i + 2] + angleDelta(from[i + 2], to[i + 2]) * alpha;
    out[i + 3] = from[i + 3] + (to[i + 3] - from[i + 3]) * alpha;
  }
  return out;
}
var FrameInterpolator = class {
  constructor({ minMs = 16, maxMs = 250 } = {}) {
    this.minMs = minMs;
    this.maxMs = maxMs;
    this.from = null;
    this.to = null;
    this.current = null;
    this.start = 0;
    this.duration = 33;
    this.lastArrival = -1;
    this.settled = true;
  }
  /** A new target frame arrived at time `now` (ms). */
  push(frame, now) {
    if (this.lastArrival >= 0) {
      const gap = Math.min(this.maxMs, Math.max(this.minMs, now - this.lastArrival));
      this.duration = 0.7 * this.duration + 0.3 * gap;
    }
    this.lastArrival = now;
    if (!frame) {
      this.from = this.to = this.current = null;
      this.settled = false;
      return;
    }
    const sameShape = this.current && this.current.length === frame.length;
    this.from = sameShape ? Float32Array.from(this.current) : frame;
    this.to = frame;
    if (!sameShape) this.current = new Float32Array(frame.length);
    this.start = now;
    this.settled = false;
  }
  /** Jumps to the latest frame (no animation). */
  snap() {
    if (this.to) this.current.set(this.to);
    this.from = this.to;
    this.settled = false;
  }
  /**
   * Updates `current` for time `now`. Returns true when it changed since the previous
   * call (the caller then repaints), false once the animation has settled.
   */
  step(now) {
    if (this.settled) return false;
    if (!this.to) {
      this.settled = true;
      return true;
    }
    const alpha = this.from === this.to ? 1 : Math.min(1, (now - this.start) / this.duration);
    const { from, to, current } = this;
    if (alpha >= 1) {
      current.set(to);
      this.from = to;
      this.settled = true;
      return true;
    }
    lerpFrame(current, from, to, alpha);
    return true;
  }
};

// src/geometry.js
var dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);
function pathLength(points) {
  let total = 0;
  for (let i = 1; i < points.length; i++) total += dist(points[i - 1], points[i]);
  return total;
}
function polygonArea(points) {
  let a = 0;
  for (let i = 0, j = points.length - 1; i < points.length; j = i++) {
    a += points[j][0] * points[i][1] - points[i][0] * points[j][1];
  }
  return a / 2;
}
function pointInPolygon(p, points) {
  let inside = false;
  const [x, y] = p;
  for (let i = 0, j = points.length - 1; i < points.length; j = i++) {
    const [xi, yi] = points[i];
    const [xj, yj] = points[j];
    if (yi > y !== yj > y && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}
function distToSegment(p, a, b) {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  let t = len2 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0;
  t = Math.max(0, Math.min(1, t));
  return Math.hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}
function distToPolyline(p, points, closed = false) {
  let best = Infinity;
  const n = points.length;
  if (n === 1) return dist(p, points[0]);
  for (let i = 1; i < n + (closed ? 1 : 0); i++) {
    best = Math.min(best, distToSegment(p, points[i - 1], points[i % n]));
  }
  return best;
}
function pointInRotatedBox(px, py, cx, cy, w, h2, angleDeg2) {
  const r = -angleDeg2 * Math.PI / 180;
  const dx = px - cx;
  const dy = py - cy;
  const bx = dx * Math.cos(r) - dy * Math.sin(r);
  const by = dx * Math.sin(r) + dy * Math.cos(r);
  return Math.abs(bx) <= w / 2 && Math.abs(by) <= h2 / 2;
}
function simplify(points, tolerance = 1) {
  if (points.length < 3) return points.slice();
  const keep = new Uint8Array(points.length);
  keep[0] = keep[points.length - 1] = 1;
  const stack = [[0, points.length - 1]];
  while (stack.length) {
    const [first, last] = stack.pop();
    let worst = -1;
    let worstDist = tolerance;
    for (let i = first + 1; i < last; i++) {
      const d = distToSegment(points[i], points[first], points[last]);
      if (d > worstDist) [worst, worstDist] = [i, d];
    }
    if (worst > 0) {
      keep[worst] = 1;
      stack.push([first, worst], [worst, last]);
    }
  }
  return points.filter((_, i) => keep[i]);
}
function closeStroke(points, { snap = 16, minArea = 16 } = {}) {
  if (points.length < 3) return null;
  const start = points[0];
  let end = points.length;
  const snapped = dist(points[end - 1], start) <= snap && pathLength(points) > 3 * snap;
  if (snapped) {
    while (end > 3 && dist(points[end - 1], start) <= snap) end--;
  }
  const polygon = points.slice(0, end).map((p) => [round2(p[0]), round2(p[1])]);
  if (polygon.length < 3 || Math.abs(polygonArea(polygon)) < minArea) return null;
  return { points: polygon, snapped };
}
var round2 = (v) => Math.round(v * 100) / 100;
function ellipsePolygon(cx, cy, rx, ry, n = 48) {
  const out = [];
  for (let i = 0; i < n; i++) {
    const t = 2 * Math.PI * i / n;
    out.push([cx + rx * Math.cos(t), cy + ry * Math.sin(t)]);
  }
  return out;
}
function boxFromCorners(a, b) {
  return {
    x: Math.min(a[0], b[0]),
    y: Math.min(a[1], b[1]),
    w: Math.abs(b[0] - a[0]),
    h: Math.abs(b[1] - a[1])
  };
}
function angleDeg(a, b) {
  const deg = Math.atan2(b[1] - a[1], b[0] - a[0]) * 180 / Math.PI;
  return round2((deg + 360) % 360);
}

// src/hit-index.js
var HitIndex = class {
  constructor(units, frame, { cellSize = 0 } = {}) {
    const n = Math.min(units ? units.length : 0, frame ? frame.length : 0) / 4;
    this.n = n;
    this.units = units;
    this.frame = frame;
    this.half = new Float32Array(n);
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity, sum = 0;
    for (let i = 0; i < n; i++) {
      const s = frame[4 * i + 3];
      const r = 0.5 * Math.hypot(units[4 * i + 2] * s, units[4 * i + 3] * s);
      const x = frame[4 * i];
      const y = frame[4 * i + 1];
      this.half[i] = Number.isFinite(r + x + y) ? r : -1;
      if (this.half[i] < 0) continue;
      sum += r;
      minX = Math.min(minX, x - r);
      minY = Math.min(minY, y - r);
      maxX = Math.max(maxX, x + r);
      maxY = Math.max(maxY, y + r);
    }
    if (!(minX <= maxX)) return void (this.n = 0);
    const span = Math.max(maxX - minX, maxY - minY, 1);
    this.cell = Math.max(cellSize || Math.max(4, 2 * sum / n), span / 511);
    this.x0 = minX;
    this.y0 = minY;
    this.cols = Math.ceil((maxX - minX) / this.cell) + 1;
    this.rows = Math.ceil((maxY - minY) / this.cell) + 1;
    this.build();
  }
  cellOf(v, origin, count) {
    return Math.max(0, Math.min(count - 1, Math.floor((v - origin) / this.cell)));
  }
  build() {
    const { n, cols, rows, frame, half } = this;
    const counts = new Uint32Array(cols * rows + 1);
    const each = (fn) => {
      for (let i = 0; i < n; i++) {
        if (half[i] < 0) continue;
        const x = frame[4 * i];
        const y = frame[4 * i + 1];
        const c0 = this.cellOf(x - half[i], this.x0, cols), c1 = this.cellOf(x + half[i], this.x0, cols);
        const r0 = this.cellOf(y - half[i], this.y0, rows), r1 = this.cellOf(y + half[i], this.y0, rows);
        for (let r = r0; r <= r1; r++) for (let c = c0; c <= c1; c++) fn(r * cols + c, i);
      }
    };
    each((cell) => counts[cell + 1]++);
    for (let k = 1; k < counts.length; k++) counts[k] += counts[k - 1];
    this.starts = counts.slice();
    this.items = new Uint32Array(counts[counts.length - 1]);
    const fill = counts.slice();
    each((cell, i) => this.items[fill[cell]++] = i);
  }
  /** Index of the topmost mark (drawn last = highest index) under (x, y), or -1. */
  query(x, y) {
    if (!this.n) return -1;
    const c = Math.floor((x - this.x0) / this.cell);
    const r = Math.floor((y - this.y0) / this.cell);
    if (c < 0 || r < 0 || c >= this.cols || r >= this.rows) return -1;
    const cell = r * this.cols + c;
    let best = -1;
    for (let k = this.starts[cell]; k < this.starts[cell + 1]; k++) {
      const i = this.items[k];
      if (i > best && this.contains(i, x, y)) best = i;
    }
    return best;
  }
  contains(i, x, y) {
    const f = this.frame;
    const s = f[4 * i + 3];
    const w = this.units[4 * i + 2] * s;
    const h2 = this.units[4 * i + 3] * s;
    return pointInRotatedBox(x, y, f[4 * i], f[4 * i + 1], w, h2, f[4 * i + 2]);
  }
  /** Indices of marks whose centre lies inside the polygon (lasso selection), ascending. */
  inPolygon(points) {
    const out = [];
    for (let i = 0; i < this.n; i++) {
      if (this.half[i] >= 0 && pointInPolygon([this.frame[4 * i], this.frame[4 * i + 1]], points)) out.push(i);
    }
    return out;
  }
};

// src/bezier.js
var add = (a, b) => [a[0] + b[0], a[1] + b[1]];
var sub = (a, b) => [a[0] - b[0], a[1] - b[1]];
var mul = (a, s) => [a[0] * s, a[1] * s];
var dot = (a, b) => a[0] * b[0] + a[1] * b[1];
var norm = (a) => {
  const len = Math.hypot(a[0], a[1]);
  return len ? [a[0] / len, a[1] / len] : [0, 0];
};
function cubicAt(b, t) {
  const s = 1 - t;
  const w0 = s * s * s;
  const w1 = 3 * s * s * t;
  const w2 = 3 * s * t * t;
  const w3 = t * t * t;
  return [
    w0 * b[0][0] + w1 * b[1][0] + w2 * b[2][0] + w3 * b[3][0],
    w0 * b[0][1] + w1 * b[1][1] + w2 * b[2][1] + w3 * b[3][1]
  ];
}
function derivative(b) {
  const out = [];
  for (let i = 0; i < b.length - 1; i++) out.push(mul(sub(b[i + 1], b[i]), b.length - 1));
  return out;
}
function bezierAt(b, t) {
  let pts = b;
  while (pts.length > 1) {
    const next = [];
    for (let i = 0; i < pts.length - 1; i++) next.push(add(mul(pts[i], 1 - t), mul(pts[i + 1], t)));
    pts = next;
  }
  return pts[0];
}
function segments(points) {
  const out = [];
  for (let i = 0; i + 3 < points.length; i += 3) out.push(points.slice(i, i + 4));
  return out;
}
function sampleCurve(points, perSegment = 24) {
  const out = [];
  segments(points).forEach((seg, k) => {
    for (let i = k ? 1 : 0; i <= perSegment; i++) out.push(cubicAt(seg, i / perSegment));
  });
  return out;
}
function fitCurve(points, tolerance = 4) {
  const pts = points.filter((p, i) => i === 0 || p[0] !== points[i - 1][0] || p[1] !== points[i - 1][1]);
  if (pts.length < 2) return [];
  const left = endTangent(pts);
  const right = endTangent(pts.slice().reverse());
  const out = [pts[0]];
  fitCubic(pts, left, right, tolerance * tolerance, out);
  return out.map((p) => [Math.round(p[0] * 100) / 100, Math.round(p[1] * 100) / 100]);
}
function fitCubic(pts, tan1, tan2, error2, out) {
  if (pts.length === 2) {
    const d = Math.hypot(...sub(pts[1], pts[0])) / 3;
    out.push(add(pts[0], mul(tan1, d)), add(pts[1], mul(tan2, d)), pts[1]);
    return;
  }
  let u = chordParams(pts);
  let bez = generate(pts, u, tan1, tan2);
  let [maxErr, split] = maxError(pts, bez, u);
  if (maxErr < error2) return void out.push(bez[1], bez[2], bez[3]);
  if (maxErr < Math.max(error2 * 16, 400)) {
    for (let i = 0; i < 50; i++) {
      u = u.map((t, j) => newtonRaphson(bez, pts[j], t));
      bez = generate(pts, u, tan1, tan2);
      [maxErr, split] = maxError(pts, bez, u);
      if (maxErr < error2) return void out.push(bez[1], bez[2], bez[3]);
    }
  }
  const center = norm(sub(pts[split - 1], pts[split + 1]));
  fitCubic(pts.slice(0, split + 1), tan1, center, error2, out);
  fitCubic(pts.slice(split), mul(center, -1), tan2, error2, out);
}
function endTangent(pts) {
  const total = pts.length - 1;
  if (total < 2) return norm(sub(pts[total], pts[0]));
  const d = (i, j) => Math.hypot(...sub(pts[j], pts[i]));
  let k = 1;
  while (2 * k + 2 <= total && d(0, k) < 6) k++;
  const [p0, p1, p2] = [pts[0], pts[k], pts[Math.min(total, 2 * k)]];
  const d1 = d(0, k);
  const d2 = Math.hypot(...sub(p2, p1));
  if (!d1 || !d2) return norm(sub(pts[total], pts[0]));
  const a = -(2 * d1 + d2) / (d1 * (d1 + d2));
  const b = (d1 + d2) / (d1 * d2);
  const c = -d1 / (d2 * (d1 + d2));
  const t = norm([a * p0[0] + b * p1[0] + c * p2[0], a * p0[1] + b * p1[1] + c * p2[1]]);
  const chord = norm(sub(p1, p0));
  return dot(t, chord) > 0.5 ? t : chord;
}
function chordParams(pts) {
  const u = [0];
  for (let i = 1; i < pts.length; i++) u.push(u[i - 1] + Math.hypot(...sub(pts[i], pts[i - 1])));
  const total = u[u.length - 1];
  return u.map((v) => v / total);
}
function generate(pts, u, tan1, tan2) {
  const first = pts[0];
  const last = pts[pts.length - 1];
  const c = [0, 0, 0];
  const x = [0, 0];
  u.forEach((t, i) => {
    const s = 1 - t;
    const a1 = mul(tan1, 3 * s * s * t);
    const a2 = mul(tan2, 3 * s * t * t);
    c[0] += dot(a1, a1);
    c[1] += dot(a1, a2);
    c[2] += dot(a2, a2);
    const base = add(mul(first, s * s * s + 3 * s * s * t), mul(last, 3 * s * t * t + t * t * t));
    const tmp = sub(pts[i], base);
    x[0] += dot(a1, tmp);
    x[1] += dot(a2, tmp);
  });
  const det = c[0] * c[2] - c[1] * c[1];
  let alpha1 = det ? (x[0] * c[2] - x[1] * c[1]) / det : 0;
  let alpha2 = det ? (c[0] * x[1] - c[1] * x[0]) / det : 0;
  const segLen = Math.hypot(...sub(last, first));
  if (alpha1 < 1e-6 * segLen || alpha2 < 1e-6 * segLen) alpha1 = alpha2 = segLen / 3;
  return [first, add(first, mul(tan1, alpha1)), add(last, mul(tan2, alpha2)), last];
}
function maxError(pts, bez, u) {
  let worst = 0;
  let split = Math.floor(pts.length / 2);
  for (let i = 1; i < pts.length - 1; i++) {
    const d = sub(cubicAt(bez, u[i]), pts[i]);
    const e = dot(d, d);
    if (e >= worst) [worst, split] = [e, i];
  }
  return [worst, split];
}
function newtonRaphson(bez, p, t) {
  const d1 = derivative(bez);
  const d2 = derivative(d1);
  const diff = sub(bezierAt(bez, t), p);
  const q1 = bezierAt(d1, t);
  const q2 = bezierAt(d2, t);
  const den = dot(q1, q1) + dot(diff, q2);
  if (!den) return t;
  const next = t - dot(diff, q1) / den;
  return Math.min(1, Math.max(0, next));
}

// src/shapes.js
var PALETTE = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#b07aa1", "#edc948", "#ff9da7"];
var layerColor = (i) => PALETTE[i % PALETTE.length];
function containerPath(c, canvas) {
  const p = new Path2D();
  if (!c || c.kind === "canvas") p.rect(0, 0, canvas[0], canvas[1]);
  else if (c.kind === "rect") p.rect(c.x, c.y, c.w, c.h);
  else if (c.kind === "ellipse") p.ellipse(c.cx, c.cy, Math.abs(c.rx), Math.abs(c.ry), 0, 0, 2 * Math.PI);
  else if (c.kind === "polygon" && Array.isArray(c.points) && c.points.length) {
    c.points.forEach((q, i) => i ? p.lineTo(q[0], q[1]) : p.moveTo(q[0], q[1]));
    p.closePath();
  } else if (c.kind === "path" && typeof c.d === "string") {
    try {
      return new Path2D(c.d);
    } catch {
      return null;
    }
  } else return null;
  return p;
}
var imageBox = (c, canvas) => Array.isArray(c.box) ? c.box : [0, 0, canvas[0], canvas[1]];
function containerOutline(c, canvas) {
  if (!c || c.kind === "canvas") return null;
  if (c.kind === "rect") return [[c.x, c.y], [c.x + c.w, c.y], [c.x + c.w, c.y + c.h], [c.x, c.y + c.h]];
  if (c.kind === "ellipse") return ellipsePolygon(c.cx, c.cy, Math.abs(c.rx), Math.abs(c.ry));
  if (c.kind === "polygon") return c.points;
  if (c.kind === "image") {
    const [x, y, w, h2] = imageBox(c, canvas);
    return [[x, y], [x + w, y], [x + w, y + h2], [x, y + h2]];
  }
  return null;
}
function containerBounds(c, canvas) {
  const pts = containerOutline(c, canvas);
  if (!pts || !pts.length) return [0, 0, canvas[0], canvas[1]];
  const xs = pts.map((p) => p[0]);
  const ys = pts.map((p) => p[1]);
  return [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
}
function insideContainer(c, p, canvas, ctx) {
  if (!c || c.kind === "canvas") return p[0] >= 0 && p[1] >= 0 && p[0] <= canvas[0] && p[1] <= canvas[1];
  if (c.kind === "path") {
    const path = containerPath(c, canvas);
    return !!(path && ctx && ctx.isPointInPath(path, p[0], p[1], "evenodd"));
  }
  const pts = containerOutline(c, canvas);
  return !!pts && pointInPolygon(p, pts);
}
function directionArrow(layer, canvas, angle) {
  const [x0, y0, x1, y1] = containerBounds(layer.container, canvas);
  const from = [(x0 + x1) / 2, (y0 + y1) / 2];
  const r = angle * Math.PI / 180;
  const len = 60;
  return { from, to: [from[0] + len * Math.cos(r), from[1] + len * Math.sin(r)] };
}
var emitterPolyline = (emitter) => emitter && emitter.kind === "curve" && Array.isArray(emitter.points) && emitter.points.length >= 4 ? sampleCurve(emitter.points, 20) : null;

// src/draw-scene.js
function drawScene(ctx, stage, design, current, images) {
  const canvas = design.canvas;
  const scratch = scratchFor(stage);
  const sctx = scratch.getContext("2d");
  design.layers.forEach((layer, i) => {
    const c = layer.container;
    if (!c || c.kind === "canvas" && !(c.cuts && c.cuts.length)) {
      if (i === current) outlineCanvas(ctx, canvas, layerColor(i));
      return;
    }
    sctx.setTransform(1, 0, 0, 1, 0, 0);
    sctx.clearRect(0, 0, scratch.width, scratch.height);
    const k = stage.k();
    sctx.setTransform(k, 0, 0, k, 0, 0);
    paintContainer(sctx, c, canvas, layerColor(i), i === current, images);
    paintCuts(sctx, c.cuts);
    ctx.save();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.globalAlpha = i === current ? 1 : 0.55;
    ctx.drawImage(scratch, 0, 0);
    ctx.restore();
  });
}
function scratchFor(stage) {
  const { width, height } = stage.canvases.scene;
  if (!stage.scratch) stage.scratch = document.createElement("canvas");
  if (stage.scratch.width !== width || stage.scratch.height !== height) {
    stage.scratch.width = width;
    stage.scratch.height = height;
  }
  return stage.scratch;
}
function paintContainer(ctx, c, canvas, color, active, images) {
  ctx.lineWidth = active ? 2 : 1;
  ctx.strokeStyle = color;
  ctx.setLineDash(active ? [] : [6, 4]);
  if (c.kind === "image") {
    const img = images.get(c.image);
    const [x, y, w, h2] = imageBox(c, canvas);
    if (img) {
      ctx.globalAlpha = 0.35;
      ctx.drawImage(img, x, y, w, h2);
      ctx.globalAlpha = 1;
    }
    ctx.strokeRect(x, y, w, h2);
    return;
  }
  const path = containerPath(c, canvas);
  if (!path) return;
  ctx.fillStyle = color;
  ctx.globalAlpha = active ? 0.16 : 0.08;
  ctx.fill(path, "evenodd");
  ctx.globalAlpha = 1;
  if (c.kind !== "canvas") ctx.stroke(path);
  ctx.setLineDash([]);
}
function paintCuts(ctx, cuts) {
  if (!Array.isArray(cuts) || !cuts.length) return;
  ctx.save();
  ctx.globalCompositeOperation = "destination-out";
  ctx.lineCap = "round";
  ctx.lineJoin = "round";
  ctx.strokeStyle = "#000";
  for (const cut of cuts) {
    if (!cut || !Array.isArray(cut.points) || !cut.points.length) continue;
    ctx.lineWidth = Math.max(1, Number(cut.width) || 12);
    ctx.beginPath();
    cut.points.forEach((p, i) => i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]));
    if (cut.points.length === 1) ctx.lineTo(cut.points[0][0] + 0.01, cut.points[0][1]);
    ctx.stroke();
  }
  ctx.restore();
}
function outlineCanvas(ctx, canvas, color) {
  ctx.save();
  ctx.strokeStyle = color;
  ctx.globalAlpha = 0.5;
  ctx.setLineDash([4, 4]);
  ctx.lineWidth = 1;
  ctx.strokeRect(0.5, 0.5, canvas[0] - 1, canvas[1] - 1);
  ctx.restore();
}

// src/draw-overlay.js
function drawOverlay(ctx, { design, current, picked, unit, tool, guides = true, pins = null }) {
  design.layers.forEach((layer, i) => {
    const active = i === current;
    ctx.globalAlpha = active ? 1 : 0.4;
    const color = layerColor(i);
    if (guides) drawEmitter(ctx, layer, design.canvas, color, active, unit);
    if (guides) (layer.forces || []).forEach((f, k) => {
      const hot = active && picked && picked.kind === "force" && picked.index === k;
      if (f.kind === "point") drawPoint(ctx, [f.x, f.y], color, hot, unit);
      else if (f.kind === "direction") {
        const { from, to } = directionArrow(layer, design.canvas, f.angle);
        drawArrow(ctx, from, to, color, hot, unit);
      }
    });
    if (active && picked && picked.kind === "container") highlightContainer(ctx, layer.container, design.canvas, unit);
  });
  ctx.globalAlpha = 1;
  if (pins && pins.frame) {
    for (const i of pins.list) if (4 * i + 1 < pins.frame.length) drawPin(ctx, pins.frame[4 * i], pins.frame[4 * i + 1], unit);
  }
  if (tool && tool.preview) tool.preview(ctx, unit);
}
function drawPin(ctx, x, y, unit) {
  const r = 4 * unit;
  const top = y - 9 * unit;
  ctx.lineWidth = 1.5 * unit;
  ctx.strokeStyle = "#fff";
  ctx.beginPath();
  ctx.moveTo(x, y);
  ctx.lineTo(x, top);
  ctx.stroke();
  ctx.strokeStyle = "#333";
  ctx.lineWidth = unit;
  ctx.stroke();
  ctx.beginPath();
  ctx.arc(x, top, r, 0, 2 * Math.PI);
  ctx.fillStyle = "#d93025";
  ctx.fill();
  ctx.lineWidth = 1.5 * unit;
  ctx.strokeStyle = "#fff";
  ctx.stroke();
}
function drawEmitter(ctx, layer, canvas, color, active, unit) {
  const e = layer.emitter;
  if (!e) return;
  if (e.kind === "grid") {
    const path = containerPath(layer.container && layer.container.kind !== "image" ? layer.container : null, canvas);
    ctx.save();
    ctx.clip(path, "evenodd");
    ctx.strokeStyle = color;
    ctx.globalAlpha *= 0.45;
    ctx.lineWidth = unit;
    ctx.beginPath();
    for (let d = -canvas[1]; d < canvas[0]; d += 14) {
      ctx.moveTo(d, 0);
      ctx.lineTo(d + canvas[1], canvas[1]);
    }
    ctx.stroke();
    ctx.restore();
    return;
  }
  const line = emitterPolyline(e);
  if (!line) return;
  ctx.strokeStyle = color;
  ctx.lineWidth = 3 * unit;
  ctx.setLineDash([10 * unit, 5 * unit]);
  polyline(ctx, line);
  ctx.stroke();
  ctx.setLineDash([]);
  if (!active) return;
  const pts = e.points;
  ctx.lineWidth = unit;
  ctx.strokeStyle = "#555";
  for (let a = 0; a < pts.length; a += 3) {
    if (a > 0) segment(ctx, pts[a], pts[a - 1]);
    if (a + 1 < pts.length) segment(ctx, pts[a], pts[a + 1]);
  }
  pts.forEach((p, j) => {
    ctx.fillStyle = j % 3 === 0 ? color : "#fff";
    ctx.strokeStyle = j % 3 === 0 ? "#fff" : color;
    ctx.beginPath();
    if (j % 3 === 0) ctx.rect(p[0] - 5 * unit, p[1] - 5 * unit, 10 * unit, 10 * unit);
    else ctx.arc(p[0], p[1], 4 * unit, 0, 2 * Math.PI);
    ctx.fill();
    ctx.stroke();
  });
}
function drawPoint(ctx, p, color, hot, unit) {
  ctx.beginPath();
  ctx.arc(p[0], p[1], 7 * unit, 0, 2 * Math.PI);
  ctx.fillStyle = color;
  ctx.fill();
  ctx.lineWidth = (hot ? 3 : 2) * unit;
  ctx.strokeStyle = hot ? "#1a73e8" : "#fff";
  ctx.stroke();
}
function drawArrow(ctx, from, to, color, hot, unit) {
  const a = Math.atan2(to[1] - from[1], to[0] - from[0]);
  const head = 12 * unit;
  ctx.strokeStyle = hot ? "#1a73e8" : color;
  ctx.fillStyle = ctx.strokeStyle;
  ctx.lineWidth = 3 * unit;
  segment(ctx, from, to);
  ctx.beginPath();
  ctx.moveTo(to[0], to[1]);
  ctx.lineTo(to[0] - head * Math.cos(a - 0.45), to[1] - head * Math.sin(a - 0.45));
  ctx.lineTo(to[0] - head * Math.cos(a + 0.45), to[1] - head * Math.sin(a + 0.45));
  ctx.closePath();
  ctx.fill();
}
function highlightContainer(ctx, c, canvas, unit) {
  const path = containerPath(c && c.kind === "image" ? { kind: "rect", x: c.box?.[0] ?? 0, y: c.box?.[1] ?? 0, w: c.box?.[2] ?? canvas[0], h: c.box?.[3] ?? canvas[1] } : c, canvas);
  if (!path) return;
  ctx.strokeStyle = "#1a73e8";
  ctx.lineWidth = 2 * unit;
  ctx.setLineDash([6 * unit, 4 * unit]);
  ctx.stroke(path);
  ctx.setLineDash([]);
}
function polyline(ctx, pts) {
  ctx.beginPath();
  pts.forEach((p, i) => i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]));
}
function segment(ctx, a, b) {
  ctx.beginPath();
  ctx.moveTo(a[0], a[1]);
  ctx.lineTo(b[0], b[1]);
  ctx.stroke();
}

// src/draw-marks.js
var RAD = Math.PI / 180;
function markCount({ units, frame }) {
  return Math.floor(Math.min(units ? units.length : 0, frame ? frame.length : 0) / 4);
}
function drawRange(ctx, k, { units, frame, colors, bitmaps, clips }, from, until) {
  let maxSide = 0;
  let upright = false;
  for (let i = from; i < until; i++) {
    const s = frame[4 * i + 3];
    const w = units[4 * i + 2] * s;
    const h2 = units[4 * i + 3] * s;
    const x = frame[4 * i];
    const y = frame[4 * i + 1];
    if (!(w > 0 && h2 > 0) || !Number.isFinite(x + y)) continue;
    if (w > maxSide) maxSide = w;
    if (h2 > maxSide) maxSide = h2;
    const deg = frame[4 * i + 2];
    let cx = 0;
    let cy = 0;
    if (deg === 0) {
      if (!upright) ctx.setTransform(k, 0, 0, k, 0, 0);
      upright = true;
      cx = x;
      cy = y;
    } else {
      const c = Math.cos(deg * RAD) * k;
      const sn = Math.sin(deg * RAD) * k;
      ctx.setTransform(c, sn, -sn, c, x * k, y * k);
      upright = false;
    }
    const bmp = bitmaps.get(units[4 * i + 1]);
    const cut = clips && clips[i] < 1;
    if (cut) {
      ctx.save();
      ctx.beginPath();
      ctx.rect(cx - w / 2, cy - h2 / 2, w * clips[i], h2);
      ctx.clip();
    }
    if (bmp) {
      ctx.drawImage(bmp, cx - w / 2, cy - h2 / 2, w, h2);
    } else {
      ctx.fillStyle = rgba(colors, i);
      ctx.beginPath();
      ctx.ellipse(cx, cy, w / 2, h2 / 2, 0, 0, 2 * Math.PI);
      ctx.fill();
    }
    if (cut) ctx.restore();
  }
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  return { maxSide };
}
function drawSelection(ctx, k, state) {
  const { units, frame, selected } = state;
  if (selected && selected.size) outlineSelected(ctx, k, units, frame, markCount(state), selected);
  ctx.setTransform(1, 0, 0, 1, 0, 0);
}
function outlineSelected(ctx, k, units, frame, n, selected) {
  for (const i of selected) {
    if (i < 0 || i >= n) continue;
    const s = frame[4 * i + 3];
    const w = units[4 * i + 2] * s;
    const h2 = units[4 * i + 3] * s;
    const a = frame[4 * i + 2] * RAD;
    const c = Math.cos(a) * k;
    const sn = Math.sin(a) * k;
    ctx.setTransform(c, sn, -sn, c, frame[4 * i] * k, frame[4 * i + 1] * k);
    ctx.strokeStyle = "#ffffff";
    ctx.lineWidth = 4 / k;
    ctx.strokeRect(-w / 2 - 2 / k, -h2 / 2 - 2 / k, w + 4 / k, h2 + 4 / k);
    ctx.strokeStyle = "#1a73e8";
    ctx.lineWidth = 2 / k;
    ctx.strokeRect(-w / 2 - 2 / k, -h2 / 2 - 2 / k, w + 4 / k, h2 + 4 / k);
  }
}
function rgba(colors, i) {
  if (!colors || colors.length < 4 * i + 4) return "rgba(120, 120, 120, 0.8)";
  return `rgba(${colors[4 * i]}, ${colors[4 * i + 1]}, ${colors[4 * i + 2]}, ${colors[4 * i + 3] / 255})`;
}

// src/marks-painter.js
var SLICE_MS = 8;
var BACK_OPTIONS = { willReadFrequently: true };
var FIRST_SLICE = 512;
var MarksPainter = class {
  /**
   * target: the visible canvas; makeCanvas(): a new canvas for the back buffer;
   * now(): a clock in ms (performance.now by default).
   */
  constructor(target, { makeCanvas = () => document.createElement("canvas"), now = () => performance.now(), sliceMs = SLICE_MS, firstSlice = FIRST_SLICE } = {}) {
    this.target = target;
    this.back = null;
    this.makeCanvas = makeCanvas;
    this.now = now;
    this.sliceMs = sliceMs;
    this.perSlice = firstSlice;
    this.frame = new Float32Array(0);
    this.state = null;
    this.next = 0;
    this.maxSide = 0;
    this.busy = false;
    this.px = 0;
  }
  /** Starts painting `state` ({units, frame, colors, bitmaps, selected}) at zoom k. */
  start(k, state) {
    const n = 4 * markCount(state);
    if (this.frame.length !== n) this.frame = new Float32Array(n);
    if (n) this.frame.set(state.frame.subarray(0, n));
    this.state = { ...state, frame: this.frame };
    this.k = k;
    if (!this.back) this.back = this.makeCanvas();
    if (this.back.width !== this.target.width || this.back.height !== this.target.height) {
      this.back.width = this.target.width;
      this.back.height = this.target.height;
    }
    const ctx = this.back.getContext("2d", BACK_OPTIONS);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.back.width, this.back.height);
    this.next = 0;
    this.maxSide = 0;
    this.busy = true;
  }
  /** Drops an unfinished paint (the canvas was resized: it would show at the old size). */
  cancel() {
    this.busy = false;
  }
  /** Draws one slice; returns true when this step finished the paint and showed it. */
  step() {
    if (!this.busy) return false;
    const n = markCount(this.state);
    const back = this.back.getContext("2d", BACK_OPTIONS);
    const t0 = this.now();
    const until = Math.min(n, this.next + this.perSlice);
    const done = drawRange(back, this.k, this.state, this.next, until);
    back.getImageData(0, 0, 1, 1);
    const ms = Math.max(1e-3, this.now() - t0);
    if (until > this.next) this.perSlice = Math.max(16, Math.floor(this.sliceMs * (until - this.next) / ms));
    this.next = until;
    this.maxSide = Math.max(this.maxSide, done.maxSide);
    if (this.next < n) return false;
    const ctx = this.target.getContext("2d");
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.globalAlpha = 1;
    ctx.globalCompositeOperation = "source-over";
    ctx.clearRect(0, 0, this.target.width, this.target.height);
    ctx.drawImage(this.back, 0, 0);
    drawSelection(ctx, this.k, this.state);
    this.px = this.maxSide * this.k;
    this.busy = false;
    return true;
  }
};

// src/tools/stroke.js
var Stroke = class {
  constructor(p, minStep = 1) {
    this.points = [p];
    this.minStep = minStep;
  }
  add(p) {
    const last = this.points[this.points.length - 1];
    if (Math.hypot(p[0] - last[0], p[1] - last[1]) >= this.minStep) this.points.push(p);
  }
  draw(ctx, { color = "#1a73e8", width = 2, closeHint = false } = {}) {
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.lineCap = ctx.lineJoin = "round";
    polyline(ctx, this.points);
    ctx.stroke();
    if (closeHint && this.points.length > 2) {
      const a = this.points[this.points.length - 1];
      const b = this.points[0];
      ctx.setLineDash([4 * (width / 2), 4 * (width / 2)]);
      polyline(ctx, [a, b]);
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }
};
function strokeTool(view, finish, look) {
  let stroke = null;
  return {
    down(p) {
      stroke = new Stroke(p, view.unit());
    },
    move(p) {
      if (stroke) stroke.add(p);
    },
    up(p) {
      if (!stroke) return;
      stroke.add(p);
      const points = stroke.points;
      stroke = null;
      finish(points);
    },
    cancel() {
      stroke = null;
    },
    preview(ctx, unit) {
      if (stroke) stroke.draw(ctx, look(unit));
    }
  };
}

// src/throttle.js
var timers = {
  now: () => performance.now(),
  later: (fn, ms) => setTimeout(fn, ms),
  clear: (id) => clearTimeout(id)
};
function throttle(fn, ms, clock = timers) {
  let last = -Infinity;
  let held = null;
  let timer = null;
  const fire = () => {
    timer = null;
    last = clock.now();
    const args = held;
    held = null;
    fn(...args);
  };
  const call = (...args) => {
    held = args;
    const wait = last + ms - clock.now();
    if (wait <= 0 && timer === null) fire();
    else if (timer === null) timer = clock.later(fire, wait);
  };
  call.cancel = () => {
    if (timer !== null) clock.clear(timer);
    timer = held = null;
  };
  return call;
}

// src/tools/select.js
var DRAG_MS = 100;
var additive = (ev) => !!(ev.shiftKey || ev.ctrlKey || ev.metaKey);
var rp = (p) => [round2(p[0]), round2(p[1])];
function select(view) {
  let grab = null;
  let lasso = null;
  let drag = null;
  const live = throttle((d, p) => send("drag", d, p), DRAG_MS);
  const liveForce = throttle((g, p) => sendForce(g, p, false), DRAG_MS);
  function find(p, design, li) {
    const layer = design.layers[li];
    if (!layer) return null;
    const r = 8 * view.unit();
    const e = layer.emitter;
    if (e && e.kind === "curve" && Array.isArray(e.points)) {
      const j = nearest(e.points, p, r);
      if (j >= 0) return { kind: "emitter", index: j };
    }
    const forces = layer.forces || [];
    for (let k = forces.length - 1; k >= 0; k--) {
      const f = forces[k];
      if (f.kind === "point" && dist([f.x, f.y], p) <= r) return { kind: "force", index: k };
      if (f.kind === "direction" && dist(directionArrow(layer, design.canvas, f.angle).to, p) <= 1.5 * r) {
        return { kind: "force", index: k, direction: true };
      }
    }
    if (view.hit(p) >= 0) return { kind: "mark", index: view.hit(p) };
    const c = layer.container;
    if (c && c.kind !== "canvas" && (nearOutline(c, p, design.canvas, 6 * view.unit()) || !view.hasFrame() && insideContainer(c, p, design.canvas, view.hitContext()))) {
      return { kind: "container", index: 0 };
    }
    return null;
  }
  function nearOutline(c, p, canvas, tol) {
    const pts = containerOutline(c, canvas);
    if (pts) return distToPolyline(p, pts, true) <= tol;
    const ctx = view.hitContext();
    const path = containerPath(c, canvas);
    if (!path || !ctx) return false;
    ctx.save();
    ctx.lineWidth = 2 * tol;
    const hit = ctx.isPointInStroke(path, p[0], p[1]);
    ctx.restore();
    return hit;
  }
  function dragged(p) {
    const { kind, index, start, design } = grab;
    const li = view.layer();
    if (kind === "container") {
      const [dx, dy] = [round2(p[0] - start[0]), round2(p[1] - start[1])];
      return updateLayer(design, li, (l) => void (l.container = translateContainer(l.container, dx, dy, design.canvas)));
    }
    if (kind === "emitter") {
      return updateLayer(design, li, (l) => {
        const pts = l.emitter.points;
        const d = [p[0] - pts[index][0], p[1] - pts[index][1]];
        const moved2 = index % 3 === 0 ? [index - 1, index, index + 1] : [index];
        for (const j of moved2) if (pts[j]) pts[j] = rp([pts[j][0] + d[0], pts[j][1] + d[1]]);
      });
    }
    return updateLayer(design, li, (l) => {
      const f = l.forces[index];
      if (f.kind === "point") Object.assign(f, { x: round2(p[0]), y: round2(p[1]) });
      else f.angle = angleDeg(directionArrow(l, design.canvas, f.angle).from, p);
    });
  }
  return {
    down(p, ev) {
      const design = view.design();
      const found = find(p, design, view.layer());
      if (found && found.kind === "mark") {
        view.pick(null);
        const sel = view.selected();
        const indices = ev.shiftKey && sel.has(found.index) ? [...sel] : [found.index];
        const frame = view.frame();
        const from = indices.filter((i) => frame && 4 * i + 1 < frame.length).map((i) => [i, frame[4 * i], frame[4 * i + 1]]);
        drag = { index: found.index, indices, from, start: p, at: p, moved: false, additive: additive(ev) };
        return;
      }
      if (found) {
        view.pick({ kind: found.kind, index: found.index });
        grab = { ...found, start: p, design: clone(design), moved: false, layer: view.layer() };
        const force = found.kind === "force" && !found.direction && design.layers[grab.layer].forces[found.index];
        grab.live = !!force && view.hasFrame() && view.model.get("status") !== "running";
        if (grab.live) grab.from = [force.x, force.y];
        return;
      }
      view.pick(null);
      lasso = new Stroke(p, view.unit());
      lasso.shift = additive(ev);
    },
    move(p) {
      if (drag) {
        if (!drag.moved && (dist(p, drag.start) < 2 * view.unit() || view.model.get("status") === "running")) return;
        drag.moved = true;
        drag.at = p;
        live(drag, p);
      } else if (grab) {
        if (!grab.moved && dist(p, grab.start) < 2 * view.unit()) return;
        grab.moved = true;
        view.setDraft(dragged(p));
        if (grab.live) liveForce(grab, p);
      } else if (lasso) lasso.add(p);
    },
    up(p) {
      if (drag) {
        live.cancel();
        if (drag.moved) send("pin", drag, p);
        else view.toggleSelect([drag.index], drag.additive);
        drag = null;
      } else if (grab) {
        liveForce.cancel();
        if (grab.moved) view.commit(dragged(p), grab.design);
        view.setDraft(null);
        if (grab.moved && grab.live) sendForce(grab, p, true);
        grab = null;
      } else if (lasso) {
        lasso.add(p);
        const closed = closeStroke(lasso.points, { snap: 0, minArea: 4 });
        view.toggleSelect(closed ? view.marksInPolygon(closed.points) : [], lasso.shift);
        lasso = null;
      }
    },
    cancel() {
      live.cancel();
      liveForce.cancel();
      if (grab && grab.moved && grab.live) sendForce(grab, grab.from, true);
      if (grab) view.setDraft(null);
      grab = lasso = drag = null;
    },
    /** Delete or Backspace: removes the picked container, force or emitter. */
    deletePicked(picked) {
      if (!picked) return false;
      const design = view.design();
      const li = view.layer();
      if (picked.kind === "container") view.commit(setContainer(design, li, null));
      else if (picked.kind === "force") view.commit(removeForce(design, li, picked.index));
      else if (picked.kind === "emitter") view.commit(setEmitter(design, li, null));
      else return false;
      view.pick(null);
      return true;
    },
    preview(ctx, unit) {
      if (drag && drag.moved) return void moved(drag).forEach(([i, x, y]) => ghost(ctx, i, x, y, unit));
      if (!lasso) return;
      lasso.draw(ctx, { color: "rgba(26, 115, 232, 0.9)", width: 1.5 * unit, closeHint: true });
    }
  };
  function moved(d, at = d.at) {
    const [dx, dy] = [at[0] - d.start[0], at[1] - d.start[1]];
    return d.from.map(([i, x, y]) => [i, round2(x + dx), round2(y + dy)]);
  }
  function send(type, d, p) {
    const marks = moved(d, p);
    if (marks.length) view.send({ type, units: marks.map((m) => m[0]), x: marks.map((m) => m[1]), y: marks.map((m) => m[2]) });
  }
  function sendForce(g, p, final) {
    view.send({ type: "force", layer: g.layer, index: g.index, x: round2(p[0]), y: round2(p[1]), final });
  }
  function ghost(ctx, i, x, y, unit) {
    const units = view.units();
    const frame = view.frame();
    if (!units || 4 * i + 3 >= units.length) return;
    const s = frame[4 * i + 3];
    const [w, h2] = [units[4 * i + 2] * s, units[4 * i + 3] * s];
    ctx.save();
    ctx.translate(x, y);
    ctx.rotate(frame[4 * i + 2] * Math.PI / 180);
    ctx.setLineDash([4 * unit, 3 * unit]);
    ctx.strokeStyle = "rgba(26, 115, 232, 0.9)";
    ctx.lineWidth = 1.5 * unit;
    ctx.strokeRect(-w / 2, -h2 / 2, w, h2);
    ctx.restore();
    drawPin(ctx, x, y, unit);
  }
}
function nearest(points, p, r) {
  let best = -1;
  let bestD = r;
  points.forEach((q, j) => {
    const d = dist(q, p);
    if (d <= bestD) [best, bestD] = [j, d];
  });
  return best;
}

// src/tools/container-freehand.js
function containerFreehand(view) {
  return strokeTool(
    view,
    (stroke) => {
      const pts = simplify(stroke, 0.75 * view.unit());
      const closed = closeStroke(pts, { snap: 16 * view.unit() });
      if (closed) view.commit(setContainer(view.design(), view.layer(), { kind: "polygon", points: closed.points, cuts: [] }));
    },
    (unit) => ({ width: 2 * unit, closeHint: true })
  );
}

// src/tools/container-shape.js
function containerShape(view, kind) {
  let start = null;
  let end = null;
  const toContainer = () => {
    const b = boxFromCorners(start, end);
    if (kind === "rect") return { kind: "rect", x: round2(b.x), y: round2(b.y), w: round2(b.w), h: round2(b.h), cuts: [] };
    return {
      kind: "ellipse",
      cx: round2(b.x + b.w / 2),
      cy: round2(b.y + b.h / 2),
      rx: round2(b.w / 2),
      ry: round2(b.h / 2),
      cuts: []
    };
  };
  return {
    down(p) {
      start = end = p;
    },
    move(p) {
      if (start) end = p;
    },
    up(p) {
      if (!start) return;
      end = p;
      const b = boxFromCorners(start, end);
      const big = b.w >= 4 * view.unit() && b.h >= 4 * view.unit();
      if (big) view.commit(setContainer(view.design(), view.layer(), toContainer()));
      start = end = null;
    },
    cancel() {
      start = end = null;
    },
    preview(ctx, unit) {
      if (!start) return;
      const c = toContainer();
      ctx.strokeStyle = "#1a73e8";
      ctx.lineWidth = 2 * unit;
      ctx.setLineDash([6 * unit, 4 * unit]);
      ctx.beginPath();
      if (kind === "rect") ctx.rect(c.x, c.y, c.w, c.h);
      else ctx.ellipse(c.cx, c.cy, c.rx, c.ry, 0, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.setLineDash([]);
    }
  };
}

// src/tools/erase.js
function erase(view) {
  return strokeTool(
    view,
    (stroke) => {
      let pts = simplify(stroke, 0.5 * view.unit()).map((q) => [round2(q[0]), round2(q[1])]);
      if (pts.length === 1) pts = [pts[0], pts[0]];
      view.commit(addCut(view.design(), view.layer(), { points: pts, width: view.eraserWidth() }));
    },
    () => ({ color: "rgba(220, 60, 60, 0.45)", width: view.eraserWidth() })
  );
}

// src/tools/emitter-grid.js
function emitterGrid(view) {
  return {
    up(p) {
      const design = view.design();
      const layer = design.layers[view.layer()];
      if (!layer || !insideContainer(layer.container, p, design.canvas, view.hitContext())) return;
      const old = layer.emitter || {};
      const emitter = { kind: "grid", speed: old.speed ?? 1, direction: old.kind === "grid" ? old.direction ?? null : null };
      view.commit(setEmitter(design, view.layer(), emitter));
    }
  };
}

// src/tools/emitter-curve.js
var FIT_TOLERANCE = 4;
function emitterCurve(view) {
  return strokeTool(
    view,
    (pts) => {
      if (pathLength(pts) < 8 * view.unit()) return;
      const points = fitCurve(pts, FIT_TOLERANCE * view.unit());
      if (points.length < 4) return;
      const design = view.design();
      const old = design.layers[view.layer()]?.emitter;
      const keep = old && old.kind === "curve" ? old : { speed: 1, direction: "along", mode: "free" };
      const emitter = { kind: "curve", points, speed: keep.speed ?? 1, direction: keep.direction ?? "along", mode: keep.mode ?? "free" };
      view.commit(setEmitter(design, view.layer(), emitter));
    },
    (unit) => ({ color: "#f28e2b", width: 3 * unit })
  );
}

// src/tools/forces.js
function forcePoint(view) {
  return {
    up(p) {
      view.commit(addPointForce(view.design(), view.layer(), round2(p[0]), round2(p[1])));
    }
  };
}
function forceDirection(view) {
  let from = null;
  let to = null;
  return {
    down(p) {
      from = to = p;
    },
    move(p) {
      if (from) to = p;
    },
    up(p) {
      if (!from) return;
      to = p;
      if (dist(from, to) >= 8 * view.unit()) view.commit(setDirectionForce(view.design(), view.layer(), angleDeg(from, to)));
      from = to = null;
    },
    cancel() {
      from = to = null;
    },
    preview(ctx, unit) {
      if (from && dist(from, to) > 0) drawArrow(ctx, from, to, "#1a73e8", false, unit);
    }
  };
}

// src/tools/index.js
var TOOLS = [
  { name: "select", label: "Select", icon: "↖", make: select },
  { name: "container-freehand", label: "Container: freehand lasso", icon: "✎", make: containerFreehand },
  { name: "container-rect", label: "Container: rectangle", icon: "▭", make: (v) => containerShape(v, "rect") },
  { name: "container-ellipse", label: "Container: ellipse", icon: "◯", make: (v) => containerShape(v, "ellipse") },
  { name: "erase", label: "Eraser: cut a hole in the container", icon: "⌫", make: erase },
  { name: "emitter-grid", label: "Emitter: grid (click in the container)", icon: "▦", make: emitterGrid },
  { name: "emitter-curve", label: "Emitter: curve (draw a stroke)", icon: "∿", make: emitterCurve },
  { name: "force-point", label: "Force: point (click)", icon: "◉", make: forcePoint },
  { name: "force-direction", label: "Force: direction (drag an arrow)", icon: "→", make: forceDirection }
];
function makeTools(view) {
  return Object.fromEntries(TOOLS.map((t) => [t.name, t.make(view)]));
}

// src/pointer.js
function attachInput(view, tools, signal) {
  const { stage, root } = view;
  let active = null;
  const tool = () => tools[view.session.tool] || tools.select;
  listen(stage.el, "pointerdown", (ev) => {
    if (ev.button !== 0 || active) return;
    ev.preventDefault();
    root.focus({ preventScroll: true });
    stage.el.setPointerCapture(ev.pointerId);
    stage.hideTooltip();
    active = tool();
    if (active.down) active.down(stage.toCanvas(ev), ev);
    view.redraw("over");
  }, signal);
  listen(stage.el, "pointermove", (ev) => {
    const p = stage.toCanvas(ev);
    if (active) {
      if (active.move) active.move(p, ev);
      view.redraw("over");
      return;
    }
    hover(p);
  }, signal);
  const finish = (ev, cancelled) => {
    if (!active) return;
    const t = active;
    active = null;
    if (cancelled) t.cancel && t.cancel();
    else if (t.up) t.up(stage.toCanvas(ev), ev);
    view.redraw("over");
  };
  listen(stage.el, "pointerup", (ev) => finish(ev, false), signal);
  listen(stage.el, "pointercancel", (ev) => finish(ev, true), signal);
  listen(stage.el, "pointerleave", () => !active && stage.hideTooltip(), signal);
  listen(stage.el, "contextmenu", (ev) => active && ev.preventDefault(), signal);
  function hover(p) {
    if (view.session.tool !== "select") return stage.hideTooltip();
    const i = view.hit(p);
    const titles = view.model.get("titles");
    const text = i >= 0 && Array.isArray(titles) && titles[i] != null ? String(titles[i]) : "";
    stage.el.style.cursor = i >= 0 ? "pointer" : "";
    if (text) stage.showTooltip(text, p);
    else stage.hideTooltip();
  }
  listen(root, "keydown", (ev) => {
    const typing = /^(INPUT|TEXTAREA|SELECT)$/.test(ev.target.tagName) || ev.target.isContentEditable;
    const mod = ev.ctrlKey || ev.metaKey;
    const key = ev.key.toLowerCase();
    if (mod && key === "z" && !typing) {
      ev.preventDefault();
      ev.shiftKey ? view.redo() : view.undo();
    } else if (mod && key === "y" && !typing) {
      ev.preventDefault();
      view.redo();
    } else if ((ev.key === "Delete" || ev.key === "Backspace") && !typing) {
      if (tools.select.deletePicked(view.session.picked)) ev.preventDefault();
    } else if (ev.key === "Escape" && active) {
      active.cancel && active.cancel();
      active = null;
      view.redraw("over");
    } else return;
    ev.stopPropagation();
  }, signal);
}

// src/toolbar.js
function createToolbar(view) {
  const { model } = view;
  const toolButtons = TOOLS.map(
    (t) => h("button", {
      type: "button",
      class: "ut-btn ut-tool",
      dataset: { tool: t.name },
      title: t.label,
      "aria-label": t.label,
      onclick: () => view.setTool(t.name)
    }, t.icon)
  );
  const action = (name, label, text, fn, extra = "") => h("button", { type: "button", class: `ut-btn ${extra}`, dataset: { action: name }, title: label, "aria-label": label, onclick: fn }, text);
  const buttons = {
    undo: action("undo", "Undo (Ctrl+Z)", "↶", () => view.undo()),
    redo: action("redo", "Redo (Ctrl+Shift+Z)", "↷", () => view.redo()),
    run: action("run", "Run the layout", "▶ Run", () => view.run(), "ut-run"),
    stop: action("stop", "Stop the layout", "■ Stop", () => view.send({ type: "stop" })),
    svg: action("export-svg", "Export SVG", "SVG ⤓", () => view.send({ type: "export", format: "svg" })),
    png: action("export-png", "Export PNG", "PNG ⤓", () => view.send({ type: "export", format: "png" })),
    code: action("copy-code", "Copy as Python (w.to_code())", "</> Python", () => view.send({ type: "code" }))
  };
  const eraser = h("input", { type: "range", min: "2", max: "80", value: "16", class: "ut-eraser", title: "Eraser width (canvas px)", "aria-label": "Eraser width" });
  const el = h(
    "div",
    { class: "ut-toolbar", role: "toolbar" },
    h("div", { class: "ut-group" }, toolButtons),
    h("label", { class: "ut-eraser-label", title: "Eraser width" }, "⌫", eraser),
    h("div", { class: "ut-group" }, buttons.undo, buttons.redo),
    h("div", { class: "ut-group" }, buttons.run, buttons.stop),
    h("div", { class: "ut-group" }, buttons.svg, buttons.png, buttons.code)
  );
  function update() {
    const s = view.session;
    for (const b of toolButtons) b.setAttribute("aria-pressed", String(b.dataset.tool === s.tool));
    buttons.undo.setAttribute("aria-disabled", String(!s.history.canUndo));
    buttons.redo.setAttribute("aria-disabled", String(!s.history.canRedo));
    const running = model.get("status") === "running" && view.kernel() !== "gone";
    buttons.stop.disabled = !running;
    buttons.run.classList.toggle("ut-busy", running);
  }
  return { el, update, eraserWidth: () => Number(eraser.value) || 16 };
}

// src/status-text.js
function statusLabel(status, stale, kernel = "live") {
  const s = ["idle", "running", "done", "stopped", "error"].includes(status) ? status : "idle";
  if (kernel === "gone") return { text: "no kernel", state: "gone" };
  if (kernel === "waiting" && s !== "running") return { text: "waiting for the kernel", state: "waiting" };
  if (stale && s !== "running" && s !== "error") return { text: "changed: run again", state: "stale" };
  return { text: s, state: s };
}
var PHASES = { settle: "settling", polish: "polishing" };
function progressBar(p) {
  const it = Number(p && p.iteration) || 0;
  const max = Number(p && p.max_iterations) || 0;
  const done = !!(p && p.done);
  const seconds = Number(p && p.seconds);
  const parts = [];
  if (done && Number.isFinite(seconds)) {
    parts.push(`${p.stopped ? "stopped after" : "done in"} ${seconds.toFixed(1)} s`);
  } else if (!done && p && PHASES[p.phase]) {
    parts.push(PHASES[p.phase]);
  }
  if (max) parts.push(`iteration ${it} / ${max}`);
  return { max: max || 1, value: done ? max || 1 : Math.min(it, max || 1), hidden: !max, detail: parts.join(" · ") };
}

// src/panels/status.js
var NO_ANSWER_MS = 2e3;
var WAITING = "Waiting for the kernel: it is busy (Run starts when it is free), or no kernel runs this notebook's cells yet.";
var NO_KERNEL = "No kernel is connected to this view (it was restarted, shut down, or never started): run the notebook's cells again to get a live widget.";
function createStatus(model, signal, onKernel = () => {
}) {
  const word = h("span", { class: "ut-status-word" });
  const bar = h("progress", { class: "ut-progress", max: 1, value: 0 });
  const detail = h("span", { class: "ut-progress-text" });
  const el = h("div", { class: "ut-status", "aria-live": "polite" }, word, bar, detail);
  const text = h("span", { class: "ut-error-text", role: "alert" });
  const dismiss = h("button", {
    type: "button",
    class: "ut-btn ut-icon",
    dataset: { action: "dismiss-error" },
    title: "Dismiss this error",
    "aria-label": "Dismiss this error",
    onclick: () => {
      dismissed = String(model.get("error") || "");
      banner.hidden = true;
      send({ type: "dismiss-error" });
    }
  }, "✕");
  const banner = h("div", { class: "ut-error", hidden: true }, text, dismiss);
  const notice = h("div", { class: "ut-notice", dataset: { role: "notice" }, role: "status", hidden: true });
  let dismissed = null;
  let timer = 0;
  let kernel = "live";
  signal.addEventListener("abort", () => clearTimeout(timer), { once: true });
  function send(msg) {
    if (kernel === "gone") return gone(), false;
    try {
      model.send(msg);
      return true;
    } catch {
      gone();
      return false;
    }
  }
  function run() {
    clearTimeout(timer);
    notice.hidden = true;
    if (!send({ type: "run" })) return;
    timer = setTimeout(() => {
      kernel = "waiting";
      notify(WAITING);
      onKernel();
    }, NO_ANSWER_MS);
  }
  function gone() {
    clearTimeout(timer);
    kernel = "gone";
    notify(NO_KERNEL);
    onKernel();
  }
  const probe = () => kernel !== "gone" && send({ type: "ping" });
  const closed = () => gone();
  for (const [event, fn] of [["comm_live_update", probe], ["comm:close", closed], ["destroy", closed]]) {
    model.on(event, fn);
    signal.addEventListener("abort", () => model.off(event, fn), { once: true });
  }
  function notify(message) {
    notice.textContent = message;
    notice.hidden = false;
  }
  function answered() {
    clearTimeout(timer);
    notice.hidden = true;
    kernel = "live";
  }
  function update() {
    const label = statusLabel(String(model.get("status") || "idle"), !!model.get("stale"), kernel);
    word.textContent = label.text;
    word.dataset.state = label.state;
    const p = progressBar(model.get("progress") || {});
    bar.max = p.max;
    bar.value = p.value;
    bar.hidden = p.hidden;
    detail.textContent = p.detail;
    const error = String(model.get("error") || "");
    if (error !== dismissed) dismissed = null;
    text.textContent = error;
    banner.hidden = !error || error === dismissed;
  }
  return { el, banner, notice, update, run, answered, notify, send, kernel: () => kernel };
}

// src/panels/layers.js
function createLayersPanel(view) {
  const list2 = h("ol", { class: "ut-layer-list" });
  const add2 = h("button", {
    type: "button",
    class: "ut-btn ut-small",
    dataset: { action: "add-layer" },
    title: "Add a layer",
    "aria-label": "Add a layer",
    onclick: () => {
      const next = addLayer(view.design());
      view.commit(next);
      view.setLayer(next.layers.length - 1);
    }
  }, "+ layer");
  const el = h("section", { class: "ut-panel ut-layers" }, h("header", {}, h("h3", { text: "Layers" }), add2), list2);
  function rowFor(layer, i, current, n) {
    const name = h("input", {
      class: "ut-layer-name",
      value: String(layer.name),
      "aria-label": "Layer name",
      spellcheck: false,
      onfocus: () => view.setLayer(i),
      onchange: (ev) => {
        const v = ev.target.value.trim();
        if (v && v !== layer.name) view.commit(renameLayer(view.design(), i, v));
        else ev.target.value = layer.name;
      },
      onkeydown: (ev) => ev.key === "Enter" && ev.target.blur()
    });
    const btn = (act, label, text, fn, disabled = false) => h("button", { type: "button", class: "ut-btn ut-icon", dataset: { layerAction: act }, title: label, "aria-label": label, disabled, onclick: (ev) => (ev.stopPropagation(), fn()) }, text);
    return h(
      "li",
      { class: `ut-layer${i === current ? " ut-current" : ""}`, dataset: { layer: String(i) }, onclick: () => view.setLayer(i) },
      h("span", { class: "ut-swatch", style: { background: layerColor(i) } }),
      name,
      btn("up", "Move up (drawn earlier)", "↑", () => move(i, -1), i === 0),
      btn("down", "Move down (drawn later)", "↓", () => move(i, 1), i === n - 1),
      btn("duplicate", "Duplicate", "⊞", () => {
        view.commit(duplicateLayer(view.design(), i));
        view.setLayer(i + 1);
      }),
      btn("delete", "Delete", "✕", () => {
        view.commit(deleteLayer(view.design(), i));
        view.setLayer(Math.max(0, Math.min(i, n - 2)));
      }, n <= 1)
    );
  }
  function move(i, delta) {
    view.commit(moveLayer(view.design(), i, delta));
    view.setLayer(i + delta);
  }
  let shown = null;
  function update() {
    const design = view.design();
    const current = view.layer();
    const key = JSON.stringify(design.layers.map((l) => l.name));
    if (key !== shown) {
      shown = key;
      replaceChildren(list2, design.layers.map((l, i) => rowFor(l, i, current, design.layers.length)));
    }
    [...list2.children].forEach((li, i) => li.classList.toggle("ut-current", i === current));
  }
  return { el, update };
}

// src/panels/settings.js
var num = (v) => v === "" || v == null || !Number.isFinite(Number(v)) ? null : Number(v);
function createSettingsPanel(view) {
  const body = h("div", { class: "ut-settings-body" });
  const title = h("h3", { text: "Layer settings" });
  const el = h("section", { class: "ut-panel ut-settings" }, h("header", {}, title), body);
  const set = (props) => view.commit(setLayerProps(view.design(), view.layer(), props));
  function select2(setting, options, value, onchange) {
    const s = h(
      "select",
      { dataset: { setting }, onchange: (ev) => onchange(ev.target.value) },
      options.map(([v, label]) => h("option", { value: v, text: label }))
    );
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
    const orientKind = typeof orient === "number" ? "angle" : Array.isArray(orient) ? "random" : orient || "none";
    const [lo, hi] = Array.isArray(orient) ? orient.slice(1) : [-180, 180];
    const range = (from, to) => set({ orientation: from === -180 && to === 180 ? "random" : ["random", from, to] });
    const margin = layer.encodings?.margin;
    const rows = [
      row("boundary", select2("boundary", [["closed", "closed (fill)"], ["open", "open (bound only)"]], layer.boundary || "closed", (v) => set({ boundary: v }))),
      row("fill", input("fill", { type: "number", min: "0.05", max: "1", step: "0.05", value: layer.fill ?? "", placeholder: "auto" }, (t) => set({ fill: num(t.value) }))),
      row("orientation", select2("orientation", [["none", "none"], ["to_center", "to centre"], ["along_emitter", "along emitter"], ["angle", "angle…"], ["random", "random angles…"]], orientKind, (v) => set({ orientation: v === "none" ? null : v === "angle" ? 0 : v }))),
      orientKind === "angle" && row("angle", input("angle", { type: "number", step: "5", value: orient }, (t) => set({ orientation: num(t.value) ?? 0 }))),
      orientKind === "random" && row("angles from", input("random_lo", { type: "number", step: "5", value: lo }, (t) => range(num(t.value) ?? -180, hi))),
      orientKind === "random" && row("angles to", input("random_hi", { type: "number", step: "5", value: hi }, (t) => range(lo, num(t.value) ?? 180))),
      row("arrange", select2("arrange", [["free", "free (packed)"], ["grid", "grid (rows and columns)"]], layer.arrange || "free", (v) => set({ arrange: v }))),
      ...["x", "y"].map((c) => layer.encodings?.[c] != null && row(
        `${c} scale`,
        select2(`${c}_scale`, [["linear", "linear"], ["log", "log"]], layer[`${c}_scale`] || "linear", (v) => set({ [`${c}_scale`]: v }))
      )),
      row("rotate", input("rotate", { type: "checkbox", checked: !!layer.rotate }, (t) => set({ rotate: t.checked }))),
      row("margin", input(
        "margin",
        { type: "number", min: "0", step: "0.01", value: typeof margin === "number" ? margin : "", placeholder: typeof margin === "string" ? `field ${margin}` : "0" },
        (t) => view.commit(setEncoding(view.design(), i, "margin", num(t.value) ?? 0))
      )),
      row("iterations", input("iterations", { type: "number", min: "1", step: "50", value: layer.iterations ?? 600 }, (t) => set({ iterations: Math.max(1, Math.round(num(t.value) ?? 600)) }))),
      tallyRows(layer),
      blocksRow(design, i, layer),
      emitterRows(layer, i)
    ];
    replaceChildren(body, rows);
  }
  function tallyRows(layer) {
    const numeric = (view.model.get("fields") || []).filter((f) => f.type === "numeric").map((f) => String(f.name));
    const counts = [["", "1 per row"], ...numeric.map((n) => [n, n])];
    if (layer.count != null && !numeric.includes(String(layer.count))) counts.push([String(layer.count), String(layer.count)]);
    const per = layer.per ?? null;
    return h(
      "fieldset",
      { class: "ut-tally" },
      h("legend", { text: "one mark for k units" }),
      row("count", select2("count", counts, layer.count ?? "", (v) => set({ count: v === "" ? null : v }))),
      row("per", input("per", { type: "number", min: "0", step: "any", value: per ?? "", placeholder: "1 unit" }, (t) => {
        const k = num(t.value);
        set({ per: k != null && k > 0 ? k : null });
      })),
      per != null && row("rounding", select2("rounding", [["largest-remainder", "largest remainder"], ["floor", "floor"], ["ceil", "ceil"], ["nearest", "nearest"]], layer.rounding || "largest-remainder", (v) => set({ rounding: v }))),
      per != null && row("partial", input("partial", { type: "checkbox", checked: !!layer.partial }, (t) => set({ partial: t.checked })))
    );
  }
  function blocksRow(design, i, layer) {
    const others = design.layers.filter((_, k) => k !== i);
    if (!others.length) return null;
    const boxes = others.map((o) => h(
      "label",
      { class: "ut-check" },
      h("input", {
        type: "checkbox",
        dataset: { block: String(o.name) },
        checked: (layer.blocks || []).includes(o.name),
        onchange: (ev) => {
          const blocks = new Set(layer.blocks || []);
          ev.target.checked ? blocks.add(o.name) : blocks.delete(o.name);
          set({ blocks: design.layers.map((l) => l.name).filter((n) => blocks.has(n)) });
        }
      }),
      String(o.name)
    ));
    return h("fieldset", { class: "ut-blocks" }, h("legend", { text: "blocks (obstacles)" }), boxes);
  }
  function emitterRows(layer, i) {
    const e = layer.emitter;
    if (!e) return null;
    const setE = (props) => view.commit(updateLayer(view.design(), i, (l) => void Object.assign(l.emitter, props)));
    return h(
      "fieldset",
      { class: "ut-emitter" },
      h("legend", { text: `${e.kind} emitter` }),
      row("speed", input("emitter-speed", { type: "number", min: "0", step: "0.1", value: e.speed ?? 1 }, (t) => setE({ speed: num(t.value) ?? 1 }))),
      e.kind === "curve" && row("direction", select2("emitter-direction", [["along", "along"], ["normal", "normal"]], typeof e.direction === "string" ? e.direction : "along", (v) => setE({ direction: v }))),
      e.kind === "curve" && row("mode", select2("emitter-mode", [["free", "free"], ["line", "line (1D)"], ["band", "band (2D)"]], e.mode || "free", (v) => setE({ mode: v })))
    );
  }
  return { el, update };
}

// src/panels/fields.js
var MIME = "application/x-unitopia-field";
function createFieldsPanel(view) {
  const { model } = view;
  let picked = null;
  const fieldList = h("div", { class: "ut-field-list" });
  const channels = h("div", { class: "ut-channels" });
  const el = h(
    "section",
    { class: "ut-panel ut-fields" },
    h("header", {}, h("h3", { text: "Data fields" })),
    fieldList,
    h("p", { class: "ut-hint", text: "Drag a field onto a channel, or click a field, then a channel." }),
    channels
  );
  const names = () => new Set(list(model, "fields").map((f) => String(f.name)));
  const bind = (channel, value) => view.commit(setEncoding(view.design(), view.layer(), channel, value));
  function chip(f) {
    const name = String(f.name);
    return h("span", {
      class: `ut-field${picked === name ? " ut-picked" : ""}`,
      role: "button",
      tabindex: "0",
      draggable: "true",
      dataset: { field: name, type: String(f.type || "") },
      title: `${name} (${f.type})`,
      ondragstart: (ev) => {
        ev.dataTransfer.setData(MIME, name);
        ev.dataTransfer.setData("text/plain", name);
        ev.dataTransfer.effectAllowed = "copy";
      },
      onclick: () => {
        picked = picked === name ? null : name;
        update();
      },
      onkeydown: (ev) => (ev.key === "Enter" || ev.key === " ") && (ev.preventDefault(), ev.target.click())
    }, h("span", { class: "ut-field-name", text: name }), h("small", { class: "ut-field-type", text: typeLabel(f.type) }));
  }
  function slot(channel, value) {
    const bound = value != null && !(channel === "margin" && typeof value === "number");
    const shown = bound ? String(value) : channel === "margin" ? `${value ?? 0}` : "—";
    const el2 = h(
      "div",
      {
        class: `ut-channel${bound ? " ut-bound" : ""}${picked ? " ut-target" : ""}`,
        dataset: { channel },
        tabindex: "0",
        ondragover: (ev) => {
          ev.preventDefault();
          ev.dataTransfer.dropEffect = "copy";
          el2.classList.add("ut-over");
        },
        ondragleave: () => el2.classList.remove("ut-over"),
        ondrop: (ev) => {
          ev.preventDefault();
          el2.classList.remove("ut-over");
          const name = ev.dataTransfer.getData(MIME) || ev.dataTransfer.getData("text/plain");
          if (names().has(name)) bind(channel, name);
        },
        onclick: () => {
          if (!picked) return;
          const name = picked;
          picked = null;
          bind(channel, name);
        }
      },
      h("span", { class: "ut-channel-name", text: channel }),
      h("span", { class: "ut-channel-value", text: shown }),
      bound && h("button", {
        type: "button",
        class: "ut-btn ut-icon",
        dataset: { clear: channel },
        title: `Clear ${channel}`,
        "aria-label": `Clear ${channel}`,
        onclick: (ev) => (ev.stopPropagation(), bind(channel, null))
      }, "✕"),
      channel === "color" && colorInput(value)
    );
    return el2;
  }
  function colorInput(value) {
    const literal = typeof value === "string" && /^#[0-9a-f]{6}$/i.test(value) ? value : "#4e79a7";
    return h("input", {
      type: "color",
      value: literal,
      title: "A fixed colour",
      "aria-label": "A fixed colour",
      onclick: (ev) => ev.stopPropagation(),
      onchange: (ev) => bind("color", ev.target.value)
    });
  }
  function update() {
    const fields = list(model, "fields");
    if (picked && !fields.some((f) => String(f.name) === picked)) picked = null;
    replaceChildren(fieldList, fields.length ? fields.map(chip) : h("p", { class: "ut-hint", text: "No data bound." }));
    const layer = view.design().layers[view.layer()];
    const enc = layer && layer.encodings || {};
    replaceChildren(channels, layer ? CHANNELS.map((c) => slot(c, enc[c])) : []);
  }
  return { el, update };
}
var typeLabel = (t) => ({ numeric: "123", categorical: "abc", datetime: "date" })[t] || String(t || "");

// src/mark-set.js
function withMarks(design, i, fn) {
  return updateLayer(design, i, (l) => {
    const marks = layerMarks(l);
    const keys = Array.isArray(l.mark_keys) && l.mark_keys.length === marks.length ? l.mark_keys.slice() : null;
    const out = fn(marks, keys);
    delete l.mark;
    l.marks = out.marks;
    l.mark_keys = out.keys;
  });
}
var addMark = (design, i, mark) => withMarks(design, i, (marks) => ({ marks: [...marks, mark], keys: null }));
var removeMark = (design, i, k) => withMarks(design, i, (marks, keys) => {
  if (marks.length <= 1 || k < 0 || k >= marks.length) return { marks, keys };
  return { marks: marks.filter((_, j) => j !== k), keys: keys && keys.filter((_, j) => j !== k) };
});
var moveMark = (design, i, k, delta) => withMarks(design, i, (marks, keys) => {
  const j = k + delta;
  if (k < 0 || k >= marks.length || j < 0 || j >= marks.length) return { marks, keys };
  const move = (list2) => {
    const [item] = list2.splice(k, 1);
    list2.splice(j, 0, item);
    return list2;
  };
  return { marks: move(marks), keys: keys && move(keys) };
});
function describeMark(mark) {
  if (!mark || typeof mark !== "object") return "default";
  if (mark.kind === "shape" || mark.kind === "icon") return String(mark.name);
  return String(mark.kind);
}

// src/panels/sketch-pad.js
var PAD = 160;
function createSketchPad(onUse) {
  const canvas = h("canvas", { class: "ut-pad", width: PAD * 2, height: PAD * 2, dataset: { role: "sketch-pad" } });
  const width = h("input", { type: "range", min: "1", max: "16", value: "4", "aria-label": "Stroke width", oninput: () => draw() });
  let strokes = [];
  let live = null;
  const toPad = (ev) => {
    const r = canvas.getBoundingClientRect();
    return [(ev.clientX - r.left) * PAD / r.width, (ev.clientY - r.top) * PAD / r.height];
  };
  canvas.addEventListener("pointerdown", (ev) => {
    canvas.setPointerCapture(ev.pointerId);
    live = [toPad(ev)];
    draw();
  });
  canvas.addEventListener("pointermove", (ev) => {
    if (!live) return;
    live.push(toPad(ev));
    draw();
  });
  const end = () => {
    if (live) strokes.push(simplify(live, 0.5).map((p) => [round2(p[0]), round2(p[1])]));
    live = null;
    draw();
  };
  canvas.addEventListener("pointerup", end);
  canvas.addEventListener("pointercancel", end);
  function draw() {
    const ctx = canvas.getContext("2d");
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.setTransform(canvas.width / PAD, 0, 0, canvas.height / PAD, 0, 0);
    ctx.strokeStyle = "#222";
    ctx.lineWidth = Number(width.value);
    ctx.lineCap = ctx.lineJoin = "round";
    for (const s of live ? [...strokes, live] : strokes) {
      ctx.beginPath();
      s.forEach((p, i) => i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]));
      if (s.length === 1) ctx.lineTo(s[0][0] + 0.01, s[0][1]);
      ctx.stroke();
    }
  }
  const button = (text, action, fn) => h("button", { type: "button", class: "ut-btn ut-small", dataset: { padAction: action }, onclick: fn }, text);
  const el = h(
    "div",
    { class: "ut-sketch" },
    canvas,
    h(
      "div",
      { class: "ut-sketch-tools" },
      h("label", { class: "ut-row" }, h("span", { class: "ut-label", text: "width" }), width),
      button("Clear", "clear", () => (strokes = [], draw())),
      button("Undo stroke", "undo", () => (strokes.pop(), draw())),
      button("Use as mark", "use", () => strokes.length && onUse({ kind: "sketch", strokes: strokes.map((s) => s.slice()), width: Number(width.value) }))
    )
  );
  draw();
  return { el };
}

// src/panels/icon-search.js
var DEBOUNCE_MS = 150;
function createIconSearch(model, signal, onPick) {
  const input = h("input", {
    type: "search",
    class: "ut-icon-query",
    dataset: { role: "icon-query" },
    placeholder: "+ icon name… (fa:apple)",
    "aria-label": "Find an icon mark by name",
    spellcheck: false,
    oninput: () => schedule()
  });
  const results = h("div", { class: "ut-icon-results", dataset: { role: "icon-results" }, "aria-live": "polite" });
  let timer = 0;
  function schedule() {
    clearTimeout(timer);
    timer = setTimeout(() => {
      const query = input.value.trim();
      if (!query) return replaceChildren(results);
      model.send({ type: "icons", query });
    }, DEBOUNCE_MS);
  }
  onModel(model, ["msg:custom"], (msg) => {
    if (!msg || msg.type !== "icons" || msg.query !== input.value.trim()) return;
    const names = Array.isArray(msg.names) ? msg.names.map(String) : [];
    replaceChildren(results, names.length ? names.map((name) => h("button", {
      type: "button",
      class: "ut-btn ut-small ut-icon-name",
      dataset: { icon: name },
      title: `Add ${name}`,
      onclick: () => {
        onPick(name);
        input.value = "";
        replaceChildren(results);
      }
    }, name)) : h("span", { class: "ut-hint", text: `No icon matches “${msg.query}”.` }));
  }, signal);
  signal.addEventListener("abort", () => clearTimeout(timer), { once: true });
  return { el: h("div", { class: "ut-icon-search" }, input, results) };
}

// src/panels/mark.js
var SHAPES = ["circle", "square", "triangle", "star"];
function createMarkPanel(view) {
  const { model } = view;
  const title = h("h3", { text: "Marks" });
  const items = h("ol", { class: "ut-mark-list" });
  const edit = (fn) => view.commit(fn(view.design(), view.layer()));
  const add2 = (mark) => edit((d, i) => addMark(d, i, mark));
  const shape = h(
    "select",
    { dataset: { setting: "mark-shape" }, "aria-label": "Add a shape mark", onchange: (ev) => ev.target.value && add2({ kind: "shape", name: ev.target.value }) },
    h("option", { value: "", text: "+ shape…" }),
    SHAPES.map((s) => h("option", { value: s, text: s }))
  );
  const upload = h("input", {
    type: "file",
    accept: ".svg,.png,.jpg,.jpeg,image/svg+xml,image/png,image/jpeg",
    dataset: { role: "mark-upload" },
    "aria-label": "Upload a mark (SVG or PNG)",
    onchange: async (ev) => {
      const file = ev.target.files && ev.target.files[0];
      ev.target.value = "";
      if (file) add2(await markFromFile(file));
    }
  });
  const pad = createSketchPad(add2);
  pad.el.hidden = true;
  const drawBtn = h("button", {
    type: "button",
    class: "ut-btn ut-small",
    dataset: { action: "sketch-mark" },
    "aria-expanded": "false",
    onclick: () => {
      pad.el.hidden = !pad.el.hidden;
      drawBtn.setAttribute("aria-expanded", String(!pad.el.hidden));
    }
  }, "Draw…");
  const icons = createIconSearch(model, view.signal, (name) => add2({ kind: "icon", name }));
  const el = h(
    "section",
    { class: "ut-panel ut-marks" },
    h("header", {}, title),
    items,
    h("div", { class: "ut-mark-tools" }, shape, h("label", { class: "ut-btn ut-small ut-upload" }, "+ upload…", upload), drawBtn),
    icons.el,
    pad.el
  );
  function item(layer, mark, k, n, entries) {
    const entry = entries.find((m) => m && m.layer === layer.name && (Number(m.mark) || 0) === k);
    const key = Array.isArray(layer.mark_keys) && layer.mark_keys.length === n ? layer.mark_keys[k] : void 0;
    const label = key === void 0 ? describeMark(mark) : `${describeMark(mark)} = ${key}`;
    const src = entry && typeof entry.src === "string" && entry.src.startsWith("data:image/") ? entry.src : null;
    const btn = (act, label2, text, fn, disabled) => h("button", { type: "button", class: "ut-btn ut-icon", dataset: { markAction: act }, title: label2, "aria-label": label2, disabled, onclick: fn }, text);
    return h(
      "li",
      { class: "ut-mark", dataset: { mark: String(k), kind: String(mark && mark.kind) } },
      src ? h("img", { src, alt: `mark ${k + 1}`, draggable: false }) : h("span", { class: "ut-mark-empty", text: "?" }),
      h("span", { class: "ut-mark-label", text: label, title: label }),
      btn("up", "Move up", "↑", () => edit((d, i) => moveMark(d, i, k, -1)), k === 0),
      btn("down", "Move down", "↓", () => edit((d, i) => moveMark(d, i, k, 1)), k === n - 1),
      btn("remove", "Remove this mark", "✕", () => edit((d, i) => removeMark(d, i, k)), n <= 1)
    );
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
async function markFromFile(file) {
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

// src/legend-place.js
var SIDES = ["right", "bottom", "left", "top"];
function legendSettings(design) {
  const l = design && design.legend && typeof design.legend === "object" ? design.legend : {};
  const p = l.position;
  const position = SIDES.includes(p) ? p : isPoint(p) ? [Number(p[0]), Number(p[1])] : "right";
  return { visible: l.visible !== false, position };
}
var isPoint = (p) => Array.isArray(p) && p.length === 2 && p.every((v) => Number.isFinite(Number(v)) && v !== null);
function setLegend(design, patch) {
  const next = clone(design);
  next.legend = { ...next.legend && typeof next.legend === "object" ? next.legend : {}, ...legendSettings(design), ...patch };
  return next;
}
function clampCorner([x, y], [w, h2], [W, H]) {
  const keep = (v, lo, hi) => Math.round(10 * Math.max(lo, Math.min(hi, v))) / 10;
  return [keep(x, 0, Math.max(0, W - w)), keep(y, 0, Math.max(0, H - h2))];
}

// src/legend-view.js
function createLegend(view, signal) {
  const { model, stage } = view;
  const img = h("img", { class: "ut-legend", dataset: { role: "legend" }, alt: "legend", draggable: false, hidden: true, title: "Legend: drag to move it" });
  const area = h("div", { class: "ut-canvas-area" }, stage.wrap);
  const toggle = h("button", {
    type: "button",
    class: "ut-btn",
    dataset: { action: "toggle-legend" },
    title: "Show or hide the legend",
    "aria-label": "Show or hide the legend",
    onclick: () => view.commit(setLegend(view.design(), { visible: !legendSettings(view.design()).visible }))
  }, "Legend");
  let drag = null;
  const trait = () => {
    const l = model.get("legend_image");
    return l && typeof l.src === "string" && l.src.startsWith("data:image/") ? l : null;
  };
  const size = (l) => [Number(l.width) > 0 ? Number(l.width) : img.naturalWidth, Number(l.height) > 0 ? Number(l.height) : img.naturalHeight];
  function place() {
    const l = trait();
    const { visible, position } = legendSettings(view.design());
    toggle.setAttribute("aria-pressed", String(visible));
    toggle.setAttribute("aria-disabled", String(visible && !l));
    img.hidden = !l || !visible;
    if (!l) return void img.removeAttribute("src");
    if (img.getAttribute("src") !== l.src) img.src = l.src;
    const [w, hgt] = size(l);
    const corner = drag ? drag.corner : Array.isArray(position) ? clampCorner(position, [w, hgt], stage.size) : null;
    const k = corner ? stage.scale : 1;
    img.style.width = w ? `${w * k}px` : "";
    img.style.height = hgt ? `${hgt * k}px` : "";
    if (corner) {
      if (img.parentNode !== stage.el) stage.el.append(img);
      img.style.left = `${corner[0] * k}px`;
      img.style.top = `${corner[1] * k}px`;
      area.dataset.legendSide = "inside";
    } else {
      if (img.parentNode !== area) area.append(img);
      img.style.left = img.style.top = "";
      area.dataset.legendSide = position;
    }
  }
  function cornerNow() {
    const r = img.getBoundingClientRect();
    const s = stage.el.getBoundingClientRect();
    return [(r.left - s.left - stage.el.clientLeft) / stage.scale, (r.top - s.top - stage.el.clientTop) / stage.scale];
  }
  listen(img, "pointerdown", (ev) => {
    const l = trait();
    if (ev.button !== 0 || !l || drag) return;
    ev.preventDefault();
    ev.stopPropagation();
    const start = cornerNow();
    drag = { pointer: [ev.clientX, ev.clientY], start, size: size(l), corner: null, stop: new AbortController() };
    drag.corner = clampCorner(start, drag.size, stage.size);
    stage.wrap.style.flex = `0 0 ${stage.wrap.clientWidth}px`;
    const opts = { signal: drag.stop.signal };
    window.addEventListener("pointermove", move, opts);
    window.addEventListener("pointerup", () => finish(true), opts);
    window.addEventListener("pointercancel", () => finish(false), opts);
    signal.addEventListener("abort", () => drag && drag.stop.abort(), opts);
    place();
  }, signal);
  function move(ev) {
    const d = [(ev.clientX - drag.pointer[0]) / stage.scale, (ev.clientY - drag.pointer[1]) / stage.scale];
    drag.corner = clampCorner([drag.start[0] + d[0], drag.start[1] + d[1]], drag.size, stage.size);
    place();
  }
  function finish(keep) {
    const { corner, stop } = drag;
    stop.abort();
    drag = null;
    stage.wrap.style.flex = "";
    if (keep) view.commit(setLegend(view.design(), { position: corner }));
    else place();
  }
  listen(img, "load", () => place(), signal);
  return { area, toggle, place };
}

// src/pile-labels.js
var NS = "http://www.w3.org/2000/svg";
var ANCHORS = /* @__PURE__ */ new Set(["start", "middle", "end"]);
function createPileLabels(stage) {
  const svg = document.createElementNS(NS, "svg");
  svg.setAttribute("class", "ut-pile-labels");
  svg.setAttribute("preserveAspectRatio", "none");
  svg.setAttribute("aria-hidden", "true");
  function update(labels, size) {
    const shown = Array.isArray(labels) ? labels : [];
    svg.replaceChildren();
    if (!shown.length) return void svg.remove();
    if (svg.parentNode !== stage.el) stage.el.insertBefore(svg, stage.tooltip);
    svg.setAttribute("viewBox", `0 0 ${Number(size[0]) || 1} ${Number(size[1]) || 1}`);
    for (const l of shown) {
      if (!l || !Number.isFinite(Number(l.x)) || !Number.isFinite(Number(l.y))) continue;
      const text = document.createElementNS(NS, "text");
      text.setAttribute("class", "pile-label");
      text.setAttribute("x", String(Number(l.x)));
      text.setAttribute("y", String(Number(l.y)));
      text.setAttribute("font-size", "12");
      text.setAttribute("font-family", "sans-serif");
      text.setAttribute("fill", "#222");
      text.setAttribute("text-anchor", ANCHORS.has(l.anchor) ? l.anchor : "middle");
      text.textContent = String(l.text ?? "");
      svg.append(text);
    }
  }
  return { el: svg, update };
}

// src/axes-view.js
function createAxes(model, stage) {
  const img = h("img", { class: "ut-axes", dataset: { role: "axes" }, alt: "axes", draggable: false });
  const paper = h("div", { class: "ut-axes-paper" });
  const trait = () => {
    const a = model.get("axes_image");
    const box = a ? [a.x, a.y, a.width, a.height].map(Number) : [];
    const ok = a && typeof a.src === "string" && a.src.startsWith("data:image/") && box.every(Number.isFinite) && box[2] > 0 && box[3] > 0;
    return ok ? { src: a.src, box } : null;
  };
  function update([W, H]) {
    const a = trait();
    const m = a ? [-a.box[0], -a.box[1], a.box[0] + a.box[2] - W, a.box[1] + a.box[3] - H].map((v) => Math.max(0, Math.ceil(v))) : [0, 0, 0, 0];
    if (!a) {
      img.remove();
      paper.remove();
    } else if (img.parentNode !== stage.el) {
      stage.el.prepend(paper);
      stage.bg.after(img);
    }
    if (a && img.getAttribute("src") !== a.src) img.src = a.src;
    stage.margin = m;
  }
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

// src/export.js
function exportBlob(format, data) {
  if (format === "svg") return new Blob([String(data)], { type: "image/svg+xml" });
  const text = String(data);
  const comma = text.indexOf(",");
  const header = text.slice(0, comma);
  const body = text.slice(comma + 1);
  const mime = (header.match(/^data:([^;,]+)/) || [])[1] || "image/png";
  if (!header.includes(";base64")) return new Blob([decodeURIComponent(body)], { type: mime });
  const bin = atob(body);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Blob([bytes], { type: mime });
}
function download(root, msg) {
  const format = msg.format === "png" ? "png" : "svg";
  const url = URL.createObjectURL(exportBlob(format, msg.data));
  const a = document.createElement("a");
  a.href = url;
  a.download = `unitopia.${format}`;
  a.hidden = true;
  root.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1e4);
}
async function copyText(root, text) {
  try {
    if (navigator.clipboard && window.isSecureContext) {
      await navigator.clipboard.writeText(text);
      return true;
    }
  } catch (err) {
  }
  const old = root.querySelector("textarea.ut-code");
  if (old) old.remove();
  const area = document.createElement("textarea");
  area.className = "ut-code";
  area.readOnly = true;
  area.value = text;
  area.setAttribute("aria-label", "The design as Python");
  root.append(area);
  area.select();
  let copied = false;
  try {
    copied = document.execCommand("copy");
  } catch (err) {
    copied = false;
  }
  if (copied) area.remove();
  return copied;
}

// src/workspace.js
var editing = (tool) => typeof tool === "string" && tool !== "select";
function guidesVisible({ tool, hasFrame, shown }) {
  return !hasFrame || editing(tool) || !!shown;
}
function createPageText(wrap) {
  const title = h("div", { class: "ut-title", dataset: { role: "title" }, hidden: true });
  const caption = h("div", { class: "ut-caption", dataset: { role: "caption" }, hidden: true });
  wrap.prepend(title);
  wrap.append(caption);
  const set = (el, v) => {
    const text = typeof v === "string" ? v : "";
    el.textContent = text;
    el.hidden = !text;
  };
  return { update: (design) => (set(title, design.title), set(caption, design.caption)) };
}
function foldPanels(panels) {
  for (const p of panels) {
    const header = p.el.querySelector("header");
    const name = header.querySelector("h3").textContent;
    const btn = h("button", {
      type: "button",
      class: "ut-btn ut-icon ut-fold",
      dataset: { action: "fold" },
      "aria-expanded": "true",
      title: `Fold or unfold ${name}`,
      "aria-label": `Fold or unfold ${name}`,
      onclick: () => {
        const folded = p.el.classList.toggle("ut-folded");
        btn.setAttribute("aria-expanded", String(!folded));
      }
    }, "▾");
    header.prepend(btn);
  }
}
function toggleButton(action, text, label, pressed, onChange) {
  const btn = h("button", {
    type: "button",
    class: "ut-btn",
    dataset: { action },
    "aria-pressed": String(pressed),
    title: label,
    "aria-label": label,
    onclick: () => {
      pressed = !pressed;
      btn.setAttribute("aria-pressed", String(pressed));
      onChange(pressed);
    }
  }, text);
  return btn;
}
function createToggles(side, onGuides) {
  let guides = false;
  const panels = toggleButton(
    "toggle-panels",
    "Panels",
    "Show or hide the panels",
    !side.hidden,
    (shown) => {
      side.hidden = !shown;
    }
  );
  const guide = toggleButton(
    "toggle-guides",
    "Guides",
    "Show the emitters and forces over the marks",
    guides,
    (shown) => {
      guides = shown;
      onGuides();
    }
  );
  return { panels, guide, guidesShown: () => guides };
}

// src/replay.js
var BUDGET_BYTES = 64 * 1024 * 1024;
var PLAY_FPS = 30;
var MAX_SECONDS = 10;
var Recording = class {
  constructor(budgetBytes = BUDGET_BYTES) {
    if (!(budgetBytes > 0)) throw new RangeError(`budgetBytes must be a positive number of bytes, got ${budgetBytes}`);
    this.budget = budgetBytes;
    this.clear();
  }
  clear() {
    this.kept = [];
    this.received = 0;
    this.stride = 1;
  }
  /** Kept frames. */
  get length() {
    return this.kept.length;
  }
  /** Bytes held by the kept frames. */
  get bytes() {
    return this.kept.reduce((sum, e) => sum + e.data.byteLength, 0);
  }
  push(frame) {
    if (!frame || !frame.length) return;
    if (this.kept.length && this.kept[0].data.length !== frame.length) this.clear();
    const index = this.received++;
    const tail = this.kept[this.kept.length - 1];
    const reuse = tail && tail.index % this.stride !== 0 ? this.kept.pop().data : null;
    const data = reuse || new Float32Array(frame.length);
    data.set(frame);
    this.kept.push({ index, data });
    const max = Math.max(2, Math.floor(this.budget / data.byteLength));
    while (this.kept.length > max) {
      this.stride *= 2;
      const latest = this.kept[this.kept.length - 1];
      this.kept = this.kept.filter((e) => e.index % this.stride === 0 || e === latest);
    }
  }
  /**
   * The frame at `position` (a received frame index, fractions allowed), interpolated
   * between the kept frames around it, written into `out` (reused when its length fits).
   * Null when nothing is recorded.
   */
  sample(position, out = null) {
    const kept = this.kept;
    if (!kept.length) return null;
    const first = kept[0], last = kept[kept.length - 1];
    if (!out || out.length !== first.data.length) out = new Float32Array(first.data.length);
    if (!(position > first.index)) return out.set(first.data), out;
    if (position >= last.index) return out.set(last.data), out;
    let lo = 0, hi = kept.length - 1;
    while (hi - lo > 1) {
      const mid = lo + hi >> 1;
      if (kept[mid].index <= position) lo = mid;
      else hi = mid;
    }
    const a = kept[lo], b = kept[hi];
    return lerpFrame(out, a.data, b.data, (position - a.index) / (b.index - a.index));
  }
};
var Player = class {
  constructor(recording, { fps = PLAY_FPS, maxSeconds = MAX_SECONDS } = {}) {
    this.recording = recording;
    this.fps = fps;
    this.maxSeconds = maxSeconds;
    this.position = null;
    this.playing = false;
    this.out = null;
  }
  /** The last position: the latest received frame. */
  get end() {
    return Math.max(0, this.recording.received - 1);
  }
  /** Received frames per second of replay. */
  get rate() {
    return Math.max(this.fps, this.end / this.maxSeconds);
  }
  play(now) {
    if (this.position === null || this.position >= this.end) this.position = 0;
    this.playing = true;
    this.startTime = now;
    this.startPosition = this.position;
  }
  pause() {
    this.playing = false;
  }
  /** Shows the frame at `position` (clamped to the recording), paused. */
  seek(position) {
    this.playing = false;
    this.position = Math.min(this.end, Math.max(0, Number(position) || 0));
  }
  /** Back to the live frames. */
  stop() {
    this.playing = false;
    this.position = null;
  }
  /** Advances a playing replay to time `now`; true when the position moved. */
  step(now) {
    if (!this.playing) return false;
    const elapsed = Math.max(0, now - this.startTime) / 1e3;
    this.position = Math.min(this.end, this.startPosition + elapsed * this.rate);
    if (this.position >= this.end) this.playing = false;
    return true;
  }
  /** The frame to draw, or null while the live frames show. */
  frame() {
    if (this.position === null) return null;
    this.out = this.recording.sample(this.position, this.out);
    return this.out;
  }
};

// src/replay-control.js
function createReplay(onChange) {
  const recording = new Recording();
  const player = new Player(recording);
  const button = h("button", {
    type: "button",
    class: "ut-btn",
    dataset: { action: "replay" },
    onclick: () => {
      if (player.playing) player.pause();
      else player.play(performance.now());
      show();
    }
  });
  const slider = h("input", {
    type: "range",
    class: "ut-replay-scrub",
    min: "0",
    max: "0",
    step: "1",
    value: "0",
    title: "Replay position (frame of the last run)",
    "aria-label": "Replay position (frame of the last run)",
    oninput: () => {
      player.seek(Number(slider.value));
      show();
    }
  });
  const el = h("div", { class: "ut-group ut-replay", dataset: { role: "replay", state: "live" }, role: "group", "aria-label": "Replay of the last run", hidden: true }, button, slider);
  function sync() {
    const label = player.playing ? "Pause the replay" : "Replay the last run's settling";
    button.textContent = player.playing ? "❚❚" : "▶";
    button.title = label;
    button.setAttribute("aria-label", label);
    el.dataset.state = player.playing ? "playing" : player.position === null ? "live" : "paused";
    slider.max = String(player.end);
    slider.value = String(player.position === null ? player.end : Math.round(player.position));
  }
  const show = () => (sync(), onChange());
  sync();
  return {
    el,
    /** A frame streamed during a run. */
    record(frame) {
      recording.push(frame);
      el.hidden = recording.length < 2;
      slider.max = String(player.end);
      if (player.position === null) slider.value = slider.max;
    },
    /** A new run: the recording and the replay on screen go. */
    clear() {
      recording.clear();
      player.stop();
      el.hidden = true;
      show();
    },
    /** `live`: a run streams now (a kernel is there); the replay waits until it ends. */
    update(live) {
      button.disabled = slider.disabled = !!live;
      if (live && player.position !== null) player.stop(), show();
    },
    /** Called by the view's paint at time `now`; true when the frame on screen moved. */
    step(now) {
      const moved = player.step(now);
      if (moved) sync();
      return moved;
    },
    frame: () => player.frame(),
    /** The received frame index on screen, or null while the live frames show. */
    position: () => player.position,
    playing: () => player.playing
  };
}

// src/view.js
function renderView({ model, el, signal }) {
  const s = session(model);
  const stage = createStage(signal);
  const root = h("div", { class: "unitopia", dataset: { unitopia: "", status: "idle", frames: "0", lmSuppressShortcuts: "true" }, tabindex: "0" });
  const stats = { paints: 0, paintMs: 0, framesReceived: 0 };
  root.unitopiaStats = stats;
  const hitCtx = document.createElement("canvas").getContext("2d");
  const interp = new FrameInterpolator();
  const images = new ImageCache(() => redraw("scene"));
  const bitmaps = new MarkBitmaps(() => redraw("marks"));
  let units = null, colors = null, clips = null, selected = /* @__PURE__ */ new Set(), draft = null, index = null, indexAt = null, pinned = [];
  const dirty = /* @__PURE__ */ new Set();
  const painter = new MarksPainter(stage.canvases.marks);
  let marksPending = false;
  let raf = 0;
  const view = {
    model,
    session: s,
    stage,
    root,
    signal,
    design: () => draft || readDesign(model),
    layer: () => currentLayer(model),
    unit: () => 1 / stage.scale,
    hitContext: () => hitCtx,
    eraserWidth: () => toolbar.eraserWidth(),
    /** Commits `next`; `before`: the design an undo returns to (default: the model's). */
    commit(next, before) {
      draft = null;
      commit(model, next, before);
    },
    setDraft(d) {
      draft = d;
      redraw("scene", "over");
    },
    setLayer: (i) => setUi(model, { layer: i, picked: null }),
    setTool: (name) => setUi(model, { tool: name, picked: null }),
    pick: (picked) => setUi(model, { picked }),
    undo: () => undo(model),
    redo: () => redo(model),
    hasFrame: () => !!interp.to,
    /** The shown layout: Float32Array (N, 4) x, y, angle, scale (null before a run). */
    frame: () => interp.to,
    units: () => units,
    selected: () => selected,
    hit: (p) => hitIndex().query(p[0], p[1]),
    marksInPolygon: (pts) => hitIndex().inPolygon(pts),
    toggleSelect(indices, additive2) {
      const next = new Set(additive2 ? selected : []);
      for (const i of indices) additive2 && next.has(i) && indices.length === 1 ? next.delete(i) : next.add(i);
      model.set("selected_units", [...next].sort((a, b) => a - b));
      model.save_changes();
    },
    /** Run pressed: sent to the kernel, with a notice if nothing answers. */
    run: () => status.run(),
    /** Sends a message to the kernel; false (shown in the notice) when there is none. */
    send: (msg) => status.send(msg),
    kernel: () => status.kernel(),
    redraw
  };
  function hitIndex() {
    const at = replay.position();
    const frame = at === null ? interp.to : replay.frame();
    if (!index || index.units !== units || index.frame !== frame || indexAt !== at) index = new HitIndex(units, frame);
    indexAt = at;
    return index;
  }
  const toolbar = createToolbar(view);
  const status = createStatus(model, signal, () => onStatus());
  const panels = [createLayersPanel(view), createSettingsPanel(view), createFieldsPanel(view), createMarkPanel(view)];
  const tools = makeTools(view);
  const legend = createLegend(view, signal);
  const pileLabels = createPileLabels(stage);
  const axes = createAxes(model, stage);
  const drawAxes = () => (axes.update(readDesign(model).canvas || [1, 1]), axes.place(), redraw("scene"));
  const drawLabels = () => pileLabels.update(list(model, "pile_labels"), readDesign(model).canvas || [1, 1]);
  const pageText = createPageText(stage.wrap);
  const side = h("div", { class: "ut-side" }, panels.map((p) => p.el));
  foldPanels(panels);
  const toggles = createToggles(side, () => redraw("over"));
  const replay = createReplay(() => redraw("marks"));
  root.append(
    h("div", { class: "ut-top" }, toolbar.el, legend.toggle, toggles.panels, toggles.guide, replay.el, status.el),
    status.banner,
    status.notice,
    h("div", { class: "ut-main" }, legend.area, side)
  );
  el.append(root);
  signal.addEventListener("abort", () => {
    cancelAnimationFrame(raf);
    bitmaps.dispose();
    root.remove();
  }, { once: true });
  function redraw(...what) {
    for (const w of what) dirty.add(w);
    if (!raf) raf = requestAnimationFrame(paint);
  }
  function paint(now) {
    raf = 0;
    if (signal.aborted) return;
    const design = view.design();
    if (stage.layout(design.canvas)) {
      ["scene", "over", "marks"].forEach((w) => dirty.add(w));
      painter.cancel();
      legend.place();
      axes.place();
    }
    if (interp.step(now)) dirty.add("marks");
    if (replay.step(now)) dirty.add("marks");
    const unit = view.unit();
    if (dirty.has("scene")) drawScene(stage.begin("scene"), stage, design, view.layer(), images);
    if (dirty.has("over")) {
      const guides = guidesVisible({ tool: s.tool, hasFrame: view.hasFrame(), shown: toggles.guidesShown() });
      drawOverlay(stage.begin("over"), { design, current: view.layer(), picked: s.picked, unit, tool: tools[s.tool], guides, pins: { list: pinned, frame: interp.to } });
    }
    if (dirty.has("marks")) marksPending = true;
    if (marksPending && !painter.busy) {
      painter.start(stage.k(), { units, frame: replay.frame() || interp.current, colors, clips, bitmaps, selected });
      marksPending = false;
    }
    if (painter.busy) {
      const t0 = performance.now();
      if (painter.step()) {
        bitmaps.need(painter.px);
        stats.paints++;
      }
      stats.paintMs += performance.now() - t0;
    }
    dirty.clear();
    if (!interp.settled || painter.busy || marksPending || replay.playing()) raf = requestAnimationFrame(paint);
  }
  function onDesign() {
    const design = readDesign(model);
    const bg = design.background && design.background.image;
    if (typeof bg === "string" && bg.startsWith("data:image/")) {
      if (stage.bg.getAttribute("src") !== bg) stage.bg.src = bg;
      stage.bg.hidden = false;
    } else stage.bg.hidden = true;
    images.prune(new Set(design.layers.map((l) => l.container && l.container.image).filter(Boolean)));
    pageText.update(design);
    drawLabels();
    drawAxes();
    updatePanels();
    legend.place();
    redraw("scene", "over");
  }
  function updatePanels() {
    toolbar.update();
    panels.forEach((p) => p.update());
  }
  function onFrame() {
    const frame = decodeFloat32(model.get("frame"));
    stats.framesReceived++;
    if (interp.to && sameFrame(frame, interp.to)) return;
    const had = view.hasFrame();
    interp.push(frame, performance.now());
    if (model.get("status") === "running") replay.record(frame);
    if (model.get("status") !== "running") interp.snap();
    redraw(...had === view.hasFrame() && !pinned.length ? ["marks"] : ["marks", "over"]);
  }
  function onUnits() {
    units = decodeFloat32(model.get("units"));
    colors = decodeUint8(model.get("colors"));
    clips = decodeFloat32(model.get("clips"), 1);
    redraw("marks");
  }
  function onSelected() {
    selected = new Set(list(model, "selected_units").map(Number));
    redraw("marks");
  }
  function onPinned() {
    pinned = list(model, "pinned_units").map(Number);
    redraw("over");
  }
  function onStatus() {
    root.dataset.status = String(model.get("status") || "idle");
    root.dataset.frames = String(Number(model.get("frame_count")) || 0);
    root.dataset.stale = String(!!model.get("stale"));
    root.dataset.kernel = status.kernel();
    const running = model.get("status") === "running";
    if (running && !(Number(model.get("frame_count")) > 0)) replay.clear();
    replay.update(running && status.kernel() !== "gone");
    status.update();
    toolbar.update();
  }
  onModel(model, ["change:design"], onDesign, signal);
  onModel(model, ["change:frame"], onFrame, signal);
  onModel(model, ["change:units", "change:colors", "change:clips"], onUnits, signal);
  onModel(model, ["change:selected_units"], onSelected, signal);
  onModel(model, ["change:pinned_units"], onPinned, signal);
  onModel(model, ["change:status", "change:frame_count", "change:progress", "change:error"], () => (status.answered(), onStatus()), signal);
  onModel(model, ["change:stale"], onStatus, signal);
  onModel(model, ["change:legend_image"], () => legend.place(), signal);
  onModel(model, ["change:pile_labels"], drawLabels, signal);
  onModel(model, ["change:axes_image"], drawAxes, signal);
  onModel(model, ["change:fields"], () => panels[2].update(), signal);
  onModel(model, ["change:marks"], () => {
    bitmaps.update(list(model, "marks"));
    panels[3].update();
    redraw("marks");
  }, signal);
  onModel(model, ["msg:custom"], (msg) => {
    if (msg && msg.type === "export") download(root, msg);
    else if (msg && msg.type === "notice") status.notify(String(msg.text || ""));
    else if (msg && msg.type === "code") {
      copyText(root, String(msg.code || "")).then((ok) => status.notify(ok ? "Copied the design as Python" : "Press Ctrl+C to copy the selected Python"));
    }
  }, signal);
  listen(s.bus, "ui", () => {
    updatePanels();
    redraw("scene", "over");
  }, signal);
  stage.onResize = () => redraw("scene", "over", "marks");
  attachInput(view, tools, signal);
  bitmaps.update(list(model, "marks"));
  onUnits();
  onSelected();
  onPinned();
  onStatus();
  onDesign();
  onFrame();
  stats.framesReceived = 0;
  return view;
}

// src/index.js
var index_default = {
  initialize({ model }) {
    session(model);
  },
  render({ model, el, signal }) {
    const controller = signal ? null : new AbortController();
    renderView({ model, el, signal: signal || controller.signal });
    return controller ? () => controller.abort() : void 0;
  }
};
export {
  index_default as default
};
