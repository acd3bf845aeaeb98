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
  assert.equal(progressBar({ iteration: 3, max_iterations: 10, loss: 0.123456 }).detail, "iteration 3 / 10");
});

test("the detail says what the run does and how long it took, never the loss", () => {
  assert.equal(progressBar({ iteration: 3, max_iterations: 10, loss: 0.1, phase: "settle" }).detail,
    "settling \u00b7 iteration 3 / 10");
  assert.equal(progressBar({ iteration: 9, max_iterations: 10, phase: "polish" }).detail,
    "polishing \u00b7 iteration 9 / 10");
  assert.equal(progressBar({ iteration: 9, max_iterations: 10, phase: "polish", seconds: 2.14, done: true }).detail,
    "done in 2.1 s \u00b7 iteration 9 / 10");
  assert.equal(progressBar({ iteration: 4, max_iterations: 10, seconds: 0.5, done: true, stopped: true }).detail,
    "stopped after 0.5 s \u00b7 iteration 4 / 10");
});

test("the kernel's state: gone reads no kernel, waiting reads waiting for the kernel", () => {
  assert.deepEqual(statusLabel("running", false, "gone"), { text: "no kernel", state: "gone" });
  assert.deepEqual(statusLabel("idle", false, "waiting"), { text: "waiting for the kernel", state: "waiting" });
  assert.deepEqual(statusLabel("running", false, "waiting").state, "running");
});
