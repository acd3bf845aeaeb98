import { test } from "node:test";
import assert from "node:assert/strict";
import { decodeFloat32, decodeUint8, FrameInterpolator, angleDelta } from "../src/frames.js";

test("a DataView over float32 bytes decodes to an (N, 4) Float32Array", () => {
  const src = new Float32Array([1, 2, 3, 4, 5, 6, 7, 8]);
  const out = decodeFloat32(new DataView(src.buffer));
  assert.equal(out.length, 8);
  assert.deepEqual(Array.from(out), [1, 2, 3, 4, 5, 6, 7, 8]);
});

test("an aligned byteOffset is honoured without a copy", () => {
  const src = new Float32Array([9, 9, 1, 2, 3, 4]);
  const view = new DataView(src.buffer, 8, 16);
  const out = decodeFloat32(view);
  assert.deepEqual(Array.from(out), [1, 2, 3, 4]);
  assert.equal(out.buffer, src.buffer);
});

test("an unaligned byteOffset is copied", () => {
  const bytes = new Uint8Array(3 + 16);
  bytes.set(new Uint8Array(new Float32Array([1.5, -2, 3, 400]).buffer), 3);
  const out = decodeFloat32(new DataView(bytes.buffer, 3, 16));
  assert.deepEqual(Array.from(out), [1.5, -2, 3, 400]);
});

test("empty or missing bytes decode to null; trailing partial rows are dropped", () => {
  assert.equal(decodeFloat32(null), null);
  assert.equal(decodeFloat32(new DataView(new ArrayBuffer(0))), null);
  assert.equal(decodeFloat32(new DataView(new ArrayBuffer(20))).length, 4);
  assert.deepEqual(Array.from(decodeUint8(new DataView(new Uint8Array([1, 2, 3, 4]).buffer))), [1, 2, 3, 4]);
});

test("interpolation runs from the frame on screen to the latest one", () => {
  const it = new FrameInterpolator();
  it.push(new Float32Array([0, 0, 350, 1]), 0);
  assert.equal(it.step(0), true);
  assert.deepEqual(Array.from(it.current), [0, 0, 350, 1]);
  it.push(new Float32Array([100, 50, 10, 2]), 100); // duration becomes about 0.7*33 + 0.3*100
  it.step(100 + it.duration / 2);
  const [x, y, a, s] = it.current;
  assert.ok(Math.abs(x - 50) < 1e-3 && Math.abs(y - 25) < 1e-3 && Math.abs(s - 1.5) < 1e-3);
  assert.ok(Math.abs(a - 360) < 1e-3, `angles take the short way round: ${a}`);
  assert.equal(it.step(1000), true);
  assert.deepEqual(Array.from(it.current), [100, 50, 10, 2]);
  assert.equal(it.step(1100), false, "settled: nothing to repaint");
  assert.equal(angleDelta(350, 10), 20);
});
