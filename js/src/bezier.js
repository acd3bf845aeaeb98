// Cubic Bezier curves: evaluation and a Schneider-style least-squares fit of a
// freehand stroke ("An Algorithm for Automatically Fitting Digitized Curves",
// Graphics Gems, 1990). A curve is a flat list of 3k + 1 control points [x, y]:
// anchor, handle, handle, anchor, handle, handle, anchor, ...

const add = (a, b) => [a[0] + b[0], a[1] + b[1]];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1]];
const mul = (a, s) => [a[0] * s, a[1] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1];
const norm = (a) => {
  const len = Math.hypot(a[0], a[1]);
  return len ? [a[0] / len, a[1] / len] : [0, 0];
};

/** Point of one cubic segment [p0, p1, p2, p3] at t in [0, 1]. */
export function cubicAt(b, t) {
  const s = 1 - t;
  const w0 = s * s * s;
  const w1 = 3 * s * s * t;
  const w2 = 3 * s * t * t;
  const w3 = t * t * t;
  return [
    w0 * b[0][0] + w1 * b[1][0] + w2 * b[2][0] + w3 * b[3][0],
    w0 * b[0][1] + w1 * b[1][1] + w2 * b[2][1] + w3 * b[3][1],
  ];
}

function derivative(b) {
  const out = [];
  for (let i = 0; i < b.length - 1; i++) out.push(mul(sub(b[i + 1], b[i]), b.length - 1));
  return out;
}

function bezierAt(b, t) {
  // de Casteljau for any degree (used for the first and second derivatives).
  let pts = b;
  while (pts.length > 1) {
    const next = [];
    for (let i = 0; i < pts.length - 1; i++) next.push(add(mul(pts[i], 1 - t), mul(pts[i + 1], t)));
    pts = next;
  }
  return pts[0];
}

/** The segments of a 3k + 1 control point list, each [p0, p1, p2, p3]. */
export function segments(points) {
  const out = [];
  for (let i = 0; i + 3 < points.length; i += 3) out.push(points.slice(i, i + 4));
  return out;
}

/** Samples `perSegment` points on each segment of a 3k + 1 control point list. */
export function sampleCurve(points, perSegment = 24) {
  const out = [];
  segments(points).forEach((seg, k) => {
    for (let i = k ? 1 : 0; i <= perSegment; i++) out.push(cubicAt(seg, i / perSegment));
  });
  return out;
}

/**
 * Fits cubic Bezier segments to a polyline so that no input point lies farther than
 * `tolerance` px from the curve. Returns 3k + 1 control points (k >= 1), or [] when the
 * stroke has fewer than two distinct points.
 */
export function fitCurve(points, tolerance = 4) {
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

/**
 * Unit tangent at the start of a polyline, second-order accurate: the derivative of the
 * parabola through p0, pk, p2k, with k chosen so the window spans a few pixels of arc
 * (pointer jitter would swamp the first two points alone).
 */
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
  // A sharp turn inside the window can flip the estimate; fall back to the chord then.
  const chord = norm(sub(p1, p0));
  return dot(t, chord) > 0.5 ? t : chord;
}

function chordParams(pts) {
  const u = [0];
  for (let i = 1; i < pts.length; i++) u.push(u[i - 1] + Math.hypot(...sub(pts[i], pts[i - 1])));
  const total = u[u.length - 1];
  return u.map((v) => v / total);
}

/** Least-squares handle lengths along the fixed end tangents. */
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
