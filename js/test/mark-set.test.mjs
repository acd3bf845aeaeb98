import { test } from "node:test";
import assert from "node:assert/strict";
import * as edit from "../src/design-edit.js";
import { addMark, describeMark, moveMark, removeMark } from "../src/mark-set.js";
import { clampCorner, legendSettings, setLegend } from "../src/legend-place.js";

const circle = { kind: "shape", name: "circle" };
const star = { kind: "shape", name: "star" };
const apple = { kind: "icon", name: "fa:apple-whole" };

const v1 = () => ({ schema: "unitopia-design", version: 1, canvas: [800, 500], layers: [{ name: "a", mark: circle, encodings: {} }] });

test("a version 1 layer's single mark becomes the first of its mark set", () => {
  const d = addMark(v1(), 0, apple);
  assert.deepEqual(d.layers[0].marks, [circle, apple]);
  assert.equal("mark" in d.layers[0], false, "one source of truth: marks");
  assert.deepEqual(edit.layerMarks({}), [circle]);
});

test("marks are added, moved and removed in order; the last one stays", () => {
  let d = addMark(addMark(v1(), 0, star), 0, apple);
  d = moveMark(d, 0, 2, -2);
  assert.deepEqual(d.layers[0].marks.map(describeMark), ["fa:apple-whole", "circle", "star"]);
  assert.deepEqual(moveMark(d, 0, 0, -1).layers[0].marks, d.layers[0].marks, "no move past the ends");
  d = removeMark(removeMark(d, 0, 1), 0, 1);
  assert.deepEqual(d.layers[0].marks, [apple]);
  assert.deepEqual(removeMark(d, 0, 0).layers[0].marks, [apple]);
});

test("mark_keys move and go with their marks; adding a mark drops them", () => {
  const d = v1();
  d.layers[0].marks = [circle, star, apple];
  d.layers[0].mark_keys = ["x", "y", "z"];
  const before = JSON.stringify(d);
  assert.deepEqual(moveMark(d, 0, 0, 2).layers[0].mark_keys, ["y", "z", "x"]);
  assert.deepEqual(removeMark(d, 0, 1).layers[0].mark_keys, ["x", "z"]);
  assert.equal(addMark(d, 0, circle).layers[0].mark_keys, null);
  assert.equal(JSON.stringify(d), before, "edits never mutate their input");
});

test("new layers are version 4 with a shape channel, a silhouette footprint, median-capped margins and copy the last layer's marks", () => {
  const d = addMark(edit.addLayer(edit.emptyDesign()), 0, star);
  assert.equal(d.version, 4);
  assert.equal(d.layers[0].footprint, "silhouette");
  assert.equal(d.layers[0].margin_of, "median");
  assert.equal(d.layers[0].encodings.shape, null);
  assert.deepEqual(edit.addLayer(d).layers[1].marks, [circle, star]);
  assert.ok(edit.CHANNELS.includes("shape"));
});

test("binding width keeps size: the kernel decides whether they combine", () => {
  let d = edit.setEncoding(edit.addLayer(edit.emptyDesign()), 0, "size", "S");
  d = edit.setEncoding(d, 0, "width", "W");
  assert.deepEqual([d.layers[0].encodings.size, d.layers[0].encodings.width], ["S", "W"]);
});

test("legend settings default to visible on the right; a drag is clamped to the canvas", () => {
  assert.deepEqual(legendSettings({}), { visible: true, position: "right" });
  assert.deepEqual(legendSettings({ legend: { position: "diagonal" } }).position, "right");
  assert.deepEqual(legendSettings({ legend: { position: [10, 20], visible: false } }), { visible: false, position: [10, 20] });
  const d = setLegend({ legend: { position: "left", extra: 1 } }, { visible: false });
  assert.deepEqual(d.legend, { position: "left", extra: 1, visible: false });
  assert.deepEqual(clampCorner([790.04, -5], [100, 50], [800, 500]), [700, 0]);
  assert.deepEqual(clampCorner([12.345, 40], [900, 50], [800, 500]), [0, 40]);
});
