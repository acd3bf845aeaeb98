"""Thin marks whose ink crosses are turned parallel and set side by side (uncross.py, issue 11)."""
import math

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.step.placement import Placement
from unitopia_widget.layout.solver import solve
from unitopia_widget.layout.rules.uncross import ink_pairs, turns

pytestmark = pytest.mark.usefixtures("one_thread")

ROD = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 80">'
                  '<rect width="4" height="80"/></svg>')


def rod_ink(center, angle_deg, half_w, half_h, canvas, k=8):
    """Bool ``(H k, W k)``: the pixels (at ``k`` x) inside a rotated box."""
    y, x = (np.mgrid[0:canvas[1] * k, 0:canvas[0] * k] + 0.5) / k
    a = math.radians(angle_deg)
    dx, dy = x - center[0], y - center[1]
    u, v = dx * math.cos(a) + dy * math.sin(a), -dx * math.sin(a) + dy * math.cos(a)
    return (np.abs(u) <= half_w) & (np.abs(v) <= half_h)


@pytest.mark.parametrize("boundary", ["closed", "open"])
def test_two_rods_crossing_in_an_x_end_side_by_side(boundary):
    # a crossing's overlap (w1 w2 / sin) does not change as a rod slides, and grows as they
    # turn towards parallel: Adam kept the X (closed: 2.2% overlap left after every
    # legalising round; open: the scale shrank by 37% until the rods' ends slid apart)
    canvas = (400, 300)
    df = pd.DataFrame({"v": [1.0, 1.0]})
    kwargs = dict(fill=0.05) if boundary == "open" else {}
    chart = uw.Chart(df, mark=ROD, rotate=True, canvas=canvas, boundary=boundary,
                     container=uw.Container.ellipse(200, 150, 180, 130), **kwargs)
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, canvas, 0, "cpu")
    problem.placement = Placement(np.array([[200.0, 150.0], [200.0, 150.0]]), np.radians([0.0, 60.0]),
                                  np.ones(2, bool), np.ones(2, bool), "cpu")
    start = problem.scale
    result = solve(problem)
    s = result.unit_scale
    inks = [rod_ink(result.center[i], result.angle[i], units.half_w[i] * s[i], units.half_h[i] * s[i],
                    canvas) for i in range(2)]
    assert (inks[0] & inks[1]).sum() == 0
    for i in range(2):   # each rod whole on the canvas (px at 8 x)
        box = 4 * units.half_w[i] * units.half_h[i] * s[i] ** 2
        assert inks[i].sum() == pytest.approx(box * 64, rel=0.02)
    if boundary == "open":   # the fill asked for is kept: no scale given up for the X
        assert result.scale > 0.95 * start


def test_ink_pairs_counts_the_pixels_two_marks_both_ink():
    values = torch.tensor([0.9, 0.9, 0.9, 0.2, 0.8, 0.9, 0.7])
    index = torch.tensor([5, 6, 5, 6, 7, 7, 7], dtype=torch.int32)
    owner = torch.tensor([0, 0, 1, 1, 1, 2, 0])
    pairs, shared = ink_pairs(values, index, owner, 3)
    found = {tuple(p): c for p, c in zip(pairs.tolist(), shared.tolist())}
    # px 5: units 0 and 1; px 6: unit 1 too faint; px 7: units 0, 1, 2 (neighbours in order)
    assert found == {(0, 1): 2.0, (1, 2): 1.0}


def test_turns_both_crossing_rods_to_their_bisector_the_shorter_beside_the_longer():
    center = np.array([[100.0, 100.0], [110.0, 104.0]])
    angle = np.radians([0.0, 130.0])                              # axes 50 degrees apart, mod 180
    half_w, half_h = np.array([40.0, 20.0]), np.array([2.0, 2.0])
    moves = turns(np.array([[0, 1]]), np.array([6.0]), center, angle, half_w, half_h, np.ones(2, bool))
    moves = {unit: (np.array(xy), a) for unit, xy, a in moves}
    assert sorted(moves) == [0, 1]
    assert math.degrees(moves[0][1]) == pytest.approx(-25.0)     # the nearer way round
    assert math.degrees(moves[1][1]) == pytest.approx(155.0)     # parallel: 180 apart
    np.testing.assert_allclose(moves[0][0], center[0])           # the longer keeps its place
    normal = np.array([-math.sin(moves[0][1]), math.cos(moves[0][1])])
    across = (moves[1][0] - center[0]) @ normal
    assert abs(across) == pytest.approx(4.0)                     # side by side, touching
    along = (moves[1][0] - center[1]) @ normal
    assert abs(along) < 4.0 and np.allclose(moves[1][0] - center[1], along * normal)


@pytest.mark.parametrize("case", ["parallel", "tip", "compact", "fixed", "faint"])
def test_turns_leaves_pairs_that_translations_resolve(case):
    center = np.array([[100.0, 100.0], [100.0, 103.0]])
    angle = np.radians([0.0, 10.0 if case == "parallel" else 60.0])
    half_w, half_h = np.array([40.0, 20.0]), np.array([2.0, 2.0])
    turnable, shared = np.ones(2, bool), np.array([6.0])
    if case == "tip":            # the rod's end just touches the other's side: it slides off
        center[1] = [138.0, 100.0 + 20 * math.sin(math.radians(60))]
    if case == "compact":
        half_h = np.array([2.0, 15.0])
    if case == "fixed":
        turnable[1] = False
    if case == "faint":
        shared = np.array([0.0])
    assert turns(np.array([[0, 1]]), shared, center, angle, half_w, half_h, turnable) == []
