// Icon marks by name: typing sends {"type": "icons", "query": q} to the kernel, which
// replies {"type": "icons", "query": q, "names": [...]} (at most 30 closest names);
// the names of the latest query are listed as buttons (text only) and a click picks one.
import { h, replaceChildren } from "../dom.js";
import { onModel } from "../model-sync.js";

const DEBOUNCE_MS = 150;

export function createIconSearch(model, signal, onPick) {
  const input = h("input", { type: "search", class: "ut-icon-query", dataset: { role: "icon-query" }, placeholder: "+ icon name\u2026 (fa:apple)",
    "aria-label": "Find an icon mark by name", spellcheck: false, oninput: () => schedule() });
  const results = h("div", { class: "ut-icon-results", dataset: { role: "icon-results" }, "aria-live": "polite" });
  let timer = 0;

  function schedule() {
    clearTimeout(timer);
    timer = setTimeout(() => {
      const query = input.value.trim();
      if (!query) return replaceChildren(results);
      model.send({ type: "icons", query });
    }, DEBOUNCE_MS);
  }

  onModel(model, ["msg:custom"], (msg) => {
    if (!msg || msg.type !== "icons" || msg.query !== input.value.trim()) return; // a stale reply
    const names = Array.isArray(msg.names) ? msg.names.map(String) : [];
    replaceChildren(results, names.length
      ? names.map((name) => h("button", { type: "button", class: "ut-btn ut-small ut-icon-name", dataset: { icon: name }, title: `Add ${name}`,
        onclick: () => {
          onPick(name);
          input.value = "";
          replaceChildren(results);
        } }, name))
      : h("span", { class: "ut-hint", text: `No icon matches \u201c${msg.query}\u201d.` }));
  }, signal);
  signal.addEventListener("abort", () => clearTimeout(timer), { once: true });

  return { el: h("div", { class: "ut-icon-search" }, input, results) };
}
