// erase: an eraser stroke that cuts a hole in the current layer's container, appended
// to container.cuts as {points, width} (width in canvas px).
import { round2, simplify } from "../geometry.js";
import { addCut } from "../design-edit.js";
import { Stroke } from "./stroke.js";

export function erase(view) {
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
      let pts = simplify(stroke.points, 0.5 * view.unit()).map((q) => [round2(q[0]), round2(q[1])]);
      if (pts.length === 1) pts = [pts[0], pts[0]]; // a dab: a round hole
      stroke = null;
      view.commit(addCut(view.design(), view.layer(), { points: pts, width: view.eraserWidth() }));
    },
    cancel() {
      stroke = null;
    },
    preview(ctx) {
      if (stroke) stroke.draw(ctx, { color: "rgba(220, 60, 60, 0.45)", width: view.eraserWidth() });
    },
  };
}
