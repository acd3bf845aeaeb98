// What the status line says, from the status, stale and progress traits (pure).

/**
 * The status word and its state: "running", "done", "stopped", "error", "idle"; a layout
 * made before the last edit ("stale") reads "changed: run again" instead of done/stopped;
 * `kernel` "gone" reads "no kernel" (a run it showed is not going on), "waiting" (Run sent,
 * no answer yet) "waiting for the kernel".
 */
export function statusLabel(status, stale, kernel = "live") {
  const s = ["idle", "running", "done", "stopped", "error"].includes(status) ? status : "idle";
  if (kernel === "gone") return { text: "no kernel", state: "gone" };
  if (kernel === "waiting" && s !== "running") return { text: "waiting for the kernel", state: "waiting" };
  if (stale && s !== "running" && s !== "error") return { text: "changed: run again", state: "stale" };
  return { text: s, state: s };
}

const PHASES = { settle: "settling", polish: "polishing" };

/**
 * Progress bar settings from {iteration, max_iterations, phase, seconds, done, stopped}: full
 * once done. The detail says what the run is doing ("settling", "polishing") or how long it
 * took ("done in 2.1 s"), and the iteration: words a user can act on, not the loss.
 */
export function progressBar(p) {
  const it = Number(p && p.iteration) || 0;
  const max = Number(p && p.max_iterations) || 0;
  const done = !!(p && p.done);
  const seconds = Number(p && p.seconds);
  const parts = [];
  if (done && Number.isFinite(seconds)) {
    parts.push(`${p.stopped ? "stopped after" : "done in"} ${seconds.toFixed(1)} s`);
  } else if (!done && p && PHASES[p.phase]) {
    parts.push(PHASES[p.phase]);
  }
  if (max) parts.push(`iteration ${it} / ${max}`);
  return { max: max || 1, value: done ? max || 1 : Math.min(it, max || 1), hidden: !max, detail: parts.join(" \u00b7 ") };
}
