// Paints the marks in time slices, so that no main-thread task is long however many
// marks there are: each step() draws as many marks into a back buffer as the cost
// measured so far fits in a slice, and the finished picture is copied to the visible
// canvas at once (a half-drawn frame is never shown). A paint, once started, finishes before the next one starts, so frames
// arriving faster than the marks can be drawn are skipped, never left half-drawn.
import { drawRange, drawSelection, markCount } from "./draw-marks.js";

const SLICE_MS = 8; // half a display frame at 60 Hz: the other half is left to the page
const BACK_OPTIONS = { willReadFrequently: true };
const FIRST_SLICE = 512; // marks in the first slice, before any cost is measured

export class MarksPainter {
  /**
   * target: the visible canvas; makeCanvas(): a new canvas for the back buffer;
   * now(): a clock in ms (performance.now by default).
   */
  constructor(target, { makeCanvas = () => document.createElement("canvas"), now = () => performance.now(), sliceMs = SLICE_MS, firstSlice = FIRST_SLICE } = {}) {
    this.target = target;
    this.back = null;
    this.makeCanvas = makeCanvas;
    this.now = now;
    this.sliceMs = sliceMs;
    this.perSlice = firstSlice; // marks a slice draws: learnt from the time slices take
    this.frame = new Float32Array(0); // the frame being painted: a copy, reused
    this.state = null;
    this.next = 0;
    this.maxSide = 0;
    this.busy = false;
    this.px = 0; // largest side of the last finished paint, device px
  }

  /** Starts painting `state` ({units, frame, colors, bitmaps, selected}) at zoom k. */
  start(k, state) {
    const n = 4 * markCount(state);
    if (this.frame.length !== n) this.frame = new Float32Array(n);
    if (n) this.frame.set(state.frame.subarray(0, n));
    this.state = { ...state, frame: this.frame };
    this.k = k;
    if (!this.back) this.back = this.makeCanvas();
    if (this.back.width !== this.target.width || this.back.height !== this.target.height) {
      this.back.width = this.target.width;
      this.back.height = this.target.height;
    }
    const ctx = this.back.getContext("2d", BACK_OPTIONS);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.back.width, this.back.height);
    this.next = 0;
    this.maxSide = 0;
    this.busy = true;
  }

  /** Drops an unfinished paint (the canvas was resized: it would show at the old size). */
  cancel() {
    this.busy = false;
  }

  /** Draws one slice; returns true when this step finished the paint and showed it. */
  step() {
    if (!this.busy) return false;
    const n = markCount(this.state);
    const back = this.back.getContext("2d", BACK_OPTIONS);
    const t0 = this.now();
    const until = Math.min(n, this.next + this.perSlice);
    const done = drawRange(back, this.k, this.state, this.next, until);
    // the canvas records draw calls and rasterises them when its picture is next used:
    // reading one pixel rasterises this slice now (and counts it), not all at the copy below
    back.getImageData(0, 0, 1, 1);
    const ms = Math.max(1e-3, this.now() - t0);
    if (until > this.next) this.perSlice = Math.max(16, Math.floor((this.sliceMs * (until - this.next)) / ms));
    this.next = until;
    this.maxSide = Math.max(this.maxSide, done.maxSide);
    if (this.next < n) return false;
    const ctx = this.target.getContext("2d");
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.globalAlpha = 1;
    ctx.globalCompositeOperation = "source-over";
    ctx.clearRect(0, 0, this.target.width, this.target.height);
    ctx.drawImage(this.back, 0, 0);
    drawSelection(ctx, this.k, this.state);
    this.px = this.maxSide * this.k;
    this.busy = false;
    return true;
  }
}
