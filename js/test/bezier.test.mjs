import { test } from "node:test";
import assert from "node:assert/strict";
import { cubicAt, fitCurve, sampleCurve, segments } from "../src/bezier.js";
import { distToPolyline } from "../src/geometry.js";

const known = [[100, 300], [180, 120], [420, 140], [520, 320]];
const sampleKnown = (n) => Array.from({ length: n }, (_, i) => cubicAt(known, i / (n - 1)));

test("fitting points sampled from one cubic reproduces that cubic", () => {
  for (const tol of [0.5, 1, 3]) {
    const fit = fitCurve(sampleKnown(80), tol);
    assert.equal(fit.length, 4, `tolerance ${tol}: one segment suffices`);
    assert.deepEqual(fit[0], known[0]);
    assert.deepEqual(fit[3], known[3]);
    // The fitted curve runs within the tolerance of the known one, both ways.
    const a = sampleCurve(fit, 400);
    const b = sampleCurve(known, 400);
    for (const p of sampleCurve(known, 60)) assert.ok(distToPolyline(p, a) <= tol + 0.05);
    for (const p of sampleCurve(fit, 60)) assert.ok(distToPolyline(p, b) <= tol + 0.05);
  }
  // A tight tolerance pins the handles down too.
  fitCurve(sampleKnown(80), 0.5).slice(1, 3).forEach((p, i) => {
    assert.ok(Math.hypot(p[0] - known[i + 1][0], p[1] - known[i + 1][1]) < 8, `handle ${i + 1}: ${p}`);
  });
});

test("every input point lies within the tolerance of the fitted curve", () => {
  // A wavy stroke that needs several segments.
  const stroke = Array.from({ length: 200 }, (_, i) => [10 + i * 3, 200 + 80 * Math.sin(i / 12)]);
  const tol = 2;
  const fit = fitCurve(stroke, tol);
  const dense = sampleCurve(fit, 200);
  for (const p of stroke) assert.ok(distToPolyline(p, dense) <= tol + 0.05, `point ${p} is off the curve`);
});

test("the output has 3k + 1 control points and starts and ends on the stroke", () => {
  for (const n of [2, 3, 10, 57, 300]) {
    const stroke = Array.from({ length: n }, (_, i) => [i * 4, 50 * Math.cos(i / 7) + (i % 3)]);
    const fit = fitCurve(stroke, 1);
    assert.equal((fit.length - 1) % 3, 0, `n=${n}: length ${fit.length}`);
    assert.ok(fit.length >= 4);
    const near = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1]) < 0.01;
    assert.ok(near(fit[0], stroke[0]) && near(fit[fit.length - 1], stroke[n - 1]));
    assert.equal(segments(fit).length, (fit.length - 1) / 3);
  }
});

test("a stroke without two distinct points fits nothing", () => {
  assert.deepEqual(fitCurve([[1, 1]]), []);
  assert.deepEqual(fitCurve([[1, 1], [1, 1]]), []);
});
