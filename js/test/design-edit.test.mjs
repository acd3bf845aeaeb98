import { test } from "node:test";
import assert from "node:assert/strict";
import { History } from "../src/history.js";
import * as edit from "../src/design-edit.js";
import { translatePathData } from "../src/pathdata.js";

const base = () => {
  const d = edit.emptyDesign();
  d.layers.push(edit.newLayer("a"), edit.newLayer("b"));
  d.layers[1].blocks = ["a"];
  return d;
};

test("undo and redo walk whole-design snapshots", () => {
  const h = new History();
  let design = base();
  const edits = [(d) => edit.addPointForce(d, 0, 1, 2), (d) => edit.setDirectionForce(d, 0, 90)];
  for (const e of edits) {
    h.record(design);
    design = e(design);
  }
  assert.equal(design.layers[0].forces.length, 2);
  design = h.undo(design);
  assert.equal(design.layers[0].forces.length, 1);
  design = h.undo(design);
  assert.equal(design.layers[0].forces.length, 0);
  assert.equal(h.undo(design), null);
  design = h.redo(design);
  design = h.redo(design);
  assert.equal(design.layers[0].forces[1].kind, "direction");
  assert.equal(h.redo(design), null);
  design = h.undo(design);
  h.record(design); // a new edit after an undo drops the redo branch
  assert.equal(h.canRedo, false);
});

test("edits never mutate their input", () => {
  const d = base();
  const before = JSON.stringify(d);
  edit.addCut(d, 0, { points: [[0, 0], [5, 5]], width: 12 });
  edit.renameLayer(d, 0, "z");
  edit.deleteLayer(d, 0);
  edit.setEncoding(d, 0, "size", "Duration");
  assert.equal(JSON.stringify(d), before);
});

test("a cut on the whole canvas makes a canvas container; direction forces replace", () => {
  let d = edit.addCut(base(), 0, { points: [[0, 0], [5, 5]], width: 12 });
  assert.deepEqual(d.layers[0].container, { kind: "canvas", cuts: [{ points: [[0, 0], [5, 5]], width: 12 }] });
  d = edit.addPointForce(edit.setDirectionForce(edit.setDirectionForce(d, 0, 90), 0, 45), 0, 3, 4);
  assert.deepEqual(d.layers[0].forces.map((f) => f.kind), ["direction", "point"]);
  assert.equal(d.layers[0].forces[0].angle, 45);
});

test("layer renames and deletes keep blocks consistent", () => {
  let d = edit.renameLayer(base(), 0, "ground");
  assert.deepEqual(d.layers[1].blocks, ["ground"]);
  assert.equal(edit.renameLayer(d, 0, "b").layers[0].name, "ground", "names stay unique");
  d = edit.deleteLayer(d, 0);
  assert.deepEqual(d.layers[0].blocks, []);
  assert.equal(edit.deleteLayer(d, 0).layers.length, 1, "the last layer stays");
  d = edit.duplicateLayer(edit.addLayer(d), 0);
  assert.deepEqual(d.layers.map((l) => l.name), ["b", "b-copy", "layer-2"]);
  assert.deepEqual(edit.moveLayer(d, 2, -2).layers.map((l) => l.name), ["layer-2", "b", "b-copy"]);
});

test("binding a channel leaves the others alone; clearing margin restores 0", () => {
  let d = edit.setEncoding(base(), 0, "width", "W");
  d = edit.setEncoding(d, 0, "size", "S");
  assert.equal(d.layers[0].encodings.width, "W");
  assert.equal(d.layers[0].encodings.size, "S");
  d = edit.setEncoding(edit.setEncoding(d, 0, "margin", "M"), 0, "margin", null);
  assert.equal(d.layers[0].encodings.margin, 0);
});

test("containers translate, path data included", () => {
  const c = { kind: "polygon", points: [[0, 0], [10, 0], [0, 10]], cuts: [{ points: [[1, 1]], width: 4 }] };
  const moved = edit.translateContainer(c, 5, -1);
  assert.deepEqual(moved.points, [[5, -1], [15, -1], [5, 9]]);
  assert.deepEqual(moved.cuts[0].points, [[6, 0]]);
  assert.equal(translatePathData("M 0 0 L 10 0 h 5 V 7 Z m 1 1 l 2 2 z", 1, 2), "M 1 2 L 11 2 h 5 V 9 Z m 1 1 l 2 2 z");
  assert.equal(translatePathData("m1,1 2,2", 10, 10), "m 11 11 2 2");
  assert.deepEqual(edit.translateContainer({ kind: "image", image: "x", box: null }, 3, 4, [80, 50]).box, [3, 4, 80, 50]);
});
