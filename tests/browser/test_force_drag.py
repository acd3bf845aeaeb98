"""Browser test of dragging a point force live: with the Select tool, after a run, a point
force dragged over the shown layout sends its position to the kernel at most every 100 ms
("force" messages, which move it and lay out warm, streaming frames), and the drop commits
the design once (one undo step back to before the drag) and sends the final message, on
which the kernel lays out in full."""

from __future__ import annotations

import time

import numpy as np
import pandas as pd
import pytest
from test_frontend import STAGE, layer, mount, push_layout, to_page

import unitopia_widget as uw

pytestmark = pytest.mark.browser


def test_dragging_a_point_force_streams_its_place_and_the_drop_commits_and_lays_out(page):
    df = pd.DataFrame({"v": np.random.default_rng(2).uniform(1.0, 4.0, 40)})
    w = uw.UnitoPia(df, size="v", container=uw.Container.ellipse(400, 250, 200, 150),
                    boundary="open", fill=0.2, forces=[uw.PointForce(300.0, 250.0)], iterations=80)
    w.run(wait=True)
    frame = np.frombuffer(w.frame, np.float32).reshape(-1, 4)
    units = np.frombuffer(w.units, np.float32).reshape(-1, 4)
    mount(page, design=w.design, marks=w.marks)
    push_layout(page, frame.tolist(), units=units.tolist())
    path = [(300.0 + 15 * k, 250.0) for k in range(1, 7)]
    page.locator(STAGE).hover()
    page.mouse.move(*to_page(page, 300.0, 250.0))
    page.mouse.down()
    for k, p in enumerate(path):
        page.mouse.move(*to_page(page, *p))
        if k == 2:   # the kernel moved the force along the way: the model's design follows
            page.evaluate("d => fake.push('design', d)", {**w.design, "layers": [
                {**w.design["layers"][0], "forces": [{"kind": "point", "x": 345.0, "y": 250.0, "strength": 1.0}]}]})
        page.wait_for_timeout(130)   # past the throttle's interval: each position goes
    page.mouse.up()
    sent = [m for m in page.evaluate("fake.sent") if m.get("type") == "force"]
    live, final = sent[:-1], sent[-1]
    assert len(live) >= 4 and not any(m["final"] for m in live), f"live positions: {live}"
    assert {(m["layer"], m["index"]) for m in sent} == {(0, 0)}
    assert [m["x"] for m in live] == sorted(m["x"] for m in live), "in the pointer's order"
    assert final["final"] and final["x"] == pytest.approx(390.0, abs=1) and final["y"] == pytest.approx(250.0, abs=1)
    force = layer(page)["forces"][0]
    assert (force["x"], force["y"]) == pytest.approx((390.0, 250.0), abs=1), "the drop commits the design"
    page.click('[data-action="undo"]')
    force = layer(page)["forces"][0]
    assert (force["x"], force["y"]) == (300.0, 250.0), "one undo returns to before the drag"
    for m in sent:   # the messages as the kernel receives them
        w._on_message(w, m, [])
    end = time.monotonic() + 60
    while w._drag_worker is not None or w._runner.running:
        assert time.monotonic() < end, "the drop's layout did not end"
        time.sleep(0.01)
    assert w.error == "" and w.status == "done" and not w.stale
    assert w.layers[0].forces[0] == uw.PointForce(final["x"], final["y"])
