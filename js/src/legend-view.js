// The legend beside the canvas: the `legend` trait's image ({"src": data URL, "width",
// "height"} in canvas px, drawn through <img>, never as markup) placed at
// design.legend.position. Dragging it sets position [x, y] (its top-left corner in
// canvas px, one commit on release); the toggle button sets design.legend.visible.
// Beside the canvas it is drawn at its own size (1 canvas px = 1 CSS px, so its text
// stays as legible as in the export however small the stage is); on the canvas, at the
// chart's scale.
import { h, listen } from "./dom.js";
import { clampCorner, legendSettings, setLegend } from "./legend-place.js";

export function createLegend(view, signal) {
  const { model, stage } = view;
  const img = h("img", { class: "ut-legend", dataset: { role: "legend" }, alt: "legend", draggable: false, hidden: true, title: "Legend: drag to move it" });
  const area = h("div", { class: "ut-canvas-area" }, stage.wrap);
  const toggle = h("button", { type: "button", class: "ut-btn", dataset: { action: "toggle-legend" }, title: "Show or hide the legend", "aria-label": "Show or hide the legend",
    onclick: () => view.commit(setLegend(view.design(), { visible: !legendSettings(view.design()).visible })) }, "Legend");
  let drag = null; // {pointer, start, size, corner, stop} while dragging

  const trait = () => {
    const l = model.get("legend_image");
    return l && typeof l.src === "string" && l.src.startsWith("data:image/") ? l : null;
  };
  /** The legend's size in canvas px. */
  const size = (l) => [Number(l.width) > 0 ? Number(l.width) : img.naturalWidth, Number(l.height) > 0 ? Number(l.height) : img.naturalHeight];

  function place() {
    const l = trait();
    const { visible, position } = legendSettings(view.design());
    toggle.setAttribute("aria-pressed", String(visible));
    // Python sends no legend while it is hidden, so only a visible one can be missing.
    toggle.setAttribute("aria-disabled", String(visible && !l));
    img.hidden = !l || !visible;
    if (!l) return void img.removeAttribute("src");
    if (img.getAttribute("src") !== l.src) img.src = l.src;
    const [w, hgt] = size(l);
    const corner = drag ? drag.corner : Array.isArray(position) ? clampCorner(position, [w, hgt], stage.size) : null;
    const k = corner ? stage.scale : 1;
    img.style.width = w ? `${w * k}px` : "";
    img.style.height = hgt ? `${hgt * k}px` : "";
    if (corner) {
      if (img.parentNode !== stage.el) stage.el.append(img);
      img.style.left = `${corner[0] * k}px`;
      img.style.top = `${corner[1] * k}px`;
      area.dataset.legendSide = "inside";
    } else {
      if (img.parentNode !== area) area.append(img);
      img.style.left = img.style.top = "";
      area.dataset.legendSide = position;
    }
  }

  /** The legend's top-left corner in canvas px, wherever it is shown now. */
  function cornerNow() {
    const r = img.getBoundingClientRect();
    const s = stage.el.getBoundingClientRect();
    return [(r.left - s.left - stage.el.clientLeft) / stage.scale, (r.top - s.top - stage.el.clientTop) / stage.scale];
  }

  // The drag listens on the window: the legend moves into the stage when the drag starts,
  // and an element taken out of the document loses its pointer capture.
  listen(img, "pointerdown", (ev) => {
    const l = trait();
    if (ev.button !== 0 || !l || drag) return;
    ev.preventDefault();
    ev.stopPropagation(); // not a stroke of the current tool
    const start = cornerNow();
    drag = { pointer: [ev.clientX, ev.clientY], start, size: size(l), corner: null, stop: new AbortController() };
    drag.corner = clampCorner(start, drag.size, stage.size);
    // The stage keeps its width while the legend leaves the row beside it (no rescale mid-drag).
    stage.wrap.style.flex = `0 0 ${stage.wrap.clientWidth}px`;
    const opts = { signal: drag.stop.signal };
    window.addEventListener("pointermove", move, opts);
    window.addEventListener("pointerup", () => finish(true), opts);
    window.addEventListener("pointercancel", () => finish(false), opts);
    signal.addEventListener("abort", () => drag && drag.stop.abort(), opts);
    place();
  }, signal);

  function move(ev) {
    const d = [(ev.clientX - drag.pointer[0]) / stage.scale, (ev.clientY - drag.pointer[1]) / stage.scale];
    drag.corner = clampCorner([drag.start[0] + d[0], drag.start[1] + d[1]], drag.size, stage.size);
    place();
  }

  function finish(keep) {
    const { corner, stop } = drag;
    stop.abort();
    drag = null;
    stage.wrap.style.flex = "";
    if (keep) view.commit(setLegend(view.design(), { position: corner }));
    else place();
  }
  listen(img, "load", () => place(), signal);

  return { area, toggle, place };
}
