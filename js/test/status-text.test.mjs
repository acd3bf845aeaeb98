import { test } from "node:test";
import assert from "node:assert/strict";
import { progressBar, statusLabel } from "../src/status-text.js";

test("stopped and stale layouts say so; running and errors are never called stale", () => {
  assert.deepEqual(statusLabel("stopped", false), { text: "stopped", state: "stopped" });
  assert.deepEqual(statusLabel("done", true), { text: "changed: run again", state: "stale" });
  assert.deepEqual(statusLabel("stopped", true).state, "stale");
  assert.deepEqual(statusLabel("running", true).state, "running");
  assert.deepEqual(statusLabel("error", true).state, "error");
  assert.deepEqual(statusLabel("bogus", false).state, "idle");
});

test("a finished run fills the progress bar", () => {
  assert.deepEqual(progressBar({ iteration: 107, max_iterations: 600, done: true }),
    { max: 600, value: 600, hidden: false, detail: "iteration 107 / 600" });
  assert.equal(progressBar({ iteration: 107, max_iterations: 600 }).value, 107);
  assert.equal(progressBar({}).hidden, true);
  assert.equal(progressBar({ iteration: 3, max_iterations: 10, loss: 0.123456 }).detail, "iteration 3 / 10 \u00b7 loss 0.1235");
});

test("the kernel's state: gone reads no kernel, waiting reads waiting for the kernel", () => {
  assert.deepEqual(statusLabel("running", false, "gone"), { text: "no kernel", state: "gone" });
  assert.deepEqual(statusLabel("idle", false, "waiting"), { text: "waiting for the kernel", state: "waiting" });
  assert.deepEqual(statusLabel("running", false, "waiting").state, "running");
});
