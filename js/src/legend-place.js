// Where the legend goes (design "legend": {"visible": bool, "position": side | [x, y]}):
// beside the canvas on one side, or at a top-left corner in canvas px once dragged.
import { clone } from "./design-edit.js";

export const SIDES = ["right", "bottom", "left", "top"];

/** The design's legend settings with the defaults filled in (visible, on the right). */
export function legendSettings(design) {
  const l = design && design.legend && typeof design.legend === "object" ? design.legend : {};
  const p = l.position;
  const position = SIDES.includes(p) ? p : isPoint(p) ? [Number(p[0]), Number(p[1])] : "right";
  return { visible: l.visible !== false, position };
}

const isPoint = (p) => Array.isArray(p) && p.length === 2 && p.every((v) => Number.isFinite(Number(v)) && v !== null);

/** A copy of the design with the legend settings patched (other legend keys kept). */
export function setLegend(design, patch) {
  const next = clone(design);
  next.legend = { ...(next.legend && typeof next.legend === "object" ? next.legend : {}), ...legendSettings(design), ...patch };
  return next;
}

/**
 * A dragged legend's top-left corner [x, y] in canvas px, kept inside the canvas
 * (size [w, h] is the legend's, canvas [W, H]) and rounded to 0.1 px.
 */
export function clampCorner([x, y], [w, h], [W, H]) {
  const keep = (v, lo, hi) => Math.round(10 * Math.max(lo, Math.min(hi, v))) / 10;
  return [keep(x, 0, Math.max(0, W - w)), keep(y, 0, Math.max(0, H - h))];
}
