import { test } from "node:test";
import assert from "node:assert/strict";
import { MarksPainter } from "../src/marks-painter.js";
import { sameFrame } from "../src/frames.js";

// A canvas whose 2D context records what is drawn; the clock is a counter (no timing).
function fakeCanvas(log, name) {
  const ctx = {
    setTransform() {},
    clearRect: () => log.push([name, "clear"]),
    getImageData() {},
    drawImage: (img, x) => log.push([name, img.tag, x]),
    strokeRect() {},
    beginPath() {},
    ellipse() {},
    fill() {},
  };
  return { width: 100, height: 50, getContext: () => ctx, tag: name };
}

function state(n, x = 10) {
  const units = new Float32Array(4 * n), frame = new Float32Array(4 * n);
  for (let i = 0; i < n; i++) {
    units.set([0, 0, 4, 4], 4 * i);
    frame.set([x + i, 20, 0, 1], 4 * i);
  }
  return { units, frame, colors: null, bitmaps: { get: () => ({ tag: "sprite" }) }, selected: new Set() };
}

function painter(log, tick) {
  let t = 0;
  return new MarksPainter(fakeCanvas(log, "visible"), { makeCanvas: () => fakeCanvas(log, "back"), now: () => (t += tick), sliceMs: 5, firstSlice: 100 });
}

test("a paint that outlasts its slice goes on in later steps and shows only when whole", () => {
  const log = [];
  const p = painter(log, 1); // each slice takes 1 ms: 100 marks first, then 500 a slice
  const s = state(1000);
  p.start(1, s);
  const steps = [];
  while (p.busy) steps.push(p.step());
  assert.ok(steps.length > 1, "split into several steps");
  assert.deepEqual(steps.slice(0, -1).every((v) => !v), true);
  assert.equal(steps[steps.length - 1], true);
  const sprites = log.filter(([where, what]) => where === "back" && what === "sprite");
  assert.equal(sprites.length, 1000, "every mark drawn once, into the back buffer");
  assert.deepEqual(sprites.map((e) => e[2]), Array.from({ length: 1000 }, (_, i) => 10 + i - 2), "in unit order");
  const shown = log.findIndex(([where, what]) => where === "visible" && what === "back");
  assert.equal(shown, log.length - 1, "the visible canvas gets the finished picture, once, at the end");
});

test("the frame painted is the one at start, though the caller's frame changes meanwhile", () => {
  const log = [];
  const p = painter(log, 1);
  const s = state(500);
  p.start(1, s);
  p.step();
  s.frame.fill(-1000); // the interpolator moved on
  while (p.busy) p.step();
  const xs = log.filter(([where, what]) => where === "back" && what === "sprite").map((e) => e[2]);
  assert.ok(xs.every((x) => x >= 8), "no mark drawn from the changed frame");
});

test("a short paint finishes in its first step; cancel drops an unfinished one", () => {
  const log = [];
  const p = painter(log, 0.001);
  p.start(1, state(50));
  assert.equal(p.step(), true);
  assert.equal(p.px, 4);
  const q = painter([], 1);
  q.start(1, state(1000));
  q.step();
  q.cancel();
  assert.equal(q.busy, false);
  assert.equal(q.step(), false);
});

test("sameFrame compares values, not arrays", () => {
  assert.equal(sameFrame(new Float32Array([1, 2]), new Float32Array([1, 2])), true);
  assert.equal(sameFrame(new Float32Array([1, 2]), new Float32Array([1, 3])), false);
  assert.equal(sameFrame(new Float32Array([1, 2]), new Float32Array([1, 2, 3, 4])), false);
  assert.equal(sameFrame(null, new Float32Array([1])), false);
  assert.equal(sameFrame(null, null), true);
});
