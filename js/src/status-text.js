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

/** Progress bar settings from {iteration, max_iterations, loss, done}: full once done. */
export function progressBar(p) {
  const it = Number(p && p.iteration) || 0;
  const max = Number(p && p.max_iterations) || 0;
  const done = !!(p && p.done);
  const parts = [];
  if (max) parts.push(`iteration ${it} / ${max}`);
  if (p && p.loss != null && Number.isFinite(Number(p.loss))) parts.push(`loss ${Number(p.loss).toPrecision(4)}`);
  return { max: max || 1, value: done ? max || 1 : Math.min(it, max || 1), hidden: !max, detail: parts.join(" \u00b7 ") };
}
