// Run status: the status word (statusLabel), a progress bar with iteration / max and the
// loss, the error banner (textContent only) with a dismiss button, and a notice when
// Run gets no answer: a widget restored from saved state has no kernel behind it.
import { h } from "../dom.js";
import { progressBar, statusLabel } from "../status-text.js";

export const NO_ANSWER_MS = 2000;
export const NO_KERNEL = "Run needs a running kernel: nothing answered. Start the kernel and run the notebook's cells, then press Run again.";

export function createStatus(model, signal) {
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
  signal.addEventListener("abort", () => clearTimeout(timer), { once: true });

  /** Sends a message; false when there is no kernel connection to send it on. */
  function send(msg) {
    try {
      model.send(msg);
      return true;
    } catch {
      return false;
    }
  }

  /** Run pressed: ask the kernel, and say so when nothing answers within NO_ANSWER_MS. */
  function run() {
    clearTimeout(timer);
    notice.hidden = true;
    if (!send({ type: "run" })) return showNotice();
    timer = setTimeout(showNotice, NO_ANSWER_MS);
  }
  function showNotice() {
    notify(NO_KERNEL);
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
  }

  function update() {
    const label = statusLabel(String(model.get("status") || "idle"), !!model.get("stale"));
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

  return { el, banner, notice, update, run, answered, notify };
}
