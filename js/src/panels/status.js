// Run status: the status word, a progress bar with iteration / max and the loss, and a
// red banner for the error message (textContent only).
import { h } from "../dom.js";

export function createStatus(model) {
  const word = h("span", { class: "ut-status-word" });
  const bar = h("progress", { class: "ut-progress", max: 1, value: 0 });
  const detail = h("span", { class: "ut-progress-text" });
  const el = h("div", { class: "ut-status", "aria-live": "polite" }, word, bar, detail);
  const banner = h("div", { class: "ut-error", role: "alert", hidden: true });

  function update() {
    const status = String(model.get("status") || "idle");
    word.textContent = status;
    word.dataset.state = status;
    const p = model.get("progress") || {};
    const it = Number(p.iteration) || 0;
    const max = Number(p.max_iterations) || 0;
    bar.max = max || 1;
    bar.value = Math.min(it, max || 1);
    bar.hidden = !max;
    const parts = [];
    if (max) parts.push(`iteration ${it} / ${max}`);
    if (p.loss != null && Number.isFinite(Number(p.loss))) parts.push(`loss ${Number(p.loss).toPrecision(4)}`);
    detail.textContent = parts.join(" \u00b7 ");
    const error = model.get("error");
    banner.textContent = error ? String(error) : "";
    banner.hidden = !error;
  }

  return { el, banner, update };
}
