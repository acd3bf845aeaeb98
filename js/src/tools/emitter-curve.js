// emitter-curve: a freehand stroke fitted to cubic Beziers (3k + 1 control points);
// the handles are then edited with the select tool. Speed, direction and mode of a
// previous curve emitter carry over.
import { fitCurve } from "../bezier.js";
import { setEmitter } from "../design-edit.js";
import { pathLength } from "../geometry.js";
import { Stroke } from "./stroke.js";

const FIT_TOLERANCE = 4; // screen px

export function emitterCurve(view) {
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
      const pts = stroke.points;
      stroke = null;
      if (pathLength(pts) < 8 * view.unit()) return;
      const points = fitCurve(pts, FIT_TOLERANCE * view.unit());
      if (points.length < 4) return;
      const design = view.design();
      const old = design.layers[view.layer()]?.emitter;
      const keep = old && old.kind === "curve" ? old : { speed: 1.0, direction: "along", mode: "free" };
      const emitter = { kind: "curve", points, speed: keep.speed ?? 1.0, direction: keep.direction ?? "along", mode: keep.mode ?? "free" };
      view.commit(setEmitter(design, view.layer(), emitter));
    },
    cancel() {
      stroke = null;
    },
    preview(ctx, unit) {
      if (stroke) stroke.draw(ctx, { color: "#f28e2b", width: 3 * unit });
    },
  };
}
