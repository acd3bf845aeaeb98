// Plane geometry in canvas pixels (x right, y down; angles in degrees, clockwise on screen).
// Points are [x, y] arrays, as in the design JSON.

export const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);

export function pathLength(points) {
  let total = 0;
  for (let i = 1; i < points.length; i++) total += dist(points[i - 1], points[i]);
  return total;
}

/** Signed area (shoelace); positive when the polygon runs clockwise on screen. */
export function polygonArea(points) {
  let a = 0;
  for (let i = 0, j = points.length - 1; i < points.length; j = i++) {
    a += points[j][0] * points[i][1] - points[i][0] * points[j][1];
  }
  return a / 2;
}

/** Even-odd point in polygon. */
export function pointInPolygon(p, points) {
  let inside = false;
  const [x, y] = p;
  for (let i = 0, j = points.length - 1; i < points.length; j = i++) {
    const [xi, yi] = points[i];
    const [xj, yj] = points[j];
    if (yi > y !== yj > y && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

/** Distance from p to the segment ab. */
export function distToSegment(p, a, b) {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  let t = len2 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0;
  t = Math.max(0, Math.min(1, t));
  return Math.hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

/** Distance from p to a polyline (closed adds the segment back to the start). */
export function distToPolyline(p, points, closed = false) {
  let best = Infinity;
  const n = points.length;
  if (n === 1) return dist(p, points[0]);
  for (let i = 1; i < n + (closed ? 1 : 0); i++) {
    best = Math.min(best, distToSegment(p, points[i - 1], points[i % n]));
  }
  return best;
}

/**
 * Is (px, py) inside a box of size w x h centred at (cx, cy) and rotated by angleDeg?
 * The point is rotated back into the box's frame, then compared with the half sizes.
 */
export function pointInRotatedBox(px, py, cx, cy, w, h, angleDeg) {
  const r = (-angleDeg * Math.PI) / 180;
  const dx = px - cx;
  const dy = py - cy;
  const bx = dx * Math.cos(r) - dy * Math.sin(r);
  const by = dx * Math.sin(r) + dy * Math.cos(r);
  return Math.abs(bx) <= w / 2 && Math.abs(by) <= h / 2;
}

/** Ramer-Douglas-Peucker simplification of a polyline. */
export function simplify(points, tolerance = 1) {
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

/**
 * The lasso's auto-close rule. A stroke whose end comes back within `snap` px of its
 * start closes there: the trailing points inside the snap radius are dropped so the
 * polygon does not fold back on itself. Any other stroke is closed on release anyway by
 * the straight segment from its end to its start. Returns null for a stroke that encloses
 * no area (fewer than 3 points, or less than `minArea` px^2).
 */
export function closeStroke(points, { snap = 16, minArea = 16 } = {}) {
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

export const round2 = (v) => Math.round(v * 100) / 100;

/** An ellipse as a polygon (for hit tests and previews). */
export function ellipsePolygon(cx, cy, rx, ry, n = 48) {
  const out = [];
  for (let i = 0; i < n; i++) {
    const t = (2 * Math.PI * i) / n;
    out.push([cx + rx * Math.cos(t), cy + ry * Math.sin(t)]);
  }
  return out;
}

/** The box spanned by two drag corners, as {x, y, w, h}. */
export function boxFromCorners(a, b) {
  return {
    x: Math.min(a[0], b[0]),
    y: Math.min(a[1], b[1]),
    w: Math.abs(b[0] - a[0]),
    h: Math.abs(b[1] - a[1]),
  };
}

/** Angle of the vector a -> b in degrees, clockwise on screen (90 = down), in [0, 360). */
export function angleDeg(a, b) {
  const deg = (Math.atan2(b[1] - a[1], b[0] - a[0]) * 180) / Math.PI;
  return round2((deg + 360) % 360);
}
