import { test } from "node:test";
import assert from "node:assert/strict";
import { guidesVisible } from "../src/workspace.js";

test("the guides show before a layout, while editing, or when asked; not over finished marks with Select", () => {
  assert.equal(guidesVisible({ tool: "select", hasFrame: false, shown: false }), true);
  assert.equal(guidesVisible({ tool: "select", hasFrame: true, shown: false }), false);
  assert.equal(guidesVisible({ tool: "select", hasFrame: true, shown: true }), true);
  for (const tool of ["container-rect", "emitter-grid", "force-point", "force-direction", "erase"]) {
    assert.equal(guidesVisible({ tool, hasFrame: true, shown: false }), true, tool);
  }
});
