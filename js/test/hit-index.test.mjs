import { test } from "node:test";
import assert from "node:assert/strict";
import { HitIndex } from "../src/hit-index.js";

const units = (...rows) => new Float32Array(rows.flat());

test("hits the topmost mark's rotated box", () => {
  // Two 40 x 10 marks at the same place, the second rotated upright.
  const u = units([0, 0, 40, 10], [0, 0, 40, 10]);
  const f = units([100, 100, 0, 1], [100, 100, 90, 1]);
  const idx = new HitIndex(u, f);
  assert.equal(idx.query(100, 100), 1, "topmost first");
  assert.equal(idx.query(115, 100), 0, "only the flat one reaches x + 15");
  assert.equal(idx.query(100, 115), 1, "only the upright one reaches y + 15");
  assert.equal(idx.query(115, 115), -1, "inside both bounding circles, in neither box");
  assert.equal(idx.query(500, 500), -1);
});

test("the global scale enlarges the boxes", () => {
  const idx = new HitIndex(units([0, 0, 10, 10]), units([0, 0, 0, 3]));
  assert.equal(idx.query(14, 0), 1 - 1);
  assert.equal(idx.query(16, 0), -1);
});

test("a grid over 5,000 marks answers like a brute-force scan", () => {
  const n = 5000;
  const u = new Float32Array(4 * n);
  const f = new Float32Array(4 * n);
  let seed = 7;
  const rnd = () => ((seed = (seed * 16807) % 2147483647) / 2147483647);
  for (let i = 0; i < n; i++) {
    u.set([0, 0, 4 + 12 * rnd(), 4 + 12 * rnd()], 4 * i);
    f.set([800 * rnd(), 500 * rnd(), 360 * rnd(), 1], 4 * i);
  }
  const idx = new HitIndex(u, f);
  for (let q = 0; q < 500; q++) {
    const x = 800 * rnd();
    const y = 500 * rnd();
    let expect = -1;
    for (let i = 0; i < n; i++) if (idx.contains(i, x, y)) expect = i;
    assert.equal(idx.query(x, y), expect);
  }
});

test("lasso selects marks whose centre is inside, and skips unplaced ones", () => {
  const u = units([0, 0, 10, 10], [0, 0, 10, 10], [0, 0, 10, 10]);
  const f = units([10, 10, 0, 1], [50, 50, 0, 1], [NaN, NaN, 0, 1]);
  const idx = new HitIndex(u, f);
  assert.deepEqual(idx.inPolygon([[0, 0], [30, 0], [30, 30], [0, 30]]), [0]);
  assert.equal(idx.query(NaN, NaN), -1);
});

test("no frame, no hits", () => {
  assert.equal(new HitIndex(null, null).query(1, 1), -1);
});
