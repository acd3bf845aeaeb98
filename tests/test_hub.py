"""A silhouette footprint keeps other marks out of its hub (``layout/prepare/hub.py``): the
gaps between a spiky mark's arms near its centre count as footprint, so that two flakes
do not end nested one in the other; marks with no such gap are drawn as before."""
from __future__ import annotations

import pathlib
import sys

import numpy as np
import pytest

import unitopia_widget as uw
from unitopia_widget.layout.prepare.assemble import _pyramid
from unitopia_widget.layout.prepare.hub import HUB, with_hub

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmarks"))
from corpus import generate  # noqa: E402
from designs import flake  # noqa: E402


def near_centre(shape, share):
    h, w = shape
    yy, xx = np.ogrid[:h, :w]
    return (yy + 0.5 - h / 2) ** 2 + (xx + 0.5 - w / 2) ** 2 <= (share * min(h, w) / 2) ** 2


def test_the_gaps_between_a_flakes_arms_near_its_centre_become_footprint():
    alpha = flake(6, 0.5, 5.0, "#4e79a7").as_footprint("silhouette").silhouette(256)
    hubbed = with_hub(alpha)
    core = near_centre(alpha.shape, 0.2)
    assert (alpha[core] < 0.5).mean() > 0.1          # the arms leave gaps at the centre
    assert (hubbed[core] >= 0.5).all()               # the hub closes them
    beyond = ~near_centre(alpha.shape, HUB)
    np.testing.assert_array_equal(hubbed[beyond], alpha[beyond])   # the arms' tips stay free
    assert (hubbed >= alpha).all()


@pytest.mark.parametrize("spec", ["circle", "square", "heart", "fa:sun", "star", "cross",
                                  "fa:snowflake"])
def test_a_mark_with_no_gap_at_its_centre_or_a_solid_heart_is_drawn_as_before(spec):
    # a star's, a cross's and the styled snowflake's ink is solid a quarter of the short half
    # side out from the centre: two such hearts overlap wherever the marks would nest
    alpha = uw.Mark.from_spec(spec).as_footprint("silhouette").silhouette(256)
    assert with_hub(alpha) is alpha


def test_a_thin_bar_is_drawn_as_before():
    bar = np.zeros((26, 256), np.float32)
    bar[3:23, 2:254] = 1.0
    assert with_hub(bar) is bar


def test_only_a_silhouette_footprint_has_a_hub():
    mark = flake(6, 0.5, 5.0, "#4e79a7")
    solid, ink = mark.as_footprint("silhouette"), mark.as_footprint("ink")
    assert float(_pyramid(solid, "cpu")[0].sum()) > float(solid.silhouette(256).sum()) + 100
    np.testing.assert_array_equal(_pyramid(ink, "cpu")[0][0, 0].numpy(), ink.silhouette(256))


def test_flakes_crowded_around_lettering_end_with_no_two_nested(tmp_path):
    # corpus seed 0's m038 (flakes of three drawings around "OK", closed, margin 0.1): at
    # layout seed 0 a small flake was carried onto a large one in the first 8 iterations and
    # turned until their arms interleaved; the crowd held it there to the end (centres 0.06
    # of the large one's short half side apart)
    spec = next(s for s in generate.corpus(0, 120) if s.id == "m038")
    chart = generate.build(spec, str(tmp_path), 0).chart
    chart.layout()
    pl = chart.placements
    xy = pl[["x", "y"]].to_numpy()
    short = 0.5 * np.minimum(pl["width"].to_numpy(), pl["height"].to_numpy())
    d = np.hypot(*(xy[:, None] - xy[None]).transpose(2, 0, 1))
    np.fill_diagonal(d, np.inf)
    larger = np.maximum(short[:, None], short[None])
    assert (d / larger).min() > 0.5
