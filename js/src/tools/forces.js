// force-point: each click adds an attracting point. force-direction: drag an arrow;
// a layer has at most one, a new one replaces it.
import { addPointForce, setDirectionForce } from "../design-edit.js";
import { angleDeg, dist, round2 } from "../geometry.js";
import { drawArrow } from "../draw-overlay.js";

export function forcePoint(view) {
  return {
    up(p) {
      view.commit(addPointForce(view.design(), view.layer(), round2(p[0]), round2(p[1])));
    },
  };
}

export function forceDirection(view) {
  let from = null;
  let to = null;
  return {
    down(p) {
      from = to = p;
    },
    move(p) {
      if (from) to = p;
    },
    up(p) {
      if (!from) return;
      to = p;
      if (dist(from, to) >= 8 * view.unit()) view.commit(setDirectionForce(view.design(), view.layer(), angleDeg(from, to)));
      from = to = null;
    },
    cancel() {
      from = to = null;
    },
    preview(ctx, unit) {
      if (from && dist(from, to) > 0) drawArrow(ctx, from, to, "#1a73e8", false, unit);
    },
  };
}
