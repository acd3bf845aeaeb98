// Undo and redo over whole-design snapshots. Snapshots are JSON strings: cheap to
// compare, impossible to mutate by accident, and a design is small (no mark images
// beyond what the user uploaded).

export class History {
  constructor(limit = 100) {
    this.limit = limit;
    this.past = [];
    this.future = [];
  }

  /** Records `before`, the design as it was before an edit; clears the redo stack. */
  record(before) {
    const snap = JSON.stringify(before);
    if (this.past[this.past.length - 1] !== snap) this.past.push(snap);
    if (this.past.length > this.limit) this.past.shift();
    this.future = [];
  }

  get canUndo() {
    return this.past.length > 0;
  }

  get canRedo() {
    return this.future.length > 0;
  }

  /** Returns the design to restore, given the current one; null when nothing to undo. */
  undo(current) {
    if (!this.past.length) return null;
    this.future.push(JSON.stringify(current));
    return JSON.parse(this.past.pop());
  }

  /** Returns the design to restore, given the current one; null when nothing to redo. */
  redo(current) {
    if (!this.future.length) return null;
    this.past.push(JSON.stringify(current));
    return JSON.parse(this.future.pop());
  }
}
