// emitter-curve: a freehand stroke fitted to cubic Beziers (3k + 1 control points);
// the handles are then edited with the select tool. Speed, direction and mode of a
// previous curve emitter carry over.
import { fitCurve } from "../bezier.js";
import { setEmitter } from "../design-edit.js";
import { pathLength } from "../geometry.js";
import { strokeTool } from "./stroke.js";

const FIT_TOLERANCE = 4; // screen px

export function emitterCurve(view) {
  return strokeTool(
    view,
    (pts) => {
      if (pathLength(pts) < 8 * view.unit()) return;
      const points = fitCurve(pts, FIT_TOLERANCE * view.unit());
      if (points.length < 4) return;
      const design = view.design();
      const old = design.layers[view.layer()]?.emitter;
      const keep = old && old.kind === "curve" ? old : { speed: 1.0, direction: "along", mode: "free" };
      const emitter = { kind: "curve", points, speed: keep.speed ?? 1.0, direction: keep.direction ?? "along", mode: keep.mode ?? "free" };
      view.commit(setEmitter(design, view.layer(), emitter));
    },
    (unit) => ({ color: "#f28e2b", width: 3 * unit }),
  );
}
