// Paints what sits above the marks: emitters (grid: a hatched hint over the container;
// curve: the Bezier with its control handles), forces (point: a dot; direction: an
// arrow), the picked object's highlight, a pin on every pinned mark, and the active
// tool's preview. `guides` false leaves out the emitters and forces (the finished marks
// show alone); the pins stay. `pins`: {list: unit indices, frame: (N, 4) x, y, angle, scale}.
import { containerPath, directionArrow, emitterPolyline, layerColor } from "./shapes.js";

export function drawOverlay(ctx, { design, current, picked, unit, tool, guides = true, pins = null }) {
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
  if (pins && pins.frame) for (const i of pins.list) if (4 * i + 1 < pins.frame.length) drawPin(ctx, pins.frame[4 * i], pins.frame[4 * i + 1], unit);
  if (tool && tool.preview) tool.preview(ctx, unit);
}

/** A map pin standing on (x, y): a red head on a short needle, outlined in white. */
export function drawPin(ctx, x, y, unit) {
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

export function drawArrow(ctx, from, to, color, hot, unit) {
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

export function polyline(ctx, pts) {
  ctx.beginPath();
  pts.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
}

function segment(ctx, a, b) {
  ctx.beginPath();
  ctx.moveTo(a[0], a[1]);
  ctx.lineTo(b[0], b[1]);
  ctx.stroke();
}
