// Pointer and keyboard input on the stage: routes drags to the active tool, shows the
// hovered mark's row in a tooltip, and handles Ctrl+Z / Ctrl+Shift+Z / Delete.
import { listen } from "./dom.js";

export function attachInput(view, tools, signal) {
  const { stage, root } = view;
  let active = null; // the tool handling the current drag

  const tool = () => tools[view.session.tool] || tools.select;

  listen(stage.el, "pointerdown", (ev) => {
    if (ev.button !== 0 || active) return;
    ev.preventDefault();
    root.focus({ preventScroll: true });
    stage.el.setPointerCapture(ev.pointerId);
    stage.hideTooltip();
    active = tool();
    if (active.down) active.down(stage.toCanvas(ev), ev);
    view.redraw("over");
  }, signal);

  listen(stage.el, "pointermove", (ev) => {
    const p = stage.toCanvas(ev);
    if (active) {
      if (active.move) active.move(p, ev);
      view.redraw("over");
      return;
    }
    hover(p);
  }, signal);

  const finish = (ev, cancelled) => {
    if (!active) return;
    const t = active;
    active = null;
    if (cancelled) t.cancel && t.cancel();
    else if (t.up) t.up(stage.toCanvas(ev), ev);
    view.redraw("over");
  };
  listen(stage.el, "pointerup", (ev) => finish(ev, false), signal);
  listen(stage.el, "pointercancel", (ev) => finish(ev, true), signal);
  listen(stage.el, "pointerleave", () => !active && stage.hideTooltip(), signal);
  listen(stage.el, "contextmenu", (ev) => active && ev.preventDefault(), signal);

  function hover(p) {
    if (view.session.tool !== "select") return stage.hideTooltip();
    const i = view.hit(p);
    const titles = view.model.get("titles");
    const text = i >= 0 && Array.isArray(titles) && titles[i] != null ? String(titles[i]) : "";
    stage.el.style.cursor = i >= 0 ? "pointer" : "";
    if (text) stage.showTooltip(text, p);
    else stage.hideTooltip();
  }

  listen(root, "keydown", (ev) => {
    const typing = /^(INPUT|TEXTAREA|SELECT)$/.test(ev.target.tagName) || ev.target.isContentEditable;
    const mod = ev.ctrlKey || ev.metaKey;
    const key = ev.key.toLowerCase();
    if (mod && key === "z" && !typing) {
      ev.preventDefault();
      ev.shiftKey ? view.redo() : view.undo();
    } else if (mod && key === "y" && !typing) {
      ev.preventDefault();
      view.redo();
    } else if ((ev.key === "Delete" || ev.key === "Backspace") && !typing) {
      if (tools.select.deletePicked(view.session.picked)) ev.preventDefault();
    } else if (ev.key === "Escape" && active) {
      active.cancel && active.cancel();
      active = null;
      view.redraw("over");
    } else return;
    ev.stopPropagation(); // keep Jupyter's own shortcuts out of it
  }, signal);
}
