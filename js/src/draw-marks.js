// Paints the marks: one setTransform + one drawImage per mark, in unit order (later
// units on top). A mark whose sprite is still loading is a plain ellipse in its colour.
// Upright marks (angle 0: every layout without rotation) skip the setTransform and
// draw axis-aligned, which software canvases blit about twice as fast.
// units: Float32Array (N, 4) [layer, mark, base w, base h]; frame: (N, 4) [x, y, deg, scale];
// clips: Float32Array (N,) the share of each mark's width drawn (a partial mark of per=), or null.

const RAD = Math.PI / 180;

/** Draws every mark (and the selection outlines); returns the largest side in device px. */
export function drawMarks(ctx, k, state) {
  const n = markCount(state);
  const side = drawRange(ctx, k, state, 0, n);
  drawSelection(ctx, k, state);
  return side.maxSide * k;
}

/** How many marks `state` ({units, frame}) can draw. */
export function markCount({ units, frame }) {
  return Math.floor(Math.min(units ? units.length : 0, frame ? frame.length : 0) / 4);
}

/** Draws marks from..until-1; returns {maxSide}: the largest side drawn (canvas px). */
export function drawRange(ctx, k, { units, frame, colors, bitmaps, clips }, from, until) {
  let maxSide = 0;
  let upright = false; // is the base transform (no rotation) set?
  for (let i = from; i < until; i++) {
    const s = frame[4 * i + 3];
    const w = units[4 * i + 2] * s;
    const h = units[4 * i + 3] * s;
    const x = frame[4 * i];
    const y = frame[4 * i + 1];
    if (!(w > 0 && h > 0) || !Number.isFinite(x + y)) continue;
    if (w > maxSide) maxSide = w;
    if (h > maxSide) maxSide = h;
    const deg = frame[4 * i + 2];
    let cx = 0;
    let cy = 0;
    if (deg === 0) {
      if (!upright) ctx.setTransform(k, 0, 0, k, 0, 0);
      upright = true;
      cx = x;
      cy = y;
    } else {
      const c = Math.cos(deg * RAD) * k;
      const sn = Math.sin(deg * RAD) * k;
      ctx.setTransform(c, sn, -sn, c, x * k, y * k);
      upright = false;
    }
    const bmp = bitmaps.get(units[4 * i + 1]);
    const cut = clips && clips[i] < 1;
    if (cut) {
      // a partial mark: only the left share of its box, as in the SVG export
      ctx.save();
      ctx.beginPath();
      ctx.rect(cx - w / 2, cy - h / 2, w * clips[i], h);
      ctx.clip();
    }
    if (bmp) {
      ctx.drawImage(bmp, cx - w / 2, cy - h / 2, w, h);
    } else {
      ctx.fillStyle = rgba(colors, i);
      ctx.beginPath();
      ctx.ellipse(cx, cy, w / 2, h / 2, 0, 0, 2 * Math.PI);
      ctx.fill();
    }
    if (cut) ctx.restore();
  }
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  return { maxSide };
}

/** Outlines the selected marks (state.selected: a Set of unit indices). */
export function drawSelection(ctx, k, state) {
  const { units, frame, selected } = state;
  if (selected && selected.size) outlineSelected(ctx, k, units, frame, markCount(state), selected);
  ctx.setTransform(1, 0, 0, 1, 0, 0);
}

function outlineSelected(ctx, k, units, frame, n, selected) {
  for (const i of selected) {
    if (i < 0 || i >= n) continue;
    const s = frame[4 * i + 3];
    const w = units[4 * i + 2] * s;
    const h = units[4 * i + 3] * s;
    const a = frame[4 * i + 2] * RAD;
    const c = Math.cos(a) * k;
    const sn = Math.sin(a) * k;
    ctx.setTransform(c, sn, -sn, c, frame[4 * i] * k, frame[4 * i + 1] * k);
    ctx.strokeStyle = "#ffffff";
    ctx.lineWidth = 4 / k;
    ctx.strokeRect(-w / 2 - 2 / k, -h / 2 - 2 / k, w + 4 / k, h + 4 / k);
    ctx.strokeStyle = "#1a73e8";
    ctx.lineWidth = 2 / k; // device px: the outline stays thin at any zoom
    ctx.strokeRect(-w / 2 - 2 / k, -h / 2 - 2 / k, w + 4 / k, h + 4 / k);
  }
}

function rgba(colors, i) {
  if (!colors || colors.length < 4 * i + 4) return "rgba(120, 120, 120, 0.8)";
  return `rgba(${colors[4 * i]}, ${colors[4 * i + 1]}, ${colors[4 * i + 2]}, ${colors[4 * i + 3] / 255})`;
}
