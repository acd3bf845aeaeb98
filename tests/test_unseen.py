"""Contacts a capped raster cannot read (``layout/prepare/assemble.py``: ``unseen_depth``,
``padded_margin``): where the raster is capped below the resolution it aims at, its wider
pixels read deeper contacts as apart, and the solver's footprints reach further by the
difference; drawn marks keep their size."""
from __future__ import annotations

import math
import pathlib
import sys

import numpy as np
import pandas as pd
import pytest
from scipy.spatial import cKDTree

import unitopia_widget as uw
from unitopia_widget.design.encodings import footprint
from unitopia_widget.layout.prepare import assemble
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.reflow import rebase

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmarks"))
import discs  # noqa: E402

CAP = 120_000   # raster px: a 400 x 300 canvas at 1 raster px per canvas px, not the 3.6 aimed at


def pile(n: int = 1500) -> uw.Chart:
    """``n`` equal discs poured towards the bottom of a disc, open, filling 60% of it."""
    return uw.Chart(pd.DataFrame({"v": np.ones(n)}), mark="circle", size="v", canvas=(400, 300),
                    seed=0, container=uw.Container.ellipse(200, 150, 140, 140),
                    forces=[uw.PointForce(200, 290)], boundary="open", fill=0.6)


def disc_overlap(placements: pd.DataFrame) -> float:
    """The exact pairwise overlap of the drawn discs, a share of their area."""
    c, r = placements[["x", "y"]].to_numpy(float), placements["width"].to_numpy(float) / 2
    i, j = cKDTree(c).query_pairs(2 * float(r.max()), output_type="ndarray").T
    lens = discs.lens_area(np.hypot(*(c[i] - c[j]).T), r[i], r[j])
    return float(lens.sum() / np.sum(math.pi * r * r))


@pytest.fixture(scope="module")
def capped():
    """The pile laid out on a capped raster (the cap set back after)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(assemble, "MAX_RASTER", CAP)
        chart = pile()
        chart.layout()
    return chart


def test_footprints_reach_the_unseen_depth_further_only_where_the_raster_is_capped(capped):
    p = capped.laid.problem
    assert p.grid.rho <= 1.0 and p.unseen > 0.1   # canvas px: 0.18 here
    scale = p.group_scales()[p.layer_groups()[p.layer]]
    reach = p.half_w * footprint(p.margin) * scale
    assert np.allclose(reach, p.half_w * scale + p.unseen)   # no user margin: the depth alone
    free = pile()
    units = bind(free.df, free.layers)
    q = assemble.build_problem(units, free.layers, free.canvas, 0, "cpu")
    assert q.unseen == 0.0 and q.margin is units.margin


def test_discs_on_a_capped_raster_do_not_overlap_deeper_than_its_pixels(capped):
    # without the depth: 0.23% of the discs' area overlaps, legalize's raster reading 0.1%
    # or less (their contacts are under half a raster pixel deep, in 2.8 px discs)
    assert disc_overlap(capped.placements) < 0.0005


def test_a_reflow_keeps_the_capped_raster_s_footprints(capped):
    base = capped.laid.problem
    again = rebase(base, bind(capped.df, capped.layers), capped.layers)
    assert np.array_equal(again.margin, base.margin) and again.unseen == base.unseen
