"""The front end's mark set, icon lookup, shape channel, legend and status line against
the real kernel in JupyterLab (the fake-model browser tests cover each in detail)."""

from __future__ import annotations

import pytest
from test_jupyterlab import RUN_TIMEOUT, STAGE, click, to_page, wait_done, widget

pytestmark = pytest.mark.jupyterlab

SETUP = """\
import numpy as np
import pandas as pd
import unitopia_widget as uw

rng = np.random.default_rng(0)
df = pd.DataFrame({"v": rng.uniform(0.5, 10.0, 60).round(3), "kind": rng.choice(["a", "b", "c"], 60)})
"""


def test_mark_set_shape_channel_legend_and_status_through_the_kernel(lab):
    page = lab.page
    lab.open([SETUP, 'w = uw.UnitoPia(df, mark="circle", size="v", iterations=150)\nw'])
    root = widget(lab, 1)

    # The mark set: a shape and an icon by name, both accepted by the kernel.
    root.locator('[data-setting="mark-shape"]').select_option("star")
    assert lab.wait_until("len(w.design['layers'][0]['marks']) == 2")
    root.locator('[data-role="icon-query"]').fill("apple")
    root.locator('[data-icon="fa:apple-whole"]').click(timeout=20_000)
    assert lab.wait_until("w.design['layers'][0]['marks'][-1] == {'kind': 'icon', 'name': 'fa:apple-whole'}")
    page.wait_for_function("el => el.querySelectorAll('.ut-mark-list [data-mark] img').length === 3",
                           arg=root.element_handle(), timeout=20_000)
    assert lab.eval("sorted({m['mark'] for m in w.marks})") == [0, 1, 2]

    # The shape channel: each category draws its own mark.
    root.locator('[data-field="kind"]').drag_to(root.locator('[data-channel="shape"]'))
    assert lab.wait_until("w.design['layers'][0]['encodings']['shape'] == 'kind'")
    root.locator('[data-action="run"]').click()
    wait_done(page, root, min_frames=2, timeout=RUN_TIMEOUT)
    assert lab.eval("len({int(u) for u in np.frombuffer(w.units, np.float32).reshape(-1, 4)[:, 1]})") == 3
    assert root.locator(".ut-status-word").inner_text().lower() == "done"

    # The legend beside the canvas, then dragged onto it and hidden.
    legend = root.locator("img[data-role='legend']")
    legend.wait_for(state="visible", timeout=20_000)
    legend.scroll_into_view_if_needed()
    stage = root.locator(STAGE).bounding_box()
    box = legend.bounding_box()
    assert box["x"] >= stage["x"] + stage["width"] - 1
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(*to_page(root.locator(STAGE), 40, 40), steps=5)
    page.mouse.up()
    assert lab.wait_until("isinstance(w.design['legend']['position'], list)")
    root.locator('[data-action="toggle-legend"]').click()
    assert lab.wait_until("w.design['legend']['visible'] is False")
    legend.wait_for(state="hidden")

    # Shift-click and Ctrl-click add units to the selection.
    xs = lab.eval("[[float(x), float(y)] for x, y in w.placements[['x', 'y']].to_numpy()[:3]]")
    click(page, root.locator(STAGE), *xs[0])
    for key, (x, y) in zip(["Shift", "Control"], xs[1:]):
        page.keyboard.down(key)
        click(page, root.locator(STAGE), x, y)
        page.keyboard.up(key)
    assert lab.wait_until("len(w.selected_units) == 3")

    # Width dropped beside size: size stays bound or the kernel says why; the layout is stale.
    root.locator('[data-field="v"]').drag_to(root.locator('[data-channel="width"]'))
    assert lab.wait_until("w.stale or w.error")
    enc = lab.eval("w.design['layers'][0]['encodings']")
    error = lab.eval("w.error")
    if error:
        assert root.locator('[role="alert"]').inner_text() == error
        root.locator('[data-action="dismiss-error"]').click()
        assert lab.wait_until("w.error == ''")
    else:
        assert (enc["size"], enc["width"]) == ("v", "v")
        assert root.locator(".ut-status-word").inner_text().lower() == "changed: run again"
    assert enc["size"] == "v", "width never unbinds size"
