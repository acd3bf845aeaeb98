// Design objects -> canvas geometry: container outlines as Path2D, handle positions
// for the select tool, and where a direction force's arrow is drawn.
import { sampleCurve } from "./bezier.js";
import { ellipsePolygon, pointInPolygon } from "./geometry.js";

const PALETTE = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#b07aa1", "#edc948", "#ff9da7"];
export const layerColor = (i) => PALETTE[i % PALETTE.length];

/** The container's outline as a Path2D (fill it with "evenodd"), or null for image kinds. */
export function containerPath(c, canvas) {
  const p = new Path2D();
  if (!c || c.kind === "canvas") p.rect(0, 0, canvas[0], canvas[1]);
  else if (c.kind === "rect") p.rect(c.x, c.y, c.w, c.h);
  else if (c.kind === "ellipse") p.ellipse(c.cx, c.cy, Math.abs(c.rx), Math.abs(c.ry), 0, 0, 2 * Math.PI);
  else if (c.kind === "polygon" && Array.isArray(c.points) && c.points.length) {
    c.points.forEach((q, i) => (i ? p.lineTo(q[0], q[1]) : p.moveTo(q[0], q[1])));
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

/** The box an image container's mask covers. */
export const imageBox = (c, canvas) => (Array.isArray(c.box) ? c.box : [0, 0, canvas[0], canvas[1]]);

/** A polygon approximating the container's outline (hit tests); null for none/canvas. */
export function containerOutline(c, canvas) {
  if (!c || c.kind === "canvas") return null;
  if (c.kind === "rect") return [[c.x, c.y], [c.x + c.w, c.y], [c.x + c.w, c.y + c.h], [c.x, c.y + c.h]];
  if (c.kind === "ellipse") return ellipsePolygon(c.cx, c.cy, Math.abs(c.rx), Math.abs(c.ry));
  if (c.kind === "polygon") return c.points;
  if (c.kind === "image") {
    const [x, y, w, h] = imageBox(c, canvas);
    return [[x, y], [x + w, y], [x + w, y + h], [x, y + h]];
  }
  return null; // path data: hit-tested through Path2D instead
}

/** Bounding box [x0, y0, x1, y1] of a container (the canvas for none). */
export function containerBounds(c, canvas) {
  const pts = containerOutline(c, canvas);
  if (!pts || !pts.length) return [0, 0, canvas[0], canvas[1]];
  const xs = pts.map((p) => p[0]);
  const ys = pts.map((p) => p[1]);
  return [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
}

/** Is p inside the container (the whole canvas when there is none)? */
export function insideContainer(c, p, canvas, ctx) {
  if (!c || c.kind === "canvas") return p[0] >= 0 && p[1] >= 0 && p[0] <= canvas[0] && p[1] <= canvas[1];
  if (c.kind === "path") {
    const path = containerPath(c, canvas);
    return !!(path && ctx && ctx.isPointInPath(path, p[0], p[1], "evenodd"));
  }
  const pts = containerOutline(c, canvas);
  return !!pts && pointInPolygon(p, pts);
}

/** Where the direction arrow of a layer is drawn: from its container's centre. */
export function directionArrow(layer, canvas, angle) {
  const [x0, y0, x1, y1] = containerBounds(layer.container, canvas);
  const from = [(x0 + x1) / 2, (y0 + y1) / 2];
  const r = (angle * Math.PI) / 180;
  const len = 60;
  return { from, to: [from[0] + len * Math.cos(r), from[1] + len * Math.sin(r)] };
}

/** The polyline of a curve emitter, for drawing and hit tests. */
export const emitterPolyline = (emitter) =>
  emitter && emitter.kind === "curve" && Array.isArray(emitter.points) && emitter.points.length >= 4
    ? sampleCurve(emitter.points, 20)
    : null;
