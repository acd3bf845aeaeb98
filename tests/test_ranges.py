"""Tests for the linear scale ranges (size_range, width_range, height_range): linear extents,
the legend that says so, the design field, and a container that the range fills."""
import json
import pathlib
import warnings

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.output import publish

pytestmark = pytest.mark.usefixtures("one_thread")
STRAND = pathlib.Path(__file__).parent.parent / "benchmarks" / "data" / "strand.svg"


@pytest.fixture(scope="module")
def strands():
    """Tall strands, heights spread 94x, in a closed square: data-true and with a range."""
    v = np.geomspace(1, 94, 30)
    df = pd.DataFrame({"length": np.random.default_rng(1).permutation(v)})
    box = uw.Container.rect(10, 10, 180, 180)
    out = {}
    for span in (None, (10, 40)):
        c = uw.Chart(df, mark=uw.Mark.svg(STRAND), height="length", height_range=span,
                     container=box, canvas=(200, 200), iterations=150)
        with warnings.catch_warnings():   # data-true, the shortest strands are thin
            warnings.simplefilter("ignore", UserWarning)
            c.layout()
        out[span] = c
    return out


def test_a_range_maps_values_linearly_onto_extents():
    df = pd.DataFrame({"v": [1.0, 4.0, 5.5, 10.0]})
    for channel, axis in (("size", "half_h"), ("width", "half_w"), ("height", "half_h")):
        c = uw.Chart(df, mark="square", **{channel: "v", f"{channel}_range": (10, 40)})
        side = getattr(bind(df, c.layers), axis)
        # extents 10, 20, 25, 40 px up to the global scale: in ratio, and linear in the value
        np.testing.assert_allclose(side / side[0], [1, 2, 2.5, 4], rtol=1e-9)


def test_without_a_range_sizes_stay_data_true():
    df = pd.DataFrame({"v": [1.0, 4.0]})
    units = bind(df, uw.Chart(df, mark="square", size="v").layers)
    np.testing.assert_allclose(units.area[1] / units.area[0], 4.0)


def test_a_range_fills_a_container_that_data_true_heights_leave_empty(strands):
    covered = {span: float((c.placements.width * c.placements.height).sum()) / 180 ** 2
               for span, c in strands.items()}
    assert covered[(10, 40)] > 1.8 * covered[None], covered
    heights = strands[(10, 40)].placements.height
    assert 3.5 < heights.max() / heights.min() < 4.5   # the range's 40 / 10


def test_the_legend_says_the_scale_is_linear_with_its_drawn_px(strands):
    c = strands[(10, 40)]
    key = publish.sections(c, c._units)[-1]
    h = c.placements.height
    assert f"linear {h.min():.3g}-{h.max():.3g} px, not data-true" in key.entries[0].label
    svg = c.to_svg()
    assert "not data-true" in svg and "not data-true" not in strands[None].to_svg()


def test_a_size_range_legend_is_linear_and_says_it_is_not_area_true():
    df = pd.DataFrame({"v": np.linspace(1, 100, 12)})
    c = uw.Chart(df, mark="square", size="v", size_range=(8, 24), canvas=(300, 200),
                 iterations=60)
    c.layout()
    size = next(s for s in publish.sections(c, c._units) if s.title.startswith("Size"))
    assert "linear" in size.title and "not area-true" in size.title
    values = np.array([float(e.value) for e in size.entries])
    sides = np.array([e.h for e in size.entries])
    slope = np.polyfit(values, sides, 1)
    np.testing.assert_allclose(np.polyval(slope, values), sides, rtol=1e-6)   # linear
    w = c.placements.width   # a square's side: the legend's extents are the drawn ones
    lo_px, hi_px = w.min(), w.max()
    np.testing.assert_allclose(np.polyval(slope, [1, 100]), [lo_px, hi_px], rtol=1e-3)


def test_a_range_is_saved_in_the_design_and_loaded(tmp_path):
    df = pd.DataFrame({"v": [1.0, 3.0]})
    c = uw.Chart(df, mark="circle", width="v", width_range=[5, 20])
    path = tmp_path / "d.json"
    c.save(path)
    assert json.loads(path.read_text())["layers"][0]["width_range"] == [5.0, 20.0]
    assert uw.Chart.load(path, df).layers[0].width_range == (5.0, 20.0)
    assert "size_range" not in uw.Chart(df).design()["layers"][0]   # additive: absent unless set


@pytest.mark.parametrize("kwargs, message", [
    (dict(size_range=(10, 40)), "size_range=(10.0, 40.0) needs size=<column>"),
    (dict(size="v", size_range=(40, 10)), "0 < min_px <= max_px"),
    (dict(size="v", size_range=(0, 10)), "0 < min_px <= max_px"),
    (dict(height="v", height_range="big"), "height_range must be None or (min_px, max_px)"),
])
def test_bad_ranges_are_refused_naming_the_argument(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        uw.Chart(pd.DataFrame({"v": [1.0, 2.0]}), **kwargs)
