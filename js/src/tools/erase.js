// erase: an eraser stroke that cuts a hole in the current layer's container, appended
// to container.cuts as {points, width} (width in canvas px).
import { round2, simplify } from "../geometry.js";
import { addCut } from "../design-edit.js";
import { strokeTool } from "./stroke.js";

export function erase(view) {
  return strokeTool(
    view,
    (stroke) => {
      let pts = simplify(stroke, 0.5 * view.unit()).map((q) => [round2(q[0]), round2(q[1])]);
      if (pts.length === 1) pts = [pts[0], pts[0]]; // a dab: a round hole
      view.commit(addCut(view.design(), view.layer(), { points: pts, width: view.eraserWidth() }));
    },
    () => ({ color: "rgba(220, 60, 60, 0.45)", width: view.eraserWidth() }),
  );
}
