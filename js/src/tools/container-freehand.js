// container-freehand: a lasso. On release the stroke closes itself (snapping onto its
// start when it ends near it) and becomes the current layer's polygon container.
import { closeStroke, simplify } from "../geometry.js";
import { setContainer } from "../design-edit.js";
import { strokeTool } from "./stroke.js";

export function containerFreehand(view) {
  return strokeTool(
    view,
    (stroke) => {
      const pts = simplify(stroke, 0.75 * view.unit());
      const closed = closeStroke(pts, { snap: 16 * view.unit() });
      if (closed) view.commit(setContainer(view.design(), view.layer(), { kind: "polygon", points: closed.points, cuts: [] }));
    },
    (unit) => ({ width: 2 * unit, closeHint: true }),
  );
}
