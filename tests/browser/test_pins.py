"""Browser test of pinning by hand: a mark dragged with the Select tool after a run is
pinned in the kernel where it was dropped (its position streamed while it moves), and
shows a pin."""

from __future__ import annotations

import time

import numpy as np
import pandas as pd
import pytest
from test_frontend import drag, mount, next_paint, push_layout

import unitopia_widget as uw

pytestmark = pytest.mark.browser


def test_dragging_a_mark_pins_it_in_the_kernel_and_draws_a_pin(page):
    w = uw.UnitoPia(pd.DataFrame({"v": [1.0, 2.0, 1.5, 1.0, 2.5, 1.2]}), size="v", iterations=40)
    w.run(wait=True)
    frame = np.frombuffer(w.frame, np.float32).reshape(-1, 4)
    units = np.frombuffer(w.units, np.float32).reshape(-1, 4)
    mount(page, design=w.design, marks=w.marks)
    push_layout(page, frame.tolist(), units=units.tolist())
    x, y = (float(v) for v in frame[0, :2])
    to = (x + 40, y + 30) if x < 700 else (x - 40, y + 30)
    drag(page, [(x, y), (x + 5, y + 4), ((x + to[0]) / 2, (y + to[1]) / 2), to])
    sent = page.evaluate("fake.sent")
    pins = [m for m in sent if m.get("type") == "pin"]
    assert len(pins) == 1 and pins[0]["units"] == [0]
    drags = [m for m in sent if m.get("type") == "drag"]   # live drag: the first move went at once
    assert drags and drags[0]["units"] == [0] and sent.index(drags[-1]) < sent.index(pins[0])
    w._on_message(w, pins[0], [])   # the message as the kernel receives it: pin, then lay out
    end = time.monotonic() + 60
    while w._drag_worker is not None or w._runner.running:
        assert time.monotonic() < end, "the drop's layout did not end"
        time.sleep(0.01)
    assert w.error == ""
    row = w.pinned.set_index("row").loc[w.placements["row"].iloc[0]]
    assert abs(row.x - to[0]) < 1.0 and abs(row.y - to[1]) < 1.0
    assert w.pinned_units == [0] and w.status == "done" and not w.stale
    laid = np.frombuffer(w.frame, np.float32).reshape(-1, 4)
    page.evaluate("([p, f]) => { fake.push('pinned_units', p); fake.push('frame', unitopia.f32(f)); }",
                  [w.pinned_units, laid.tolist()])
    at = (float(laid[0, 0]), float(laid[0, 1]))   # where the drop's layout shows the pinned mark
    next_paint(page)
    unit = 800 / page.locator('[data-role="stage"]').bounding_box()["width"]   # canvas px per screen px
    head = page.evaluate(
        """([x, y]) => { const c = document.querySelectorAll('[data-role="stage"] canvas')[2];
                         const k = c.width / 800;
                         return Array.from(c.getContext('2d').getImageData(Math.round(x * k), Math.round(y * k), 1, 1).data); }""",
        [at[0], at[1] - 9 * unit])
    assert head[0] > 180 and head[1] < 90 and head[3] > 200, f"a red pin head above the dropped mark, got {head}"
