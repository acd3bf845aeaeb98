"""Contacts finer than the layout's raster (layout/rules/contacts.py): hollow marks' layouts are
drawn once more at 2 px per canvas px after the solve, and units that touch there move
apart by at most one layout raster pixel."""
from __future__ import annotations

import numpy as np
import pandas as pd
import torch

import unitopia_widget as uw
from ink import ink_metrics
from test_footprint import ELLIPSE, SUN, SVG_RING
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.rules import contacts


def test_two_rings_touching_less_than_a_raster_pixel_deep_move_apart():
    """Two rings 1.5 canvas px deep in each other (under one raster pixel here) are set
    apart, by no more than a raster pixel; a ring clear of both stays where it is."""
    chart = uw.Chart(pd.DataFrame({"v": [1.0, 1.0, 1.0]}), mark=uw.Mark.svg(SVG_RING), size="v",
                     canvas=(400, 300), boundary="closed")
    units = bind(chart.df, chart.layers)
    p = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu")
    scale = np.full(3, 20 / (0.92 * p.half_w[0]))           # the rings' outer radius: 20 canvas px
    outer = 0.92 * p.half_w[0] * scale[0]
    assert 1.5 < 1 / p.grid.rho
    center = np.array([[150.0, 150.0], [150.0 + 2 * outer - 1.5, 150.0], [300.0, 80.0]])
    move = contacts.clear(p, torch.tensor(center, dtype=torch.float32), torch.zeros(3), scale,
                          np.ones(3, dtype=bool), p.placement.rotating())
    after = center + move
    assert np.hypot(*(after[1] - after[0])) >= 2 * outer - 0.5     # within a fine pixel of touching
    assert np.all(np.hypot(*move.T) <= 1 / p.grid.rho + 1e-6) and np.all(move[2] == 0)
    held = contacts.clear(p, torch.tensor(center, dtype=torch.float32), torch.zeros(3), scale,
                          np.zeros(3, dtype=bool), p.placement.rotating())
    assert not held.any()                                         # units that may not move stay


def test_small_suns_keep_their_neighbours_rays_off_their_circle():
    """A big sun's ray tip in the gap between a small sun's circle and rays touched the
    circle, a contact the raster cannot see: 2.77% of that sun's ink before, now within 1%."""
    before = torch.get_num_threads()
    torch.set_num_threads(1)
    df = pd.DataFrame({"v": np.random.default_rng(3).lognormal(0, 0.9, 60)})
    chart = uw.Chart(df, mark=uw.Mark.svg(SUN), size="v", container=uw.Container.ellipse(*ELLIPSE),
                     canvas=(400, 300), boundary="closed", seed=3)
    chart.layout()
    torch.set_num_threads(before)
    m = ink_metrics(chart.to_svg(legend=False), chart.canvas, ellipse=ELLIPSE)
    print(f"largest share of one sun's ink inside another's silhouette: {100 * m['nested_max']:.2f}%")
    assert m["nested_max"] <= 0.01 and m["overlap"] <= 0.01 and m["outside"] <= 0.005
