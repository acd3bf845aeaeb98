// The tool registry: data-tool name -> factory(view) returning pointer handlers
// {down, move, up, cancel, preview}. Every tool edits the current layer.
import { select } from "./select.js";
import { containerFreehand } from "./container-freehand.js";
import { containerShape } from "./container-shape.js";
import { erase } from "./erase.js";
import { emitterGrid } from "./emitter-grid.js";
import { emitterCurve } from "./emitter-curve.js";
import { forceDirection, forcePoint } from "./forces.js";

export const TOOLS = [
  { name: "select", label: "Select", icon: "\u2196", make: select },
  { name: "container-freehand", label: "Container: freehand lasso", icon: "\u270e", make: containerFreehand },
  { name: "container-rect", label: "Container: rectangle", icon: "\u25ad", make: (v) => containerShape(v, "rect") },
  { name: "container-ellipse", label: "Container: ellipse", icon: "\u25ef", make: (v) => containerShape(v, "ellipse") },
  { name: "erase", label: "Eraser: cut a hole in the container", icon: "\u232b", make: erase },
  { name: "emitter-grid", label: "Emitter: grid (click in the container)", icon: "\u25a6", make: emitterGrid },
  { name: "emitter-curve", label: "Emitter: curve (draw a stroke)", icon: "\u223f", make: emitterCurve },
  { name: "force-point", label: "Force: point (click)", icon: "\u25c9", make: forcePoint },
  { name: "force-direction", label: "Force: direction (drag an arrow)", icon: "\u2192", make: forceDirection },
];

export function makeTools(view) {
  return Object.fromEntries(TOOLS.map((t) => [t.name, t.make(view)]));
}
