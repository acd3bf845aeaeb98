// container-rect and container-ellipse: drag a box from corner to corner.
import { boxFromCorners, round2 } from "../geometry.js";
import { setContainer } from "../design-edit.js";

export function containerShape(view, kind) {
  let start = null;
  let end = null;
  const toContainer = () => {
    const b = boxFromCorners(start, end);
    if (kind === "rect") return { kind: "rect", x: round2(b.x), y: round2(b.y), w: round2(b.w), h: round2(b.h), cuts: [] };
    return {
      kind: "ellipse",
      cx: round2(b.x + b.w / 2),
      cy: round2(b.y + b.h / 2),
      rx: round2(b.w / 2),
      ry: round2(b.h / 2),
      cuts: [],
    };
  };
  return {
    down(p) {
      start = end = p;
    },
    move(p) {
      if (start) end = p;
    },
    up(p) {
      if (!start) return;
      end = p;
      const b = boxFromCorners(start, end);
      const big = b.w >= 4 * view.unit() && b.h >= 4 * view.unit();
      if (big) view.commit(setContainer(view.design(), view.layer(), toContainer()));
      start = end = null;
    },
    cancel() {
      start = end = null;
    },
    preview(ctx, unit) {
      if (!start) return;
      const c = toContainer();
      ctx.strokeStyle = "#1a73e8";
      ctx.lineWidth = 2 * unit;
      ctx.setLineDash([6 * unit, 4 * unit]);
      ctx.beginPath();
      if (kind === "rect") ctx.rect(c.x, c.y, c.w, c.h);
      else ctx.ellipse(c.cx, c.cy, c.rx, c.ry, 0, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.setLineDash([]);
    },
  };
}
