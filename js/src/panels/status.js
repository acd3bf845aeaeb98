// Run status: the status word (statusLabel), a progress bar with iteration / max and the
// loss, the error banner (textContent only) with a dismiss button, and a notice about the
// kernel: "waiting" while Run gets no answer (a busy kernel queues it), "gone" once a
// message cannot be sent or the model's comm closed (a restarted or dead kernel, or a
// widget restored from saved state). Sending never throws.
import { h } from "../dom.js";
import { progressBar, statusLabel } from "../status-text.js";

export const NO_ANSWER_MS = 2000;
export const WAITING = "Waiting for the kernel: it is busy (Run starts when it is free), or no kernel runs this notebook's cells yet.";
export const NO_KERNEL = "No kernel is connected to this view (it was restarted, shut down, or never started): run the notebook's cells again to get a live widget.";

export function createStatus(model, signal, onKernel = () => {}) {
  const word = h("span", { class: "ut-status-word" });
  const bar = h("progress", { class: "ut-progress", max: 1, value: 0 });
  const detail = h("span", { class: "ut-progress-text" });
  const el = h("div", { class: "ut-status", "aria-live": "polite" }, word, bar, detail);
  const text = h("span", { class: "ut-error-text", role: "alert" });
  const dismiss = h("button", { type: "button", class: "ut-btn ut-icon", dataset: { action: "dismiss-error" }, title: "Dismiss this error", "aria-label": "Dismiss this error",
    onclick: () => {
      dismissed = String(model.get("error") || "");
      banner.hidden = true;
      send({ type: "dismiss-error" });
    } }, "\u2715");
  const banner = h("div", { class: "ut-error", hidden: true }, text, dismiss);
  const notice = h("div", { class: "ut-notice", dataset: { role: "notice" }, role: "status", hidden: true });
  let dismissed = null; // the error text the user dismissed (shown again only when it changes)
  let timer = 0;
  let kernel = "live"; // "live", "waiting" (asked, no answer yet) or "gone"
  signal.addEventListener("abort", () => clearTimeout(timer), { once: true });

  /** Sends a message; false (and the kernel shown as gone) when it cannot be sent. */
  function send(msg) {
    if (kernel === "gone") return gone(), false;
    try {
      model.send(msg);
      return true;
    } catch {
      gone();
      return false;
    }
  }

  /** Run pressed: ask the kernel, and say it is busy when nothing answers within NO_ANSWER_MS. */
  function run() {
    clearTimeout(timer);
    notice.hidden = true;
    if (!send({ type: "run" })) return;
    timer = setTimeout(() => {
      kernel = "waiting";
      notify(WAITING);
      onKernel();
    }, NO_ANSWER_MS);
  }
  /** The model's comm closed, or a message could not be sent: no kernel is behind the view. */
  function gone() {
    clearTimeout(timer);
    kernel = "gone";
    notify(NO_KERNEL);
    onKernel();
  }
  // the comm's liveness changed (a restart disconnects it): a probe send tells if it is gone
  const probe = () => kernel !== "gone" && send({ type: "ping" });
  const closed = () => gone();
  for (const [event, fn] of [["comm_live_update", probe], ["comm:close", closed], ["destroy", closed]]) {
    model.on(event, fn);
    signal.addEventListener("abort", () => model.off(event, fn), { once: true });
  }
  /** A notice from the kernel ({"type": "notice", "text"}), e.g. an export refused mid-run. */
  function notify(message) {
    notice.textContent = message;
    notice.hidden = false;
  }

  /** A status, progress, frame or error change: the kernel is there. */
  function answered() {
    clearTimeout(timer);
    notice.hidden = true;
    kernel = "live";
  }

  function update() {
    const label = statusLabel(String(model.get("status") || "idle"), !!model.get("stale"), kernel);
    word.textContent = label.text;
    word.dataset.state = label.state;
    const p = progressBar(model.get("progress") || {});
    bar.max = p.max;
    bar.value = p.value;
    bar.hidden = p.hidden;
    detail.textContent = p.detail;
    const error = String(model.get("error") || "");
    if (error !== dismissed) dismissed = null;
    text.textContent = error;
    banner.hidden = !error || error === dismissed;
  }

  return { el, banner, notice, update, run, answered, notify, send, kernel: () => kernel };
}
