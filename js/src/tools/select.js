// select: drag emitter handles, forces and containers of the current layer (Delete or
// Backspace removes the picked one); click a mark to select it (Shift, Ctrl or Cmd toggles); drag on
// empty space to lasso-select marks. Drags show a draft design and commit once on release.
// After a run, dragging a mark pins it where it is dropped (a "pin" message: the kernel
// pins the rows and lays out); Shift-dragging a selected mark moves and pins the whole selection.
// While the mark is dragged its position goes to the kernel at most every DRAG_MS ("drag"
// messages): the kernel pins it there and reflows, so the marks around it move aside live.
// A point force dragged after a run goes the same way ("force" messages): the kernel moves
// it and lays out warm, so the marks follow it live; the drop commits the design (one undo
// step) and sends the last message, `final`, which lays out in full.
import { clone, removeForce, setContainer, setEmitter, translateContainer, updateLayer } from "../design-edit.js";
import { angleDeg, closeStroke, dist, distToPolyline, round2 } from "../geometry.js";
import { containerOutline, containerPath, directionArrow, insideContainer } from "../shapes.js";
import { Stroke } from "./stroke.js";
import { drawPin } from "../draw-overlay.js";
import { throttle } from "../throttle.js";

export const DRAG_MS = 100; // the most often a dragged mark's position goes to the kernel

/** Shift-, Ctrl- or Cmd-click adds to (toggles in) the selection. */
const additive = (ev) => !!(ev.shiftKey || ev.ctrlKey || ev.metaKey);
const rp = (p) => [round2(p[0]), round2(p[1])];

export function select(view) {
  let grab = null; // {kind, index, start, design}
  let lasso = null;
  let drag = null; // a mark drag: {index, indices, from: [[unit, x, y]] where they were, start, at, moved, additive}
  const live = throttle((d, p) => send("drag", d, p), DRAG_MS);
  const liveForce = throttle((g, p) => sendForce(g, p, false), DRAG_MS);

  function find(p, design, li) {
    const layer = design.layers[li];
    if (!layer) return null;
    const r = 8 * view.unit();
    const e = layer.emitter;
    if (e && e.kind === "curve" && Array.isArray(e.points)) {
      const j = nearest(e.points, p, r);
      if (j >= 0) return { kind: "emitter", index: j };
    }
    const forces = layer.forces || [];
    for (let k = forces.length - 1; k >= 0; k--) {
      const f = forces[k];
      if (f.kind === "point" && dist([f.x, f.y], p) <= r) return { kind: "force", index: k };
      if (f.kind === "direction" && dist(directionArrow(layer, design.canvas, f.angle).to, p) <= 1.5 * r) {
        return { kind: "force", index: k, direction: true };
      }
    }
    if (view.hit(p) >= 0) return { kind: "mark", index: view.hit(p) };
    const c = layer.container;
    if (c && c.kind !== "canvas" && (nearOutline(c, p, design.canvas, 6 * view.unit()) || (!view.hasFrame() && insideContainer(c, p, design.canvas, view.hitContext())))) {
      return { kind: "container", index: 0 };
    }
    return null;
  }

  function nearOutline(c, p, canvas, tol) {
    const pts = containerOutline(c, canvas);
    if (pts) return distToPolyline(p, pts, true) <= tol;
    const ctx = view.hitContext();
    const path = containerPath(c, canvas);
    if (!path || !ctx) return false;
    ctx.save();
    ctx.lineWidth = 2 * tol;
    const hit = ctx.isPointInStroke(path, p[0], p[1]);
    ctx.restore();
    return hit;
  }

  function dragged(p) {
    const { kind, index, start, design } = grab;
    const li = view.layer();
    if (kind === "container") {
      const [dx, dy] = [round2(p[0] - start[0]), round2(p[1] - start[1])];
      return updateLayer(design, li, (l) => void (l.container = translateContainer(l.container, dx, dy, design.canvas)));
    }
    if (kind === "emitter") {
      return updateLayer(design, li, (l) => {
        const pts = l.emitter.points;
        const d = [p[0] - pts[index][0], p[1] - pts[index][1]];
        const moved = index % 3 === 0 ? [index - 1, index, index + 1] : [index];
        for (const j of moved) if (pts[j]) pts[j] = rp([pts[j][0] + d[0], pts[j][1] + d[1]]);
      });
    }
    return updateLayer(design, li, (l) => {
      const f = l.forces[index];
      if (f.kind === "point") Object.assign(f, { x: round2(p[0]), y: round2(p[1]) });
      else f.angle = angleDeg(directionArrow(l, design.canvas, f.angle).from, p);
    });
  }

  return {
    down(p, ev) {
      const design = view.design();
      const found = find(p, design, view.layer());
      if (found && found.kind === "mark") {
        view.pick(null);
        const sel = view.selected();
        const indices = ev.shiftKey && sel.has(found.index) ? [...sel] : [found.index];
        const frame = view.frame();
        const from = indices.filter((i) => frame && 4 * i + 1 < frame.length).map((i) => [i, frame[4 * i], frame[4 * i + 1]]);
        drag = { index: found.index, indices, from, start: p, at: p, moved: false, additive: additive(ev) };
        return;
      }
      if (found) {
        view.pick({ kind: found.kind, index: found.index });
        grab = { ...found, start: p, design: clone(design), moved: false, layer: view.layer() };
        // a point force dragged over a shown layout moves the marks live
        const force = found.kind === "force" && !found.direction && design.layers[grab.layer].forces[found.index];
        grab.live = !!force && view.hasFrame() && view.model.get("status") !== "running";
        if (grab.live) grab.from = [force.x, force.y];
        return;
      }
      view.pick(null);
      lasso = new Stroke(p, view.unit());
      lasso.shift = additive(ev);
    },
    move(p) {
      if (drag) {
        if (!drag.moved && (dist(p, drag.start) < 2 * view.unit() || view.model.get("status") === "running")) return;
        drag.moved = true;
        drag.at = p;
        live(drag, p);
      } else if (grab) {
        if (!grab.moved && dist(p, grab.start) < 2 * view.unit()) return;
        grab.moved = true;
        view.setDraft(dragged(p));
        if (grab.live) liveForce(grab, p);
      } else if (lasso) lasso.add(p);
    },
    up(p) {
      if (drag) {
        live.cancel(); // the drop's pin is the last word
        if (drag.moved) send("pin", drag, p);
        else view.toggleSelect([drag.index], drag.additive);
        drag = null;
      } else if (grab) {
        liveForce.cancel(); // the drop's message is the last word
        // undo returns to the design before the drag (the kernel moved the force along the way)
        if (grab.moved) view.commit(dragged(p), grab.design);
        view.setDraft(null);
        if (grab.moved && grab.live) sendForce(grab, p, true);
        grab = null;
      } else if (lasso) {
        lasso.add(p);
        const closed = closeStroke(lasso.points, { snap: 0, minArea: 4 });
        view.toggleSelect(closed ? view.marksInPolygon(closed.points) : [], lasso.shift);
        lasso = null;
      }
    },
    cancel() {
      live.cancel();
      liveForce.cancel();
      if (grab && grab.moved && grab.live) sendForce(grab, grab.from, true); // back where it was
      if (grab) view.setDraft(null);
      grab = lasso = drag = null;
    },
    /** Delete or Backspace: removes the picked container, force or emitter. */
    deletePicked(picked) {
      if (!picked) return false;
      const design = view.design();
      const li = view.layer();
      if (picked.kind === "container") view.commit(setContainer(design, li, null));
      else if (picked.kind === "force") view.commit(removeForce(design, li, picked.index));
      else if (picked.kind === "emitter") view.commit(setEmitter(design, li, null));
      else return false;
      view.pick(null);
      return true;
    },
    preview(ctx, unit) {
      if (drag && drag.moved) return void moved(drag).forEach(([i, x, y]) => ghost(ctx, i, x, y, unit));
      if (!lasso) return;
      lasso.draw(ctx, { color: "rgba(26, 115, 232, 0.9)", width: 1.5 * unit, closeHint: true });
    },
  };

  /** [unit, x, y] of each dragged mark at the drag's end `at` (from where it was when the drag
   * began: the live frames already show it pinned along the way). */
  function moved(d, at = d.at) {
    const [dx, dy] = [at[0] - d.start[0], at[1] - d.start[1]];
    return d.from.map(([i, x, y]) => [i, round2(x + dx), round2(y + dy)]);
  }

  /** A "drag" (live) or "pin" (drop) message: the dragged marks at the drag's end `p`. */
  function send(type, d, p) {
    const marks = moved(d, p);
    if (marks.length) view.send({ type, units: marks.map((m) => m[0]), x: marks.map((m) => m[1]), y: marks.map((m) => m[2]) });
  }

  /** A "force" message: the grabbed point force at `p`; `final`: the drop (or the drag given up). */
  function sendForce(g, p, final) {
    view.send({ type: "force", layer: g.layer, index: g.index, x: round2(p[0]), y: round2(p[1]), final });
  }

  /** The outline of unit i's box centred on (x, y), with a pin: where it will be pinned. */
  function ghost(ctx, i, x, y, unit) {
    const units = view.units();
    const frame = view.frame();
    if (!units || 4 * i + 3 >= units.length) return;
    const s = frame[4 * i + 3];
    const [w, h] = [units[4 * i + 2] * s, units[4 * i + 3] * s];
    ctx.save();
    ctx.translate(x, y);
    ctx.rotate((frame[4 * i + 2] * Math.PI) / 180);
    ctx.setLineDash([4 * unit, 3 * unit]);
    ctx.strokeStyle = "rgba(26, 115, 232, 0.9)";
    ctx.lineWidth = 1.5 * unit;
    ctx.strokeRect(-w / 2, -h / 2, w, h);
    ctx.restore();
    drawPin(ctx, x, y, unit);
  }
}

function nearest(points, p, r) {
  let best = -1;
  let bestD = r;
  points.forEach((q, j) => {
    const d = dist(q, p);
    if (d <= bestD) [best, bestD] = [j, d];
  });
  return best;
}
