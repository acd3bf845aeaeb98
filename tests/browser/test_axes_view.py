"""The widget draws the axes of x= and y= as Python sends them (the `axes_image` trait):
past the canvas, in a margin the stage keeps for them, so that nothing of them is clipped,
and under the marks, none of which they cover."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from test_frontend import STAGE, mount, next_paint

import unitopia_widget as uw

pytestmark = pytest.mark.browser

AXES = "img[data-role='axes']"


def laid_out_widget():
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"v": rng.normal(0, 1, 60), "k": np.repeat(["ant", "bee", "cat"], 20)})
    w = uw.UnitoPia(df, mark="circle", x="v", y="k", color="k", canvas=(800, 500), iterations=60)
    w.run(wait=True)
    return w


def push_widget(page, w):
    """The traits Python sends after a run, pushed to the fake model."""
    rows = lambda data, dtype: np.frombuffer(data, dtype).reshape(-1, 4).tolist()   # noqa: E731
    page.evaluate(
        """([marks, units, colors, frame, axes]) => {
            fake.push('marks', marks);
            fake.push('units', unitopia.f32(units));
            fake.push('colors', unitopia.u8(colors));
            fake.push('frame', unitopia.f32(frame));
            fake.push('status', 'done');
            fake.push('axes_image', axes);
        }""",
        [w.marks, rows(w.units, np.float32), rows(w.colors, np.uint8), rows(w.frame, np.float32),
         w.axes_image])


def covered(page, boxes) -> int:
    """How many of the axes image's opaque pixels lie inside ``boxes`` (canvas px)."""
    return page.evaluate(
        """([sel, stageSel, boxes]) => {
            const img = document.querySelector(sel), s = document.querySelector(stageSel);
            const r = img.getBoundingClientRect(), st = s.getBoundingClientRect(), k = st.width / 800;
            const c = document.createElement('canvas');
            c.width = Math.round(r.width); c.height = Math.round(r.height);
            const ctx = c.getContext('2d');
            ctx.drawImage(img, 0, 0, c.width, c.height);
            const px = ctx.getImageData(0, 0, c.width, c.height).data;
            let hits = 0;
            for (const [x0, y0, x1, y1] of boxes) {
                const lx = Math.max(0, Math.floor(st.left + x0 * k - r.left)), hx = Math.min(c.width, Math.ceil(st.left + x1 * k - r.left));
                const ly = Math.max(0, Math.floor(st.top + y0 * k - r.top)), hy = Math.min(c.height, Math.ceil(st.top + y1 * k - r.top));
                for (let y = ly; y < hy; y++) for (let x = lx; x < hx; x++) hits += px[4 * (y * c.width + x) + 3] > 0;
            }
            return hits;
        }""",
        [AXES, STAGE, boxes],
    )


def test_the_axes_are_drawn_past_the_canvas_unclipped_and_under_no_mark(page):
    w = laid_out_widget()
    assert w.axes_image, "x= and y= bound and laid out: Python sends the axes"
    mount(page, design=json.loads(json.dumps(w.design)))
    push_widget(page, w)
    axes = page.locator(AXES)
    axes.wait_for(state="visible")
    page.wait_for_function("(s) => document.querySelector(s).complete", arg=AXES)
    next_paint(page)
    stage, box = page.locator(STAGE).bounding_box(), axes.bounding_box()
    wrap = page.locator(".ut-stage-wrap").bounding_box()
    k = stage["width"] / 800
    a = w.axes_image
    assert box["x"] == pytest.approx(stage["x"] + a["x"] * k, abs=1)
    assert box["width"] == pytest.approx(a["width"] * k, abs=1), "at the chart's scale"
    assert box["x"] < stage["x"] - 10 and box["y"] + box["height"] > stage["y"] + stage["height"] + 10, \
        "the y axis' labels left of the canvas, the x axis' under it"
    assert wrap["x"] <= box["x"] and box["x"] + box["width"] <= wrap["x"] + wrap["width"] + 0.5, \
        "the stage keeps a margin for them: the wrap (overflow hidden) clips nothing"
    assert wrap["y"] <= box["y"] and box["y"] + box["height"] <= wrap["y"] + wrap["height"] + 0.5
    p = w.placements
    marks = np.column_stack([p["x"] - p["width"] / 2, p["y"] - p["height"] / 2,
                             p["x"] + p["width"] / 2, p["y"] + p["height"] / 2]).tolist()
    assert covered(page, [[-1e4, -1e4, 1e4, 1e4]]) > 500, "the measure sees the axes' ink"
    assert covered(page, marks) == 0, "no axis line, tick or label over a mark"
    order = page.evaluate(
        "(s) => [...document.querySelector(s).children].map((e) => e.dataset.role || e.className)", STAGE)
    assert order.index("axes") < order.index("ut-canvas"), "under the containers and marks"
    # x= and y= unbound: Python clears the trait, the image and the margin go
    page.evaluate("() => fake.push('axes_image', {})")
    next_paint(page)
    assert axes.count() == 0 and page.locator(".ut-axes-paper").count() == 0
    plain = page.locator(STAGE).bounding_box()
    assert plain["x"] == pytest.approx(wrap["x"], abs=1) and plain["width"] > stage["width"]
