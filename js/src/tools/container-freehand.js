// container-freehand: a lasso. On release the stroke closes itself (snapping onto its
// start when it ends near it) and becomes the current layer's polygon container.
import { closeStroke, simplify } from "../geometry.js";
import { setContainer } from "../design-edit.js";
import { Stroke } from "./stroke.js";

export function containerFreehand(view) {
  let stroke = null;
  return {
    down(p) {
      stroke = new Stroke(p, view.unit());
    },
    move(p) {
      if (stroke) stroke.add(p);
    },
    up(p) {
      if (!stroke) return;
      stroke.add(p);
      const pts = simplify(stroke.points, 0.75 * view.unit());
      stroke = null;
      const closed = closeStroke(pts, { snap: 16 * view.unit() });
      if (closed) view.commit(setContainer(view.design(), view.layer(), { kind: "polygon", points: closed.points, cuts: [] }));
    },
    cancel() {
      stroke = null;
    },
    preview(ctx, unit) {
      if (stroke) stroke.draw(ctx, { width: 2 * unit, closeHint: true });
    },
  };
}
