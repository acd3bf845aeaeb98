// Pure edits of a layer's mark set (design version 2: layer "marks", a list of at least
// one mark, with "mark_keys": null or the category each mark draws, kept in step).
// Each returns a new design; a version 1 layer's single "mark" becomes the list.
import { layerMarks, updateLayer } from "./design-edit.js";

function withMarks(design, i, fn) {
  return updateLayer(design, i, (l) => {
    const marks = layerMarks(l);
    const keys = Array.isArray(l.mark_keys) && l.mark_keys.length === marks.length ? l.mark_keys.slice() : null;
    const out = fn(marks, keys);
    delete l.mark;
    l.marks = out.marks;
    l.mark_keys = out.keys;
  });
}

/**
 * Appends a mark to layer i. With mark_keys set, the new mark has no category yet, so
 * the keys are dropped (null: categories take the marks in list order).
 */
export const addMark = (design, i, mark) => withMarks(design, i, (marks) => ({ marks: [...marks, mark], keys: null }));

/** Removes mark k of layer i; the last mark stays (a layer always has one). */
export const removeMark = (design, i, k) =>
  withMarks(design, i, (marks, keys) => {
    if (marks.length <= 1 || k < 0 || k >= marks.length) return { marks, keys };
    return { marks: marks.filter((_, j) => j !== k), keys: keys && keys.filter((_, j) => j !== k) };
  });

/** Moves mark k of layer i by delta places; its category key moves with it. */
export const moveMark = (design, i, k, delta) =>
  withMarks(design, i, (marks, keys) => {
    const j = k + delta;
    if (k < 0 || k >= marks.length || j < 0 || j >= marks.length) return { marks, keys };
    const move = (list) => {
      const [item] = list.splice(k, 1);
      list.splice(j, 0, item);
      return list;
    };
    return { marks: move(marks), keys: keys && move(keys) };
  });

/** A short label for a mark spec: the shape or icon name, else its kind. */
export function describeMark(mark) {
  if (!mark || typeof mark !== "object") return "default";
  if (mark.kind === "shape" || mark.kind === "icon") return String(mark.name);
  return String(mark.kind);
}
