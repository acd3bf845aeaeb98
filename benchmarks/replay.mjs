// The replay's recording: per received frame, the cost of keeping it (Recording.push) and
// of drawing-side sampling (Player.frame, interpolated), and what stays in memory, for a
// run of 1,000 frames of 1,000 and 20,000 upright units (angle 0: layouts without rotation). Prints a table; writes nothing.
//
//     node benchmarks/replay.mjs [frames]
import { BUDGET_BYTES, Player, Recording } from "../js/src/replay.js";

const frames = Number(process.argv[2]) || 1000;
console.log(`budget ${BUDGET_BYTES / 2 ** 20} MiB, ${frames} frames received`);
console.log("units   push ms/frame   sample ms/frame   kept   MiB    every k-th");
for (const n of [1000, 20000]) {
  const rec = new Recording();
  const frame = new Float32Array(4 * n);
  let pushMs = 0;
  for (let i = 0; i < frames; i++) {
    for (let u = 0; u < n; u++) { // upright marks moving
      frame[4 * u] = u + i;
      frame[4 * u + 1] = i;
      frame[4 * u + 3] = 1;
    }
    const t = performance.now();
    rec.push(frame);
    pushMs += performance.now() - t;
  }
  const push = pushMs / frames;
  const player = new Player(rec);
  const samples = 200;
  const t0 = performance.now();
  for (let i = 0; i < samples; i++) {
    player.seek(((i + 0.5) / samples) * player.end);
    player.frame();
  }
  const sample = (performance.now() - t0) / samples;
  console.log([String(n).padEnd(7), push.toFixed(3).padEnd(15), sample.toFixed(3).padEnd(17),
    String(rec.length).padEnd(6), (rec.bytes / 2 ** 20).toFixed(1).padEnd(6), rec.stride].join(" "));
}
