"""Live drag in a real JupyterLab with Chromium (issue 49, item 2, "Done when"): dragging a
mark with the Select tool for 2 s with 1,000 marks on the canvas shows at least 10 distinct
frames in which other marks moved, before the pointer is released; the drop ends with the
final layout, the mark pinned where it was dropped. The same for a point force dragged under
1,000 marks: the marks move in at least 10 frames while it moves, and the drop lays out."""

from __future__ import annotations

import math
import time

import pytest
from test_jupyterlab import STAGE, to_page, use_tool, wait_done, widget

pytestmark = pytest.mark.jupyterlab

DRAG_S = 2.0   # the pointer moves for this long
DRAG_PX = 90   # towards the container's centre

SETUP = """\
import time
import numpy as np
import pandas as pd
import unitopia_widget as uw

df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1.0, 10.0, 1000).round(3)})
"""


def watch(method: str) -> str:
    """Kernel code for the kernel's side of a drag: each frame sent (time, x y of every unit)
    and the arrival of each live message the widget's ``method`` answers (``final=False``;
    the drop is ``final=True``), to count the frames sent while the pointer moved."""
    return f"""\
sent, dragged = [], []
w.observe(lambda c: sent.append((time.perf_counter(),
          np.frombuffer(c["new"], np.float32).reshape(-1, 4)[:, :2].copy())), "frame")
_answer = w.{method}
def _spy(*args, final):
    if not final:
        dragged.append(time.perf_counter())
    _answer(*args, final=final)
w.{method} = _spy
"""


# frames sent between the first and the last drag message in which a mark other than
# the dragged one moved by over 0.05 px
MOVED = """\
(lambda k: sum(1 for (t0, a), (t1, b) in zip(sent, sent[1:])
               if dragged[0] <= t1 <= dragged[-1] and len(a) == len(b)
               and float(np.abs(np.delete(b - a, k, axis=0)).max()) > 0.05))({k})"""


def test_dragging_a_mark_for_2_s_among_1000_moves_the_others_live_then_pins_it(lab):
    page = lab.page
    lab.open([SETUP, 'w = uw.UnitoPia(df, size="v", container=uw.Container.ellipse(400, 250, 240, 240))\nw'])
    root = widget(lab, 1)
    stage = root.locator(STAGE)
    root.locator('[data-action="run"]').click()
    wait_done(page, root, timeout=300_000)
    # the mark nearest (280, 250): dragged right, towards the centre, through the crowd
    k, x, y = lab.eval("(lambda p: (lambda k: [k, float(p.x[k]), float(p.y[k])])"
                       "(int(np.hypot(p.x - 280, p.y - 250).argmin())))(w.placements)")
    lab.run(watch("_drag"))
    use_tool(root, "select")
    stats = "el => [el.unitopiaStats.framesReceived, el.unitopiaStats.paints]"
    stage.scroll_into_view_if_needed()
    stage.hover()
    page.mouse.move(*to_page(stage, x, y))
    page.mouse.down()
    before = root.evaluate(stats)
    began = time.monotonic()
    while (held := time.monotonic() - began) < DRAG_S:   # the pointer moves for 2 s
        page.mouse.move(*to_page(stage, x + DRAG_PX * held / DRAG_S, y))
        page.wait_for_timeout(10)
    page.mouse.move(*to_page(stage, x + DRAG_PX, y))
    held = time.monotonic() - began
    during = root.evaluate(stats)
    page.mouse.up()   # the kernel is asked after: a cell run scrolls the notebook under the pointer
    moved = lab.eval(MOVED.format(k=k))   # between the first and the last drag message: before the drop
    messages = lab.eval("len(dragged)")
    received, paints = during[0] - before[0], during[1] - before[1]
    print(f"held {held:.2f} s: drag messages {messages}, frames with other marks moved {moved}, "
          f"frames received by the view {received}, paints {paints}")
    assert messages <= math.ceil(held / 0.1) + 1, "the widget throttles to one message per 100 ms"
    assert moved >= 10, f"only {moved} frames moved the other marks while the mark was dragged"
    assert received >= moved and paints >= 10, "the view received and drew them"
    # a drag message's run also ends "done": wait for the drop's pin and its layout
    final = (f"w.status == 'done' and not w.stale and len(w.pinned) == 1 and float(np.hypot("
             f"w.pinned.x.iloc[0] - {x + DRAG_PX}, w.pinned.y.iloc[0] - {y})) < 1.5 and float(np.hypot("
             f"w.placements.x[{k}] - w.pinned.x.iloc[0], w.placements.y[{k}] - w.pinned.y.iloc[0])) < 0.01")
    assert lab.wait_until(final, timeout=120), lab.eval("[w.status, w.stale, w.error, w.pinned.values.tolist()]")
    assert lab.eval("w.pinned.iloc[0][['x', 'y']].tolist()") == pytest.approx([x + DRAG_PX, y], abs=1.5)
    assert not lab.eval("w.error")


# frames sent between the first and the last force message in which some mark moved by over 0.05 px
MOVED_ANY = """\
sum(1 for (t0, a), (t1, b) in zip(sent, sent[1:])
    if dragged[0] <= t1 <= dragged[-1] and len(a) == len(b) and float(np.abs(b - a).max()) > 0.05)"""


def test_dragging_a_point_force_for_2_s_under_1000_marks_moves_them_live_then_lays_out(lab):
    page = lab.page
    lab.open([SETUP, 'w = uw.UnitoPia(df, size="v", container=uw.Container.ellipse(400, 250, 240, 240), '
                     'boundary="open", fill=0.3, forces=[uw.PointForce(330, 320)])\nw'])
    root = widget(lab, 1)
    stage = root.locator(STAGE)
    root.locator('[data-action="run"]').click()
    wait_done(page, root, timeout=300_000)
    lab.run(watch("_drag_force"))
    use_tool(root, "select")
    stage.scroll_into_view_if_needed()
    stage.hover()
    x, y = 330.0, 320.0
    page.mouse.move(*to_page(stage, x, y))
    page.mouse.down()
    began = time.monotonic()
    while (held := time.monotonic() - began) < DRAG_S:   # the force moves right for 2 s
        page.mouse.move(*to_page(stage, x + DRAG_PX * held / DRAG_S, y))
        page.wait_for_timeout(10)
    page.mouse.move(*to_page(stage, x + DRAG_PX, y))
    held = time.monotonic() - began
    page.mouse.up()
    moved = lab.eval(MOVED_ANY)
    messages = lab.eval("len(dragged)")
    print(f"held {held:.2f} s: force messages {messages}, frames with marks moved {moved}")
    assert messages <= math.ceil(held / 0.1) + 1, "the widget throttles to one message per 100 ms"
    assert moved >= 10, f"only {moved} frames moved the marks while the force was dragged"
    # a drag message's run also ends "done": wait for the drop's force and its layout
    final = (f"w.status == 'done' and not w.stale and not w._chart.result.cancelled and float(np.hypot("
             f"w.layers[0].forces[0].x - {x + DRAG_PX}, w.layers[0].forces[0].y - {y})) < 1.5")
    assert lab.wait_until(final, timeout=120), lab.eval("[w.status, w.stale, w.error]")
    force = lab.eval("[w.layers[0].forces[0].x, w.layers[0].forces[0].y]")
    assert force == pytest.approx([x + DRAG_PX, y], abs=1.5), "the force where it was dropped"
    assert not lab.eval("w.error")
