// A small sketch pad for hand-drawn marks: strokes in pad px, sent as
// {"kind": "sketch", "strokes": [[[x, y], ...], ...], "width": w}.
import { h } from "../dom.js";
import { round2, simplify } from "../geometry.js";

const PAD = 160;

export function createSketchPad(onUse) {
  const canvas = h("canvas", { class: "ut-pad", width: PAD * 2, height: PAD * 2, dataset: { role: "sketch-pad" } });
  const width = h("input", { type: "range", min: "1", max: "16", value: "4", "aria-label": "Stroke width", oninput: () => draw() });
  let strokes = [];
  let live = null;

  const toPad = (ev) => {
    const r = canvas.getBoundingClientRect();
    return [((ev.clientX - r.left) * PAD) / r.width, ((ev.clientY - r.top) * PAD) / r.height];
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
      s.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
      if (s.length === 1) ctx.lineTo(s[0][0] + 0.01, s[0][1]);
      ctx.stroke();
    }
  }

  const button = (text, action, fn) => h("button", { type: "button", class: "ut-btn ut-small", dataset: { padAction: action }, onclick: fn }, text);
  const el = h("div", { class: "ut-sketch" }, canvas,
    h("div", { class: "ut-sketch-tools" },
      h("label", { class: "ut-row" }, h("span", { class: "ut-label", text: "width" }), width),
      button("Clear", "clear", () => ((strokes = []), draw())),
      button("Undo stroke", "undo", () => (strokes.pop(), draw())),
      button("Use as mark", "use", () => strokes.length && onUse({ kind: "sketch", strokes: strokes.map((s) => s.slice()), width: Number(width.value) }))));
  draw();
  return { el };
}
