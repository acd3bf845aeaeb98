"""Fit caps (``layout/prepare/fit.py``): no closed scale grows past where its largest mark
still fits its container by its own shape."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.layout.prepare import fit
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.prepare.lattice import Region

from ink import ink_metrics

pytestmark = pytest.mark.usefixtures("one_thread")

SQUARE = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
                     '<rect width="10" height="10" fill="#555"/></svg>')
FLAT = (200, 150, 190, 45)   # a flat ellipse: its widest disc is 45 px in radius


def test_a_square_fits_a_band_up_to_the_bands_width_at_its_own_angle():
    # a 100 x 40 px band; the square's box has half sides of 1 px at scale 1
    inside = np.zeros((60, 120), bool)
    inside[10:50, 10:110] = True
    region = Region(inside.astype(float), 1.0)
    outside = (~region.inside).astype(np.float32)
    upright = fit.fit_scale(region, outside, SQUARE, 1.0, 1.0, 0.0)
    assert 19.0 <= upright <= 20.5                # 40 px across, to a raster px
    turned = fit.fit_scale(region, outside, SQUARE, 1.0, 1.0, math.radians(45))
    assert 14.0 <= turned <= 14.5                 # its diagonal across: 40 / sqrt(2)


def outlier_chart(seed: int) -> uw.Chart:
    """Forty stars in a flat ellipse, closed; the eighth 20x the median size."""
    v = np.random.default_rng(seed).lognormal(0, 0.3, 40)
    v[7] = 20 * np.median(v)
    return uw.Chart(pd.DataFrame({"v": v}), mark="star", size="v", canvas=(400, 300),
                    container=uw.Container.ellipse(*FLAT), seed=seed)


@pytest.mark.parametrize("seed", [0, 1])
def test_one_mark_of_an_outlying_size_keeps_its_closed_container_and_the_scale_its_fit(seed):
    # the fill controller grew the scale past where the large star fits anywhere: it poked
    # out, 0.35% and 0.39% of the ink at seeds 0 and 1 (the legalising rounds' target: 0.1%)
    chart = outlier_chart(seed)
    chart.layout()
    measured = ink_metrics(chart.to_svg(legend=False), chart.canvas, ellipse=FLAT)
    assert measured["outside"] < 0.001, measured["outside"]
    cap = fit.layer_cap(bind(chart.df, chart.layers), chart.layers[0], chart.canvas, 0)
    assert 0.9 * cap <= chart.result.scale <= cap      # grown up to the cap, not short of it
