"""Marks that end outside their container (layout/rules/strays.py): brought back, after the
solve, to the nearest spot wholly inside it and on no other mark."""
from __future__ import annotations

import numpy as np
import pandas as pd
import torch

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.rules import strays


def problem(center):
    chart = uw.Chart(pd.DataFrame({"v": [1.0] * len(center)}), mark="circle", size="v",
                     canvas=(400, 300), container=uw.Container.ellipse(200, 150, 120, 90),
                     boundary="closed")
    p = engine.build_problem(bind(chart.df, chart.layers), chart.layers, chart.canvas, 0, "cpu")
    with torch.no_grad():
        p.placement.t[:] = torch.tensor(center, dtype=torch.float32)
    return p, np.full(len(center), 10 / p.half_w[0])      # circles 10 canvas px in radius


def test_a_mark_left_outside_its_container_moves_to_the_nearest_free_spot_inside():
    center = np.array([[200.0, 150.0], [225.0, 150.0], [40.0, 150.0]])   # the ellipse: x 80..320
    p, scale = problem(center)
    after = center + strays.bring_back(p, p.placement, scale)
    assert np.array_equal(after[:2], center[:2])                       # the ones inside stay
    x, y = after[2]
    assert ((x - 200) / 110) ** 2 + ((y - 150) / 80) ** 2 <= 1.0 + 1e-6   # wholly inside
    assert 90 <= x < 100                                               # by the left end, nearest
    assert np.hypot(*(after[2] - after[:2]).T).min() >= 20             # on no other circle


def test_a_mark_with_no_free_spot_in_reach_stays():
    center = np.array([[200.0, 150.0], [40.0, 150.0]])
    p, scale = problem(center)
    move = strays.bring_back(p, p.placement, scale, strays.StraysSettings(reach=0.05))
    assert not move.any()                                              # the wall is 50 px away
