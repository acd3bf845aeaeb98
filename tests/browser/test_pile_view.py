"""The widget draws the piles Python lays out: each pile's container on the scene canvas and
its label as SVG <text class="pile-label"> under it, moving with the container."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from test_frontend import STAGE, mount, next_paint

import unitopia_widget as uw
from unitopia_widget.design.piles import LABEL_GAP

pytestmark = pytest.mark.browser


def test_the_piles_containers_and_labels_are_drawn_under_each_pile(page):
    df = pd.DataFrame({"kind": np.repeat(["ant", "bee", "cat"], [10, 20, 5])})
    w = uw.UnitoPia(df, by="kind", canvas=(800, 500))
    boxes = [(c["x"], c["y"], c["w"], c["h"]) for c in (x["container"] for x in w.design["layers"])]
    mount(page, design=json.loads(json.dumps(w.design)), pile_labels=w.pile_labels)
    page.wait_for_function(
        """(boxes) => { const c = document.querySelectorAll('[data-role="stage"] canvas')[0];
                   const k = c.width / 800, ctx = c.getContext('2d');
                   const alpha = (x, y) => ctx.getImageData(Math.round(x * k), Math.round(y * k), 1, 1).data[3];
                   return boxes.every(([x, y, w, h]) => alpha(x + w / 2, y + h - 2) > 0)
                       && alpha((boxes[0][0] + boxes[0][2] + boxes[1][0]) / 2, 490) === 0; }""",
        arg=boxes)
    stage = page.locator(STAGE).bounding_box()
    k = stage["width"] / 800
    texts = page.locator("svg text.pile-label")
    assert texts.all_text_contents() == ["ant", "bee", "cat"]
    for i, (x, y, w_, h) in enumerate(boxes):
        box = texts.nth(i).bounding_box()
        assert box["y"] >= stage["y"] + (y + h) * k, "under its pile"
        assert box["y"] + box["height"] <= stage["y"] + stage["height"] + 1, "on the canvas"
        assert box["x"] + box["width"] / 2 == pytest.approx(stage["x"] + (x + w_ / 2) * k, abs=2)
    # the user moves a pile (Python answers with the design and labels): the label follows
    w.layer("ant").set(container=uw.Container.rect(20, 100, 200, 200))
    page.evaluate("([d, l]) => { fake.push('design', d); fake.push('pile_labels', l); }",
                  [json.loads(json.dumps(w.design)), w.pile_labels])
    next_paint(page)
    box = texts.nth(0).bounding_box()
    assert box["y"] == pytest.approx(stage["y"] + (300 + LABEL_GAP) * k, abs=4)
