// emitter-grid: a click inside the current layer's container sets a grid emitter.
import { setEmitter } from "../design-edit.js";
import { insideContainer } from "../shapes.js";

export function emitterGrid(view) {
  return {
    up(p) {
      const design = view.design();
      const layer = design.layers[view.layer()];
      if (!layer || !insideContainer(layer.container, p, design.canvas, view.hitContext())) return;
      const old = layer.emitter || {};
      const emitter = { kind: "grid", speed: old.speed ?? 1.0, direction: old.kind === "grid" ? old.direction ?? null : null };
      view.commit(setEmitter(design, view.layer(), emitter));
    },
  };
}
