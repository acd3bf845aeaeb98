// A uniform grid over the marks' bounding boxes for hover and click hit tests, so
// 5,000 marks stay fast: a query looks at one cell, then tests rotated boxes exactly.
import { pointInPolygon, pointInRotatedBox } from "./geometry.js";

/**
 * units: Float32Array (N, 4) [layer, mark, base width, base height];
 * frame: Float32Array (N, 4) [x, y, angle deg, scale].
 */
export class HitIndex {
  constructor(units, frame, { cellSize = 0 } = {}) {
    const n = Math.min(units ? units.length : 0, frame ? frame.length : 0) / 4;
    this.n = n;
    this.units = units;
    this.frame = frame;
    this.half = new Float32Array(n); // half diagonal: radius of the rotated box's bound
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity, sum = 0;
    for (let i = 0; i < n; i++) {
      const s = frame[4 * i + 3];
      const r = 0.5 * Math.hypot(units[4 * i + 2] * s, units[4 * i + 3] * s);
      const x = frame[4 * i];
      const y = frame[4 * i + 1];
      this.half[i] = Number.isFinite(r + x + y) ? r : -1; // -1: not placed, never hit
      if (this.half[i] < 0) continue;
      sum += r;
      minX = Math.min(minX, x - r);
      minY = Math.min(minY, y - r);
      maxX = Math.max(maxX, x + r);
      maxY = Math.max(maxY, y + r);
    }
    if (!(minX <= maxX)) return void (this.n = 0); // nothing placed
    // Cells about one mark across; at most 512 x 512 of them.
    const span = Math.max(maxX - minX, maxY - minY, 1);
    this.cell = Math.max(cellSize || Math.max(4, (2 * sum) / n), span / 511);
    this.x0 = minX;
    this.y0 = minY;
    this.cols = Math.ceil((maxX - minX) / this.cell) + 1;
    this.rows = Math.ceil((maxY - minY) / this.cell) + 1;
    this.build();
  }

  cellOf(v, origin, count) {
    return Math.max(0, Math.min(count - 1, Math.floor((v - origin) / this.cell)));
  }

  build() {
    // Two passes into flat arrays (counting sort): no per-cell JS arrays to allocate.
    const { n, cols, rows, frame, half } = this;
    const counts = new Uint32Array(cols * rows + 1);
    const each = (fn) => {
      for (let i = 0; i < n; i++) {
        if (half[i] < 0) continue;
        const x = frame[4 * i];
        const y = frame[4 * i + 1];
        const c0 = this.cellOf(x - half[i], this.x0, cols), c1 = this.cellOf(x + half[i], this.x0, cols);
        const r0 = this.cellOf(y - half[i], this.y0, rows), r1 = this.cellOf(y + half[i], this.y0, rows);
        for (let r = r0; r <= r1; r++) for (let c = c0; c <= c1; c++) fn(r * cols + c, i);
      }
    };
    each((cell) => counts[cell + 1]++);
    for (let k = 1; k < counts.length; k++) counts[k] += counts[k - 1];
    this.starts = counts.slice();
    this.items = new Uint32Array(counts[counts.length - 1]);
    const fill = counts.slice();
    each((cell, i) => (this.items[fill[cell]++] = i));
  }

  /** Index of the topmost mark (drawn last = highest index) under (x, y), or -1. */
  query(x, y) {
    if (!this.n) return -1;
    const c = Math.floor((x - this.x0) / this.cell);
    const r = Math.floor((y - this.y0) / this.cell);
    if (c < 0 || r < 0 || c >= this.cols || r >= this.rows) return -1;
    const cell = r * this.cols + c;
    let best = -1;
    for (let k = this.starts[cell]; k < this.starts[cell + 1]; k++) {
      const i = this.items[k];
      if (i > best && this.contains(i, x, y)) best = i;
    }
    return best;
  }

  contains(i, x, y) {
    const f = this.frame;
    const s = f[4 * i + 3];
    const w = this.units[4 * i + 2] * s;
    const h = this.units[4 * i + 3] * s;
    return pointInRotatedBox(x, y, f[4 * i], f[4 * i + 1], w, h, f[4 * i + 2]);
  }

  /** Indices of marks whose centre lies inside the polygon (lasso selection), ascending. */
  inPolygon(points) {
    const out = [];
    for (let i = 0; i < this.n; i++) {
      if (this.half[i] >= 0 && pointInPolygon([this.frame[4 * i], this.frame[4 * i + 1]], points)) out.push(i);
    }
    return out;
  }
}
