// The toolbar: one button per tool (data-tool), the actions (data-action: undo, redo,
// run, stop, export-svg, export-png, copy-code) and the eraser width.
import { h } from "./dom.js";
import { TOOLS } from "./tools/index.js";

export function createToolbar(view) {
  const { model } = view;
  const toolButtons = TOOLS.map((t) =>
    h("button", {
      type: "button",
      class: "ut-btn ut-tool",
      dataset: { tool: t.name },
      title: t.label,
      "aria-label": t.label,
      onclick: () => view.setTool(t.name),
    }, t.icon),
  );
  const action = (name, label, text, fn, extra = "") =>
    h("button", { type: "button", class: `ut-btn ${extra}`, dataset: { action: name }, title: label, "aria-label": label, onclick: fn }, text);
  const buttons = {
    undo: action("undo", "Undo (Ctrl+Z)", "\u21b6", () => view.undo()),
    redo: action("redo", "Redo (Ctrl+Shift+Z)", "\u21b7", () => view.redo()),
    run: action("run", "Run the layout", "\u25b6 Run", () => view.run(), "ut-run"),
    stop: action("stop", "Stop the layout", "\u25a0 Stop", () => view.send({ type: "stop" })),
    svg: action("export-svg", "Export SVG", "SVG \u2913", () => view.send({ type: "export", format: "svg" })),
    png: action("export-png", "Export PNG", "PNG \u2913", () => view.send({ type: "export", format: "png" })),
    code: action("copy-code", "Copy as Python (w.to_code())", "</> Python", () => view.send({ type: "code" })),
  };
  const eraser = h("input", { type: "range", min: "2", max: "80", value: "16", class: "ut-eraser", title: "Eraser width (canvas px)", "aria-label": "Eraser width" });
  const el = h(
    "div",
    { class: "ut-toolbar", role: "toolbar" },
    h("div", { class: "ut-group" }, toolButtons),
    h("label", { class: "ut-eraser-label", title: "Eraser width" }, "\u232b", eraser),
    h("div", { class: "ut-group" }, buttons.undo, buttons.redo),
    h("div", { class: "ut-group" }, buttons.run, buttons.stop),
    h("div", { class: "ut-group" }, buttons.svg, buttons.png, buttons.code),
  );

  function update() {
    const s = view.session;
    for (const b of toolButtons) b.setAttribute("aria-pressed", String(b.dataset.tool === s.tool));
    // aria-disabled, not disabled: a focused button that becomes disabled drops the
    // focus out of the widget, and the next Ctrl+Z would go to the notebook instead.
    buttons.undo.setAttribute("aria-disabled", String(!s.history.canUndo));
    buttons.redo.setAttribute("aria-disabled", String(!s.history.canRedo));
    const running = model.get("status") === "running" && view.kernel() !== "gone";
    buttons.stop.disabled = !running;
    buttons.run.classList.toggle("ut-busy", running);
  }

  return { el, update, eraserWidth: () => Number(eraser.value) || 16 };
}
