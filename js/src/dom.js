// A tiny element builder. Strings from the model only ever become text nodes or
// textContent, never markup.

/**
 * h("button", {class: "x", dataset: {tool: "select"}, onclick: fn, text: "Run"}, ...children)
 * Props: class, text (textContent), dataset, style (object), on<event> (listener),
 * anything else as a property when the element has it, else as an attribute.
 */
export function h(tag, props = {}, ...children) {
  const el = document.createElement(tag);
  for (const [key, value] of Object.entries(props)) {
    if (value == null || value === false) continue;
    if (key === "class") el.className = value;
    else if (key === "text") el.textContent = String(value);
    else if (key === "dataset") Object.assign(el.dataset, value);
    else if (key === "style") Object.assign(el.style, value);
    else if (key.startsWith("on") && typeof value === "function") el.addEventListener(key.slice(2), value);
    else if (key in el && typeof value !== "string") el[key] = value;
    else el.setAttribute(key, value === true ? "" : String(value));
  }
  for (const child of children.flat()) {
    if (child == null || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return el;
}

/** Replaces all children of el. */
export function replaceChildren(el, ...children) {
  el.replaceChildren(...children.flat().filter((c) => c != null && c !== false));
}

/** A labelled form row: <label><span>text</span>control</label>. */
export const row = (label, control, extra = {}) =>
  h("label", { class: "ut-row", ...extra }, h("span", { class: "ut-label", text: label }), control);

/** Adds a listener that goes away when `signal` aborts. */
export function listen(target, type, fn, signal, options = {}) {
  target.addEventListener(type, fn, { ...options, signal });
}
