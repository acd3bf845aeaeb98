import { test } from "node:test";
import assert from "node:assert/strict";
import { drawRange } from "../src/draw-marks.js";

// A 2D context that records the clip rectangles and the sprites drawn.
function recorder(log) {
  return {
    setTransform() {},
    save: () => log.push(["save"]),
    restore: () => log.push(["restore"]),
    beginPath() {},
    rect: (x, y, w, h) => log.push(["rect", x, y, w, h]),
    clip: () => log.push(["clip"]),
    drawImage: (img, x, y, w, h) => log.push(["draw", x, y, w, h]),
    ellipse() {},
    fill() {},
  };
}

test("a partial mark is clipped to its share of the width, from its left; whole marks are not", () => {
  const units = new Float32Array([0, 0, 10, 20, 0, 0, 10, 20]);
  const frame = new Float32Array([50, 50, 0, 2, 100, 50, 0, 2]); // drawn 20 x 40 each
  const log = [];
  const bitmaps = { get: () => ({}) };
  drawRange(recorder(log), 1, { units, frame, colors: null, bitmaps, clips: new Float32Array([1, 0.25]) }, 0, 2);
  assert.deepEqual(log, [
    ["draw", 40, 30, 20, 40],
    ["save"], ["rect", 90, 30, 5, 40], ["clip"], ["draw", 90, 30, 20, 40], ["restore"],
  ]);
});

test("without clips every mark is drawn whole", () => {
  const log = [];
  drawRange(recorder(log), 1, { units: new Float32Array([0, 0, 4, 4]), frame: new Float32Array([5, 5, 0, 1]), colors: null, bitmaps: { get: () => ({}) }, clips: null }, 0, 1);
  assert.deepEqual(log, [["draw", 3, 3, 4, 4]]);
});
