// Paints the layers' containers under the marks: a translucent fill and outline per
// layer (image containers as a translucent mask), with eraser cuts punched out.
// Each layer is drawn on a scratch canvas first so a cut removes only its own layer.
import { containerPath, imageBox, layerColor } from "./shapes.js";

export function drawScene(ctx, stage, design, current, images) {
  const canvas = design.canvas;
  const scratch = scratchFor(stage);
  const sctx = scratch.getContext("2d");
  design.layers.forEach((layer, i) => {
    const c = layer.container;
    if (!c || (c.kind === "canvas" && !(c.cuts && c.cuts.length))) {
      if (i === current) outlineCanvas(ctx, canvas, layerColor(i));
      return;
    }
    sctx.setTransform(1, 0, 0, 1, 0, 0);
    sctx.clearRect(0, 0, scratch.width, scratch.height);
    const k = stage.k();
    sctx.setTransform(k, 0, 0, k, 0, 0);
    paintContainer(sctx, c, canvas, layerColor(i), i === current, images);
    paintCuts(sctx, c.cuts);
    ctx.save();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.globalAlpha = i === current ? 1 : 0.55;
    ctx.drawImage(scratch, 0, 0);
    ctx.restore();
  });
}

function scratchFor(stage) {
  const { width, height } = stage.canvases.scene;
  if (!stage.scratch) stage.scratch = document.createElement("canvas");
  if (stage.scratch.width !== width || stage.scratch.height !== height) {
    stage.scratch.width = width;
    stage.scratch.height = height;
  }
  return stage.scratch;
}

function paintContainer(ctx, c, canvas, color, active, images) {
  ctx.lineWidth = active ? 2 : 1;
  ctx.strokeStyle = color;
  ctx.setLineDash(active ? [] : [6, 4]);
  if (c.kind === "image") {
    const img = images.get(c.image);
    const [x, y, w, h] = imageBox(c, canvas);
    if (img) {
      ctx.globalAlpha = 0.35;
      ctx.drawImage(img, x, y, w, h);
      ctx.globalAlpha = 1;
    }
    ctx.strokeRect(x, y, w, h);
    return;
  }
  const path = containerPath(c, canvas);
  if (!path) return;
  ctx.fillStyle = color;
  ctx.globalAlpha = active ? 0.16 : 0.08;
  ctx.fill(path, "evenodd");
  ctx.globalAlpha = 1;
  if (c.kind !== "canvas") ctx.stroke(path);
  ctx.setLineDash([]);
}

/** Eraser strokes: polylines of a given width removed from what is drawn so far. */
function paintCuts(ctx, cuts) {
  if (!Array.isArray(cuts) || !cuts.length) return;
  ctx.save();
  ctx.globalCompositeOperation = "destination-out";
  ctx.lineCap = "round";
  ctx.lineJoin = "round";
  ctx.strokeStyle = "#000";
  for (const cut of cuts) {
    if (!cut || !Array.isArray(cut.points) || !cut.points.length) continue;
    ctx.lineWidth = Math.max(1, Number(cut.width) || 12);
    ctx.beginPath();
    cut.points.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
    if (cut.points.length === 1) ctx.lineTo(cut.points[0][0] + 0.01, cut.points[0][1]);
    ctx.stroke();
  }
  ctx.restore();
}

function outlineCanvas(ctx, canvas, color) {
  ctx.save();
  ctx.strokeStyle = color;
  ctx.globalAlpha = 0.5;
  ctx.setLineDash([4, 4]);
  ctx.lineWidth = 1;
  ctx.strokeRect(0.5, 0.5, canvas[0] - 1, canvas[1] - 1);
  ctx.restore();
}
