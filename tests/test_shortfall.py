"""What a layout could not give is said: an open fill its marks do not reach, and a closed
container left empty because one mark caps the scale (``layout/shortfall.py``)."""
from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.shortfall import warn_curve_held, warn_unreached_fill

pytestmark = pytest.mark.usefixtures("one_thread")

BAR = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 10">'
                  '<rect width="100" height="10" fill="#555"/></svg>')


def said(run) -> list:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run()
    return [str(w.message) for w in caught]


def test_thin_bars_that_miss_their_open_fill_say_so_and_what_was_laid_out():
    # 10:1 bars pushed right into an open pen jam across each other: at the default fill
    # (none set) they reach 0.37 of the pen, silently until the check
    c = uw.Chart(pd.DataFrame({"v": np.random.default_rng(1).uniform(1, 3, 30)}), mark=BAR,
                 size="v", orientation=0.0, container=uw.Container.rect(20, 20, 260, 160),
                 boundary="open", canvas=(300, 200), forces=[uw.DirectionalForce(0)], seed=0)
    fills = [m for m in said(c.layout) if "fill=" in m]
    assert len(fills) == 1 and "fill=0.5 is more than its marks reach" in fills[0], fills
    assert "long thin marks" in fills[0] and "Lower fill=" in fills[0]
    assert "margin" not in fills[0]       # none set: not a remedy
    lowered = float(fills[0].split("laid out at fill=")[1].split(":")[0])
    reached = float((c.units.area * c.result.unit_scale ** 2).sum()) / (260 * 160)
    assert lowered == pytest.approx(reached, abs=0.01) and lowered < 0.8 * 0.5


def band_chart(fill, margin=0.0):
    """Ten discs open in a band 30 px high."""
    return uw.Chart(pd.DataFrame({"v": np.ones(10)}), mark="circle", size="v", fill=fill,
                    margin=margin, container=uw.Container.rect(0, 35, 400, 30),
                    boundary="open", canvas=(400, 100))


@pytest.mark.parametrize("kept", [0.95, 0.7])
def test_an_open_fill_is_warned_only_when_the_final_scale_leaves_it_short(kept):
    c = band_chart(0.2)
    units = bind(c.df, c.layers)
    asked = np.sqrt(0.2 * 400 * 30 / units.area.sum())
    out = said(lambda: warn_unreached_fill(units, c.layers, c.canvas,
                                           np.full(len(units.rows), kept * asked)))
    assert len(out) == (kept < 0.9), out
    if out:
        assert "laid out at fill=0.098" in out[0] and "drawn at 70% of the size" in out[0]


def test_a_band_narrower_than_its_marks_at_the_asked_fill_is_named_with_its_width():
    # at fill 0.8 each disc would be 35 px across, in a band 30 px wide
    c = band_chart(0.8, margin=0.4)
    units = bind(c.df, c.layers)
    asked = np.sqrt(0.8 * 400 * 30 / units.area.sum())
    out = said(lambda: warn_unreached_fill(units, c.layers, c.canvas,
                                           np.full(len(units.rows), 0.6 * asked)))
    assert len(out) == 1, out
    assert "the container is 30 px across at its widest and the largest mark would be" in out[0]
    assert "margin=0.4 included" in out[0] and "lower margin=" in out[0]


def tall_column(outlier: bool):
    v = np.random.default_rng(0).lognormal(0, 0.3, 30)
    if outlier:
        v[7] = 40 * np.median(v)
    return uw.Chart(pd.DataFrame({"v": v}, index=[f"r{i}" for i in range(30)]), mark="square",
                    height="v", container=uw.Container.ellipse(200, 150, 150, 100),
                    canvas=(400, 300), seed=0)


@pytest.mark.parametrize("outlier", [True, False])
def test_one_mark_that_caps_a_closed_scale_is_named_with_its_row_value_and_range(outlier):
    c = tall_column(outlier)
    capped = [m for m in said(c.layout) if "caps the scale" in m]
    if not outlier:
        assert not capped
        return
    assert len(capped) == 1, capped
    value = c.df.loc["r7", "v"]
    assert f"row 'r7' (height={value:.4g})" in capped[0]
    assert "height_range=(min_px, max_px)" in capped[0] and "size_range" not in capped[0]
    covered = float(capped[0].split("the marks cover ")[1].split("%")[0])
    empty = float(capped[0].split("and leave ")[1].split("%")[0])
    assert covered < 25 and empty > 50


def test_a_square_held_where_it_stops_fitting_a_slanted_band_is_named_too():
    # a band 70 px wide at 37 degrees: a square fits it upright only about 50 px across,
    # 0.7 of the band's widest disc, where the fill controller stops growing the scale
    # (``fit.layer_cap``); the other squares are 6 px, and 70% of the band is left empty
    v = np.random.default_rng(0).uniform(1, 2, 40)
    v[7] = 100
    a = np.arctan2(300, 400)
    along, across = 420 * np.array([np.cos(a), np.sin(a)]), 70 * np.array([-np.sin(a), np.cos(a)])
    corner = np.array([40.0, 30.0])
    band = [tuple(p) for p in (corner, corner + along, corner + along + across, corner + across)]
    c = uw.Chart(pd.DataFrame({"v": v}), mark="square", size="v", container=uw.Container.polygon(band),
                 canvas=(480, 360), seed=0)
    capped = [m for m in said(c.layout) if "caps the scale" in m]
    assert len(capped) == 1 and "row 7 (size=100)" in capped[0], capped
    side = c.placements.loc[7, "width"]
    assert 45 < side < 52   # held at the fit, not the disc (70 px)


STRAND = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 100">'
                     '<rect x="3.5" width="3" height="100" fill="#555"/></svg>')


def test_thin_marks_that_fill_their_container_are_not_said_to_leave_it_empty():
    # heights on a range of 20 to 80 px: the tallest strand, 4x the shortest and over 3x the
    # median, caps the scale, and the strands' footprints cover a quarter of the container;
    # but they stand all over it (6% of it is far from every strand), so nothing is said
    v = np.random.default_rng(5).lognormal(0, 1, 70)
    c = uw.Chart(pd.DataFrame({"v": v}), mark=STRAND, height="v", height_range=(20, 80),
                 container=uw.Container.ellipse(200, 150, 170, 120), canvas=(400, 300), seed=0)
    out = said(c.layout)
    assert not [m for m in out if "caps the scale" in m], out
    long = c.placements["height"].to_numpy()
    assert long.max() > 3 * np.median(long)   # the outlier test alone would have warned


def curve_chart(mode: str, boundary: str):
    """Sixty discs tied to a 200 px curve along the top of a 360 x 250 box."""
    top = [[100, 50], [180, 50], [220, 50], [300, 50]]
    return uw.Chart(pd.DataFrame({"v": np.ones(60)}), mark="circle", size="v",
                    emitter=uw.CurveEmitter(top, mode=mode), boundary=boundary,
                    fill=0.4 if boundary == "open" else None,
                    container=uw.Container.rect(20, 40, 360, 250), canvas=(400, 300))


@pytest.mark.parametrize("mode", ["line", "band", "free"])
def test_marks_tied_to_a_curve_too_short_for_them_are_named_with_the_curve(mode):
    # at fill 0.4 each disc would be about 28 px across: 60 of them end to end need 1,650 px of a
    # 200 px curve; drawn at a sixth of that size
    c = curve_chart(mode, "open")
    units = bind(c.df, c.layers)
    out = said(lambda: warn_unreached_fill(units, c.layers, c.canvas, np.full(60, 4.0)))
    assert len(out) == 1, out
    tied = f"are tied to its emitter's curve (mode={mode!r}), 200 px long, which holds them " \
        "end to end only at 12% of that size"
    assert (tied in out[0]) == (mode != "free"), out
    assert ("mode='free'" in out[0]) == (mode != "free")
    closed = curve_chart(mode, "closed")
    units = bind(closed.df, closed.layers)
    out = said(lambda: warn_curve_held(units, closed.layers, closed.canvas, np.full(60, 4.0)))
    assert len(out) == (mode != "free"), out
    if out:
        assert "the marks cover 1% of their closed container" in out[0] and \
            f"(mode={mode!r}), 200 px long" in out[0] and "Use CurveEmitter(mode='free')" in out[0]
    out = said(lambda: warn_curve_held(units, closed.layers, closed.canvas, np.full(60, 40.0)))
    assert out == []                      # a full container: nothing to say


def strata_chart(blocks: bool):
    """Two layers of discs pulled down into an open box, the second blocking on the first."""
    df = pd.DataFrame({"v": np.ones(40), "k": np.repeat([0, 1], 20)})
    c = uw.Chart(df, mark="circle", size="v", by="k", color="k", fill=0.6,
                 container=uw.Container.rect(50, 50, 300, 200), boundary="open",
                 forces=[uw.DirectionalForce(90)], canvas=(400, 300))
    if blocks:
        c.layer("1").set(blocks=["0"])
    return c


@pytest.mark.parametrize("blocks", [True, False])
def test_an_open_fill_short_in_strata_names_the_layers_that_rest_on_others(blocks):
    c = strata_chart(blocks)
    units = bind(c.df, c.layers)
    asked = np.sqrt(0.6 * 300 * 200 / units.area.sum())
    out = said(lambda: warn_unreached_fill(units, c.layers, c.canvas,
                                           np.full(len(units.rows), 0.7 * asked)))
    assert len(out) == 1, out
    assert ("layer '1' rests on the layers it blocks on, in strata" in out[0]) == blocks, out[0]
