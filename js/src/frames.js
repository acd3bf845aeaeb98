// Binary traits and frame interpolation.
// anywidget delivers bytes as a DataView whose byteOffset may be anything (it can be a
// view into a larger message buffer), so decoding copies when the offset is not aligned.

function asBytes(value) {
  if (!value) return null;
  if (value instanceof DataView || ArrayBuffer.isView(value)) {
    return { buffer: value.buffer, offset: value.byteOffset, length: value.byteLength };
  }
  if (value instanceof ArrayBuffer) return { buffer: value, offset: 0, length: value.byteLength };
  return null;
}

/** Bytes -> Float32Array of shape (N, cols) row-major, or null when empty. */
export function decodeFloat32(value, cols = 4) {
  const b = asBytes(value);
  if (!b || b.length < 4 * cols) return null;
  const count = Math.floor(b.length / (4 * cols)) * cols;
  if (b.offset % 4 === 0) return new Float32Array(b.buffer, b.offset, count);
  return new Float32Array(b.buffer.slice(b.offset, b.offset + count * 4));
}

/** Bytes -> Uint8Array (no alignment needed), or null when empty. */
export function decodeUint8(value) {
  const b = asBytes(value);
  if (!b || !b.length) return null;
  return new Uint8Array(b.buffer, b.offset, b.length);
}

/** Whether two frames (Float32Array or null) hold the same values. */
export function sameFrame(a, b) {
  if (!a || !b) return a === b;
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}

/** Shortest signed difference b - a between two angles in degrees. */
export function angleDelta(a, b) {
  return ((((b - a) % 360) + 540) % 360) - 180;
}

/** out = from + (to - from) * alpha per unit, angles the short way round; returns out. */
export function lerpFrame(out, from, to, alpha) {
  for (let i = 0; i < to.length; i += 4) {
    out[i] = from[i] + (to[i] - from[i]) * alpha;
    out[i + 1] = from[i + 1] + (to[i + 1] - from[i + 1]) * alpha;
    // equal angles (upright marks: every layout without rotation) skip the modular delta
    out[i + 2] = from[i + 2] === to[i + 2] ? to[i + 2] : from[i + 2] + angleDelta(from[i + 2], to[i + 2]) * alpha;
    out[i + 3] = from[i + 3] + (to[i + 3] - from[i + 3]) * alpha;
  }
  return out;
}

/**
 * Interpolates between the frame on screen and the latest frame received, over about the
 * interval at which frames arrive, so a 30 Hz stream animates smoothly at the display rate.
 */
export class FrameInterpolator {
  constructor({ minMs = 16, maxMs = 250 } = {}) {
    this.minMs = minMs;
    this.maxMs = maxMs;
    this.from = null;
    this.to = null;
    this.current = null;
    this.start = 0;
    this.duration = 33;
    this.lastArrival = -1;
    this.settled = true;
  }

  /** A new target frame arrived at time `now` (ms). */
  push(frame, now) {
    if (this.lastArrival >= 0) {
      const gap = Math.min(this.maxMs, Math.max(this.minMs, now - this.lastArrival));
      this.duration = 0.7 * this.duration + 0.3 * gap;
    }
    this.lastArrival = now;
    if (!frame) {
      this.from = this.to = this.current = null;
      this.settled = false;
      return;
    }
    const sameShape = this.current && this.current.length === frame.length;
    this.from = sameShape ? Float32Array.from(this.current) : frame;
    this.to = frame;
    if (!sameShape) this.current = new Float32Array(frame.length);
    this.start = now;
    this.settled = false;
  }

  /** Jumps to the latest frame (no animation). */
  snap() {
    if (this.to) this.current.set(this.to);
    this.from = this.to;
    this.settled = false;
  }

  /**
   * Updates `current` for time `now`. Returns true when it changed since the previous
   * call (the caller then repaints), false once the animation has settled.
   */
  step(now) {
    if (this.settled) return false;
    if (!this.to) {
      this.settled = true;
      return true;
    }
    const alpha = this.from === this.to ? 1 : Math.min(1, (now - this.start) / this.duration);
    const { from, to, current } = this;
    if (alpha >= 1) {
      current.set(to);
      this.from = to;
      this.settled = true;
      return true;
    }
    lerpFrame(current, from, to, alpha);
    return true;
  }
}
