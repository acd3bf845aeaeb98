// Replay of the last run: the view records the frames a run streams (a Recording bounded
// by a memory budget) and a Player plays, pauses and scrubs them with no kernel (the
// control is replay-control.js). Nothing is sent: the marks are drawn from the recorded
// frames through the usual draw path.
// Frames are Float32Array (N, 4) row-major: x, y (canvas px), angle (degrees), scale.
import { lerpFrame } from "./frames.js";

/** Bytes of frames one view keeps: 64 MiB, so 20,000 units keep 209 frames. */
export const BUDGET_BYTES = 64 * 1024 * 1024;
/** Replay speed in received frames per second (the rate the kernel streams at)... */
export const PLAY_FPS = 30;
/** ...but a replay lasts at most this long: a longer run plays faster. */
export const MAX_SECONDS = 10;

/**
 * A run's frames within `budgetBytes`: every received frame until the budget is full, then
 * every k-th (k doubles each time it fills again, so the kept frames stay evenly spaced),
 * and always the first and the latest one. Frames are copied (a decoded frame may be a
 * view into a message buffer). A frame of another unit count starts a new recording.
 */
export class Recording {
  constructor(budgetBytes = BUDGET_BYTES) {
    if (!(budgetBytes > 0)) throw new RangeError(`budgetBytes must be a positive number of bytes, got ${budgetBytes}`);
    this.budget = budgetBytes;
    this.clear();
  }

  clear() {
    this.kept = []; // [{index: received frame index, data: Float32Array}], by index
    this.received = 0;
    this.stride = 1;
  }

  /** Kept frames. */
  get length() {
    return this.kept.length;
  }

  /** Bytes held by the kept frames. */
  get bytes() {
    return this.kept.reduce((sum, e) => sum + e.data.byteLength, 0);
  }

  push(frame) {
    if (!frame || !frame.length) return;
    if (this.kept.length && this.kept[0].data.length !== frame.length) this.clear();
    const index = this.received++;
    const tail = this.kept[this.kept.length - 1];
    // the latest frame off the stride was kept only for being the latest: its buffer is reused
    const reuse = tail && tail.index % this.stride !== 0 ? this.kept.pop().data : null;
    const data = reuse || new Float32Array(frame.length);
    data.set(frame);
    this.kept.push({ index, data });
    const max = Math.max(2, Math.floor(this.budget / data.byteLength));
    while (this.kept.length > max) {
      this.stride *= 2;
      const latest = this.kept[this.kept.length - 1];
      this.kept = this.kept.filter((e) => e.index % this.stride === 0 || e === latest);
    }
  }

  /**
   * The frame at `position` (a received frame index, fractions allowed), interpolated
   * between the kept frames around it, written into `out` (reused when its length fits).
   * Null when nothing is recorded.
   */
  sample(position, out = null) {
    const kept = this.kept;
    if (!kept.length) return null;
    const first = kept[0], last = kept[kept.length - 1];
    if (!out || out.length !== first.data.length) out = new Float32Array(first.data.length);
    if (!(position > first.index)) return out.set(first.data), out;
    if (position >= last.index) return out.set(last.data), out;
    let lo = 0, hi = kept.length - 1; // kept[lo].index <= position < kept[hi].index
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (kept[mid].index <= position) lo = mid;
      else hi = mid;
    }
    const a = kept[lo], b = kept[hi];
    return lerpFrame(out, a.data, b.data, (position - a.index) / (b.index - a.index));
  }
}

/**
 * Plays a Recording: `position` is null while the live frames show, else the received
 * frame index on screen. Play starts from the first frame (or goes on after a pause) and
 * stops on the last one, the run's final layout. Times are ms (performance.now, rAF).
 */
export class Player {
  constructor(recording, { fps = PLAY_FPS, maxSeconds = MAX_SECONDS } = {}) {
    this.recording = recording;
    this.fps = fps;
    this.maxSeconds = maxSeconds;
    this.position = null;
    this.playing = false;
    this.out = null;
  }

  /** The last position: the latest received frame. */
  get end() {
    return Math.max(0, this.recording.received - 1);
  }

  /** Received frames per second of replay. */
  get rate() {
    return Math.max(this.fps, this.end / this.maxSeconds);
  }

  play(now) {
    if (this.position === null || this.position >= this.end) this.position = 0;
    this.playing = true;
    this.startTime = now;
    this.startPosition = this.position;
  }

  pause() {
    this.playing = false;
  }

  /** Shows the frame at `position` (clamped to the recording), paused. */
  seek(position) {
    this.playing = false;
    this.position = Math.min(this.end, Math.max(0, Number(position) || 0));
  }

  /** Back to the live frames. */
  stop() {
    this.playing = false;
    this.position = null;
  }

  /** Advances a playing replay to time `now`; true when the position moved. */
  step(now) {
    if (!this.playing) return false;
    const elapsed = Math.max(0, now - this.startTime) / 1000;
    this.position = Math.min(this.end, this.startPosition + elapsed * this.rate);
    if (this.position >= this.end) this.playing = false;
    return true;
  }

  /** The frame to draw, or null while the live frames show. */
  frame() {
    if (this.position === null) return null;
    this.out = this.recording.sample(this.position, this.out);
    return this.out;
  }
}
