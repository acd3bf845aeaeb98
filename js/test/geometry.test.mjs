import { test } from "node:test";
import assert from "node:assert/strict";
import { closeStroke, pointInRotatedBox, pointInPolygon, simplify, angleDeg } from "../src/geometry.js";

const circle = (n, r = 100, turn = 1) =>
  Array.from({ length: n }, (_, i) => [200 + r * Math.cos((2 * Math.PI * turn * i) / (n - 1)), 200 + r * Math.sin((2 * Math.PI * turn * i) / (n - 1))]);

test("a lasso that ends near its start closes there, without the trailing points", () => {
  const pts = circle(60); // last point equals the first
  const closed = closeStroke(pts, { snap: 16 });
  assert.equal(closed.snapped, true);
  assert.ok(closed.points.length < pts.length);
  const last = closed.points[closed.points.length - 1];
  assert.ok(Math.hypot(last[0] - pts[0][0], last[1] - pts[0][1]) > 16, "no point folds back onto the start");
});

test("a lasso that ends far from its start is closed on release anyway", () => {
  const pts = circle(60, 100, 0.75); // three quarters of a circle
  const closed = closeStroke(pts, { snap: 16 });
  assert.equal(closed.snapped, false);
  assert.equal(closed.points.length, pts.length, "closed by the straight segment back to the start");
});

test("a stroke without area is not a container", () => {
  assert.equal(closeStroke([[0, 0], [10, 10]]), null);
  assert.equal(closeStroke([[0, 0], [10, 10], [20, 20], [30, 30]]), null);
});

test("point in a rotated box", () => {
  // A 100 x 20 box at (50, 50): unrotated, (95, 50) is inside and (50, 80) is not.
  assert.equal(pointInRotatedBox(95, 50, 50, 50, 100, 20, 0), true);
  assert.equal(pointInRotatedBox(50, 80, 50, 50, 100, 20, 0), false);
  // Rotated 90 degrees it stands upright: the two answers swap.
  assert.equal(pointInRotatedBox(95, 50, 50, 50, 100, 20, 90), false);
  assert.equal(pointInRotatedBox(50, 80, 50, 50, 100, 20, 90), true);
  // At 45 degrees the box's long axis runs down and to the right (clockwise on screen).
  assert.equal(pointInRotatedBox(80, 80, 50, 50, 100, 20, 45), true);
  assert.equal(pointInRotatedBox(80, 20, 50, 50, 100, 20, 45), false);
});

test("point in polygon and simplification", () => {
  const square = [[0, 0], [10, 0], [10, 10], [0, 10]];
  assert.equal(pointInPolygon([5, 5], square), true);
  assert.equal(pointInPolygon([15, 5], square), false);
  const line = Array.from({ length: 50 }, (_, i) => [i, 0.1 * (i % 2)]);
  assert.deepEqual(simplify(line, 1), [[0, 0], [49, 0.1]]);
});

test("angles are clockwise on screen, 90 = down", () => {
  assert.equal(angleDeg([0, 0], [0, 10]), 90);
  assert.equal(angleDeg([0, 0], [-10, 0]), 180);
  assert.equal(angleDeg([0, 0], [0, -10]), 270);
});
