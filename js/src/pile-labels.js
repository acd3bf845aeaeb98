// The piles' labels over the stage: the `pile_labels` trait ([{text, x, y, anchor}],
// baseline points in canvas px, laid out by Python as in the export) drawn as SVG
// <text class="pile-label"> in an <svg> spanning the canvas (text only, never markup).
const NS = "http://www.w3.org/2000/svg";
const ANCHORS = new Set(["start", "middle", "end"]);

export function createPileLabels(stage) {
  const svg = document.createElementNS(NS, "svg");
  svg.setAttribute("class", "ut-pile-labels");
  svg.setAttribute("preserveAspectRatio", "none");
  svg.setAttribute("aria-hidden", "true");

  /** Draws `labels` on a canvas of `size` [w, h] px; with none, the <svg> leaves the stage. */
  function update(labels, size) {
    const shown = Array.isArray(labels) ? labels : [];
    svg.replaceChildren();
    if (!shown.length) return void svg.remove();
    if (svg.parentNode !== stage.el) stage.el.insertBefore(svg, stage.tooltip);
    svg.setAttribute("viewBox", `0 0 ${Number(size[0]) || 1} ${Number(size[1]) || 1}`);
    for (const l of shown) {
      if (!l || !Number.isFinite(Number(l.x)) || !Number.isFinite(Number(l.y))) continue;
      const text = document.createElementNS(NS, "text");
      text.setAttribute("class", "pile-label");
      text.setAttribute("x", String(Number(l.x)));
      text.setAttribute("y", String(Number(l.y)));
      text.setAttribute("font-size", "12");
      text.setAttribute("font-family", "sans-serif");
      text.setAttribute("fill", "#222");
      text.setAttribute("text-anchor", ANCHORS.has(l.anchor) ? l.anchor : "middle");
      text.textContent = String(l.text ?? "");
      svg.append(text);
    }
  }
  return { el: svg, update };
}
