"""Marks that end outside their container (layout/rules/strays.py): brought back, after the
solve, to the nearest spot wholly inside it and on no other mark."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.rules import strays
from unitopia_widget.layout.rules.state import shift


def problem(center, container=uw.Container.ellipse(200, 150, 120, 90), margin=0.0):
    chart = uw.Chart(pd.DataFrame({"v": [1.0] * len(center)}), mark="circle", size="v",
                     canvas=(400, 300), container=container, boundary="closed", margin=margin)
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


def test_a_mark_poking_out_by_a_third_of_its_ink_moves_in_and_one_grazing_the_wall_stays():
    # the ellipse's left end is x = 80: one circle's centre 3 px inside it (a third of its
    # ink out), one at the right end's wall with a sliver out, one in the middle
    center = np.array([[83.0, 150.0], [309.5, 150.0], [200.0, 150.0]])
    p, scale = problem(center)
    after = center + strays.bring_back(p, p.placement, scale)
    assert np.array_equal(after[1:], center[1:])                       # the sliver stays
    x, y = after[0]
    assert 89.5 <= x < 95 and abs(y - 150) < 5   # pushed in (its fine pixels inside), nearest


def test_a_mark_of_a_layer_resting_on_another_is_not_moved_into_that_layers_shadow():
    # a row of circles across a box (layer 0) and, under a pull down, a layer resting on it:
    # its one circle pokes out of the left wall below the row, where its nearest free spot
    # would be under the row; it must go above it
    df = pd.DataFrame({"k": [0] * 19 + [1], "v": 1.0})
    chart = uw.Chart(df, mark="circle", size="v", by="k", canvas=(400, 300), boundary="open",
                     container=uw.Container.rect(10, 10, 380, 280),
                     forces=[uw.DirectionalForce(90)])
    chart.layer("1").set(blocks=["0"])
    p = engine.build_problem(bind(chart.df, chart.layers), chart.layers, chart.canvas, 0, "cpu")
    center = np.zeros((20, 2))
    row = np.flatnonzero(p.layer == 0)
    center[row] = np.stack([20.0 + 20 * np.arange(19), np.full(19, 200.0)], 1)
    lone = int(np.flatnonzero(p.layer == 1)[0])
    center[lone] = (13.0, 250.0)
    with torch.no_grad():
        p.placement.t[:] = torch.tensor(center, dtype=torch.float32)
    scale = np.full(20, 10 / p.half_w[0])                              # circles 10 px in radius
    after = center + strays.bring_back(p, p.placement, scale)
    assert np.array_equal(np.delete(after, lone, 0), np.delete(center, lone, 0))
    x, y = after[lone]
    assert 20 <= x and y <= 180                                        # in, above the row


@pytest.mark.parametrize("gap", [True, False])
def test_a_jammed_bottom_mark_goes_beyond_the_strata_on_it_only_where_nothing_nearer_is_free(gap):
    # under a pull down, a row of circles on the floor (layer 0), an extra circle of it
    # jammed into the row, and a row of the layer resting on it (layer 1) just above: the
    # nearest free spot is on top of layer 1's row, which would set it beyond the layer that
    # rests on it. With a gap in its own row, one of the pair goes there; without, on top
    x = 20.0 + 20 * np.arange(19)
    row = np.delete(x, 4) if gap else x                                # the gap at x 100
    df = pd.DataFrame({"k": [0] * (len(row) + 1) + [1] * 19, "v": 1.0})
    chart = uw.Chart(df, mark="circle", size="v", by="k", canvas=(400, 300), boundary="open",
                     container=uw.Container.rect(10, 10, 380, 265),
                     forces=[uw.DirectionalForce(90)])
    chart.layer("1").set(blocks=["0"])
    p = engine.build_problem(bind(chart.df, chart.layers), chart.layers, chart.canvas, 0, "cpu")
    floor, top = np.flatnonzero(p.layer == 0), np.flatnonzero(p.layer == 1)
    center = np.zeros((len(df), 2))
    center[floor[:-1]] = np.stack([row, np.full(len(row), 263.0)], 1)
    center[floor[-1]] = (200.0, 258.0)                                  # jammed into the row
    center[top] = np.stack([x, np.full(19, 231.0)], 1)       # 12 px above the floor's row
    with torch.no_grad():
        p.placement.t[:] = torch.tensor(center, dtype=torch.float32)
    scale = np.full(len(df), 10 / p.half_w[0])                         # circles 10 px in radius
    move = strays.bring_back(p, p.placement, scale)
    moved = np.flatnonzero(np.abs(move).sum(1))
    assert len(moved) == 1 and p.layer[moved[0]] == 0   # one of the pair: the other is then free
    x, y = center[moved[0]] + move[moved[0]]
    if gap:
        assert abs(x - 100) < 5 and y > 250                            # in the gap, not on top
    else:
        assert y < 221                                                 # on top: the one free spot


def test_a_mark_left_deep_in_another_moves_to_the_nearest_free_spot_and_one_touching_stays():
    # two circles 10 px in radius half on top of each other, and a pair barely touching
    center = np.array([[150.0, 150.0], [160.0, 150.0], [250.0, 150.0], [269.5, 150.0]])
    p, scale = problem(center)
    after = center + strays.bring_back(p, p.placement, scale)
    assert np.array_equal(after[2:], center[2:])                       # the touching pair stays
    assert (after[:2] != center[:2]).any(axis=1).sum() == 1            # one of the two moves
    gap = np.hypot(*(after[0] - after[1]))
    assert 19.5 <= gap < 23                                            # to the nearest free spot


@pytest.mark.parametrize("inside, lands", [
    # its footprint clear of theirs (centres 40 px apart): right of the one at 200, not
    # between the two
    ([140.0, 200.0], (239.5, 246.0)),
    # no spot clears their footprints: its ink clear of them (centres 30 px apart), by the
    # band's left end
    ([145.0, 205.0, 265.0], (109.5, 116.0)),
])
def test_a_mark_whose_margins_fit_nowhere_comes_in_giving_up_the_margins_first(inside, lands):
    # a band 26 px high (x 100..300): circles 10 px in radius fit, their footprints (margin 1:
    # 20 px in radius) nowhere. Some sit inside it; the last is outside, left of the band.
    band = uw.Container.rect(100, 137, 200, 26)
    center = np.array([[x, 150.0] for x in inside] + [[40.0, 150.0]])
    p, scale = problem(center, band, margin=1.0)
    after = center + strays.bring_back(p, p.placement, scale, strays.StraysSettings(reach=0.6))
    assert np.array_equal(after[:-1], center[:-1])
    x, y = after[-1]
    assert lands[0] <= x < lands[1] and abs(y - 150) <= 3               # its ink inside, nearest


def test_a_mark_giving_its_margins_up_keeps_its_ink_a_fine_pixel_from_the_wall():
    # two bands: the nearer (x 100..200) half a px taller than a circle 10 px in radius, the
    # farther (x 220..320) 4 px taller; its footprint (margin 1) fits neither. Its ink would
    # fit the nearer flush against both walls, where an exporter's drawing of the mark can
    # differ from the engine's by a pixel: it goes to the farther, a fine px in from its end
    c = uw.Container.path("M 100 140 H 200 V 160.5 H 100 Z M 220 138 H 320 V 162 H 220 Z")
    center = np.array([[60.0, 150.0]])
    p, scale = problem(center, c, margin=1.0)
    dense = strays.StraysSettings(reach=0.45, spacing=0.01, across=100_000)   # every fine px
    x, y = (center + strays.bring_back(p, p.placement, scale, dense))[0]
    assert x == 230.5 and abs(y - 150) <= 1.5


def test_a_mark_of_a_band_left_outside_comes_back_along_its_curves_normal():
    # a curve emitter in band mode along a box's middle (y 150): marks keep their order along
    # the curve and stack along its normal. One ended above the box: it comes back straight
    # down its normal, its place along the curve (x) kept, and on no other mark; the rest stay
    df = pd.DataFrame({"v": [1.0] * 5, "when": range(5)})
    chart = uw.Chart(df, mark="circle", size="v", order="when", canvas=(400, 300),
                     container=uw.Container.rect(50, 120, 300, 60), boundary="closed",
                     emitter=uw.CurveEmitter([[60, 150], [160, 150], [240, 150], [340, 150]],
                                             mode="band"))
    p = engine.build_problem(bind(chart.df, chart.layers), chart.layers, chart.canvas, 0, "cpu")
    track = p.placement.tracks[0]
    with torch.no_grad():
        track.u[:] = torch.tensor([40.0, 90.0, 140.0, 190.0, 240.0])
        track.v[:] = torch.tensor([0.0, 0.0, -60.0, 0.0, 0.0])          # the third 60 px up
    before = p.placement.transforms()[0].detach().numpy().copy()
    scale = np.full(5, 10 / p.half_w[0])                                # circles 10 px in radius
    move = strays.bring_back(p, p.placement, scale)
    assert shift(p.placement, move)
    after = p.placement.transforms()[0].detach().numpy()
    lone = int(track.index[2])
    assert np.allclose(np.delete(after, lone, 0), np.delete(before, lone, 0))
    x, y = after[lone]
    assert x == pytest.approx(before[lone, 0], abs=1e-3)               # along the curve: kept
    assert 130 <= y <= 140                                              # wholly inside, nearest
    assert float(track.u.detach()[2]) == pytest.approx(140.0)


def test_marks_too_faint_for_the_layouts_raster_are_still_seen_on_top_of_each_other():
    # circles 1 px in radius on a raster of 4 canvas px a pixel: no footprint reaches half a
    # pixel's alpha, so two stacked read as no overlap there (the loss counts alpha past 1).
    # Read on the fine raster, the upper one moves to the nearest free spot beside the other
    center = np.array([[200.0, 150.0], [200.3, 150.2], [240.0, 150.0]])
    p, _ = problem(center)
    scale = np.full(3, 1 / p.half_w[0])
    assert p.grid.rho == 0.25
    at, angle = (t.detach() for t in p.placement.transforms())
    feet = strays.samples(p, p.grid, at, angle, p.half_w * scale, p.half_h * scale,
                          p.placement.rotating())
    assert not strays.overlapped(p, feet).any() and strays.faint(feet, 3)[:2].all()
    after = center + strays.bring_back(p, p.placement, scale)
    assert np.array_equal(after[[0, 2]], center[[0, 2]])
    assert 1.0 <= np.hypot(*(after[1] - center[1])) <= 3.0             # beside it, nearest


def test_a_mark_too_faint_for_the_layouts_raster_is_still_seen_outside():
    # a circle 1 px in radius whose ink lies left of a box's wall (x 81): the layout's raster
    # (4 canvas px a pixel) reads its centre inside and none of its ink out; read on the
    # fine raster, it moves in to the nearest spot, its ink wholly inside
    center = np.array([[200.0, 150.0], [80.0, 150.0]])
    p, _ = problem(center, uw.Container.rect(81, 60, 240, 180))
    scale = np.full(2, 1 / p.half_w[0])
    at, angle = (t.detach() for t in p.placement.transforms())
    assert not strays.outside(p, center, np.arange(2)).any()
    assert strays.ink_outside(p, at, angle, scale, p.placement.rotating())[1] < 0.05
    after = center + strays.bring_back(p, p.placement, scale)
    assert np.array_equal(after[0], center[0])
    assert 82.0 <= after[1, 0] <= 83.0 and after[1, 1] == 150.0
