import { test } from "node:test";
import assert from "node:assert/strict";
import { Recording, Player, BUDGET_BYTES } from "../src/replay.js";
import { lerpFrame } from "../src/frames.js";

/** A frame of `n` units, all at x = t, y = 2t, angle 0, scale 1. */
const frameAt = (t, n = 2) => new Float32Array(Array.from({ length: n }, () => [t, 2 * t, 0, 1]).flat());

test("under the budget every frame is kept, copied, and sampled exactly", () => {
  const rec = new Recording();
  const shared = new Float32Array(8);
  for (let t = 0; t < 5; t++) {
    shared.set(frameAt(t)); // one buffer reused by the sender: the recording must copy
    rec.push(shared);
  }
  assert.equal(rec.length, 5);
  assert.equal(rec.received, 5);
  for (let t = 0; t < 5; t++) assert.deepEqual(Array.from(rec.sample(t)), Array.from(frameAt(t)));
});

test("over the budget every k-th frame stays, evenly spaced, with the first and the latest", () => {
  assert.equal(Math.floor(BUDGET_BYTES / (20000 * 16)), 209, "the budget stated in docs/protocol.md");
  const n = 50, max = 209; // the same count of frames as 20,000 units in 64 MiB, on fewer units
  const budget = max * n * 16;
  const rec = new Recording(budget);
  const total = 1001;
  const frame = new Float32Array(4 * n);
  for (let t = 0; t < total; t++) {
    frame.fill(t);
    rec.push(frame);
    assert.ok(rec.bytes <= budget, `over the budget at frame ${t}: ${rec.bytes} bytes`);
  }
  const idx = rec.kept.map((e) => e.index);
  assert.equal(idx[0], 0);
  assert.equal(idx[idx.length - 1], total - 1, "the latest frame (the final layout) is kept");
  const gaps = new Set(idx.slice(1, -1).map((v, i) => v - idx[i]));
  assert.equal(gaps.size, 1, `kept frames evenly spaced, got gaps ${[...gaps]}`);
  assert.ok(rec.length > max / 2, `the budget is used: ${rec.length} of ${max} frames`);
  assert.equal(rec.sample(total - 1)[0], total - 1);
  assert.equal(rec.sample(1e9)[5], total - 1, "past the end: the final frame");
});

test("a position between kept frames interpolates; angles turn the short way", () => {
  const rec = new Recording(3 * 16); // one unit: three frames fit
  rec.push(new Float32Array([0, 0, 350, 1]));
  rec.push(new Float32Array([10, 20, 10, 2]));
  assert.deepEqual(Array.from(rec.sample(0.5)), [5, 10, 360, 1.5]); // 350 -> 10 through 360, not 180
  assert.deepEqual(Array.from(lerpFrame(new Float32Array(4), [0, 0, 10, 1], [4, 8, 350, 1], 0.25)), [1, 2, 5, 1]);
  for (let t = 2; t < 9; t++) rec.push(new Float32Array([10 * t, 0, 0, 1]));
  const idx = rec.kept.map((e) => e.index);
  assert.deepEqual(idx, [0, 4, 8]);
  assert.equal(rec.sample(6)[0], 60, "halfway between frames 4 and 8");
});

test("a frame of another unit count starts a new recording; clear empties it", () => {
  const rec = new Recording();
  rec.push(frameAt(1, 2));
  rec.push(frameAt(2, 2));
  rec.push(frameAt(3, 3));
  assert.equal(rec.length, 1);
  assert.equal(rec.received, 1);
  rec.clear();
  assert.equal(rec.sample(0), null);
  rec.push(null);
  assert.equal(rec.length, 0);
  assert.throws(() => new Recording(0), /budgetBytes must be a positive number of bytes, got 0/);
});

test("play starts from the first frame, advances at the stream's rate and stops on the final frame", () => {
  const rec = new Recording();
  for (let t = 0; t < 31; t++) rec.push(frameAt(t));
  const p = new Player(rec, { fps: 30, maxSeconds: 10 });
  assert.equal(p.frame(), null, "live frames until a replay");
  p.play(1000);
  assert.equal(p.frame()[0], 0, "from the first frame");
  assert.equal(p.step(1500), true);
  assert.equal(p.position, 15);
  assert.equal(p.frame()[0], 15);
  p.step(5000);
  assert.equal(p.playing, false, "stops at the end");
  assert.deepEqual(Array.from(p.frame()), Array.from(frameAt(30)), "the end is the final frame");
  assert.equal(p.step(6000), false);
  p.play(7000);
  assert.equal(p.position, 0, "played again from the end: from the first frame");
});

test("pause keeps the position, seek clamps and pauses, stop returns to the live frames", () => {
  const rec = new Recording();
  for (let t = 0; t < 11; t++) rec.push(frameAt(t));
  const p = new Player(rec, { fps: 10 });
  p.play(0);
  p.step(300);
  p.pause();
  assert.equal(p.step(900), false);
  assert.equal(p.position, 3);
  p.play(1000);
  p.step(1100);
  assert.equal(p.position, 4, "resumes where it paused");
  p.seek(99);
  assert.equal(p.playing, false);
  assert.equal(p.position, 10);
  p.seek(-5);
  assert.equal(p.frame()[0], 0);
  p.stop();
  assert.equal(p.frame(), null);
});

test("a long run replays within maxSeconds", () => {
  const rec = new Recording();
  for (let t = 0; t < 1001; t++) rec.push(frameAt(t, 1));
  const p = new Player(rec, { fps: 30, maxSeconds: 10 });
  assert.equal(p.rate, 100);
  p.play(0);
  p.step(10000);
  assert.equal(p.playing, false);
  assert.equal(p.frame()[0], 1000);
});
