"""Pinning by hand in a real JupyterLab: a mark dragged with the Select tool after a run
is pinned in the kernel where it was dropped, and the layout the drop starts keeps it there."""

from __future__ import annotations

import pytest
from test_jupyterlab import STAGE, drag, use_tool, wait_done, widget

pytestmark = pytest.mark.jupyterlab

SETUP = """\
import numpy as np
import pandas as pd
import unitopia_widget as uw

df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1.0, 3.0, 30).round(3)})
"""


def test_dragging_a_mark_in_jupyterlab_with_chromium_pins_it_in_the_kernel(lab):
    page = lab.page
    lab.open([SETUP, 'w = uw.UnitoPia(df, size="v", iterations=80)\nw'])
    root = widget(lab, 1)
    stage = root.locator(STAGE)
    root.locator('[data-action="run"]').click()
    wait_done(page, root)
    x, y, row = lab.eval("[float(w.placements.x[0]), float(w.placements.y[0]), int(w.placements.row[0])]")
    to = (x + 50 if x < 600 else x - 50, y + 30 if y < 400 else y - 30)
    use_tool(root, "select")
    drag(page, stage, [(x, y), to], steps=6)
    # the live drag's runs end "done" too, with the mark pinned where the pointer last was
    # reported (a step short of the drop): wait for the drop's own pin and its layout
    assert lab.wait_until(f"w.status == 'done' and not w.stale and len(w.pinned) == 1 and float(np.hypot("
                          f"w.pinned.x.iloc[0] - {to[0]}, w.pinned.y.iloc[0] - {to[1]})) < 1.5 and float(np.hypot("
                          "w.placements.x[0] - w.pinned.x.iloc[0], w.placements.y[0] - w.pinned.y.iloc[0])) < 0.01",
                          timeout=90), "the drop lays out, the mark where it was dropped"
    pin = lab.eval("w.pinned.iloc[0].to_dict()")
    assert pin["row"] == row and pin["x"] == pytest.approx(to[0], abs=1.5) and pin["y"] == pytest.approx(to[1], abs=1.5)
    assert lab.eval("w.pinned_units") == [0]
    placed = lab.eval("[float(w.placements.x[0]), float(w.placements.y[0])]")
    assert placed == pytest.approx([pin["x"], pin["y"]], abs=1.0)
