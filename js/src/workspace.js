// The room around the canvas: the title and caption shown live (design.title,
// design.caption, as text), panels that fold (each panel's header, and the whole side
// column), and whether the editing guides (emitters, forces) are drawn.
import { h } from "./dom.js";

/** Tools that edit the design; with any other (Select) the guides hide once marks are drawn. */
const editing = (tool) => typeof tool === "string" && tool !== "select";

/**
 * Whether the overlay draws emitters and forces: always before a layout is drawn,
 * while an editing tool is active, or when the user asked for them (`shown`).
 */
export function guidesVisible({ tool, hasFrame, shown }) {
  return !hasFrame || editing(tool) || !!shown;
}

/** Title above and caption below the stage; `update(design)` sets their text. */
export function createPageText(wrap) {
  const title = h("div", { class: "ut-title", dataset: { role: "title" }, hidden: true });
  const caption = h("div", { class: "ut-caption", dataset: { role: "caption" }, hidden: true });
  wrap.prepend(title);
  wrap.append(caption);
  const set = (el, v) => {
    const text = typeof v === "string" ? v : "";
    el.textContent = text;
    el.hidden = !text;
  };
  return { update: (design) => (set(title, design.title), set(caption, design.caption)) };
}

/** A fold button in each panel's header: the panel shows its header only while folded. */
export function foldPanels(panels) {
  for (const p of panels) {
    const header = p.el.querySelector("header");
    const name = header.querySelector("h3").textContent;
    const btn = h("button", {
      type: "button", class: "ut-btn ut-icon ut-fold", dataset: { action: "fold" }, "aria-expanded": "true",
      title: `Fold or unfold ${name}`, "aria-label": `Fold or unfold ${name}`,
      onclick: () => {
        const folded = p.el.classList.toggle("ut-folded");
        btn.setAttribute("aria-expanded", String(!folded));
      },
    }, "\u25be");
    header.prepend(btn);
  }
}

/** A button that flips between pressed and not (`aria-pressed`); `onChange(pressed)` after each press. */
function toggleButton(action, text, label, pressed, onChange) {
  const btn = h("button", {
    type: "button", class: "ut-btn", dataset: { action }, "aria-pressed": String(pressed),
    title: label, "aria-label": label,
    onclick: () => {
      pressed = !pressed;
      btn.setAttribute("aria-pressed", String(pressed));
      onChange(pressed);
    },
  }, text);
  return btn;
}

/** Top-bar toggles: the side panels, and the guides (emitters, forces) over finished marks. */
export function createToggles(side, onGuides) {
  let guides = false;
  const panels = toggleButton("toggle-panels", "Panels", "Show or hide the panels", !side.hidden,
    (shown) => { side.hidden = !shown; });
  const guide = toggleButton("toggle-guides", "Guides", "Show the emitters and forces over the marks", guides,
    (shown) => { guides = shown; onGuides(); });
  return { panels, guide, guidesShown: () => guides };
}
