// A freehand stroke being drawn: points in canvas px, thinned to >= 1 screen px apart.
import { polyline } from "../draw-overlay.js";

export class Stroke {
  constructor(p, minStep = 1) {
    this.points = [p];
    this.minStep = minStep;
  }

  add(p) {
    const last = this.points[this.points.length - 1];
    if (Math.hypot(p[0] - last[0], p[1] - last[1]) >= this.minStep) this.points.push(p);
  }

  draw(ctx, { color = "#1a73e8", width = 2, closeHint = false } = {}) {
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.lineCap = ctx.lineJoin = "round";
    polyline(ctx, this.points);
    ctx.stroke();
    if (closeHint && this.points.length > 2) {
      const a = this.points[this.points.length - 1];
      const b = this.points[0];
      ctx.setLineDash([4 * (width / 2), 4 * (width / 2)]);
      polyline(ctx, [a, b]);
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }
}

// A tool that records one freehand stroke per press: `finish(points)` gets the stroke's
// points (canvas px) on release; `look(unit)` gives the preview's draw options.
export function strokeTool(view, finish, look) {
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
      const points = stroke.points;
      stroke = null;
      finish(points);
    },
    cancel() {
      stroke = null;
    },
    preview(ctx, unit) {
      if (stroke) stroke.draw(ctx, look(unit));
    },
  };
}
