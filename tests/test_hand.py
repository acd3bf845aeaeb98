"""Hand control (issue 22): pins held in place as obstacles for every layer of their
container, data replaced by ``set_data``, runs that start from the last layout, and
``fresh=True``. One 150-mark layout of two layers in one ellipse, shared by the tests."""
import json
import warnings

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.chart import Chart

from laid import laid_copy

pytestmark = pytest.mark.usefixtures("one_thread")

ELLIPSE = uw.Container.ellipse(200, 150, 185, 135)


def data(n: int, start: int = 0) -> pd.DataFrame:
    rng = np.random.default_rng(start + 7)
    return pd.DataFrame({"v": rng.uniform(1, 3, n), "g": np.where(np.arange(n) % 3, "a", "b")},
                        index=range(start, start + n))


@pytest.fixture(scope="module")
def base():
    """A fresh layout of 150 circles: layer "a" blocks on "b", "b" ignores "a"."""
    chart = Chart(data(150), size="v", by="g", container=ELLIPSE, canvas=(400, 300),
                  iterations=300)
    chart.layer("a").set(blocks=["b"])
    chart.layout()
    return chart


@pytest.fixture
def chart(base):
    """A copy of the laid-out base chart for one test to change (its last run included)."""
    return laid_copy(base)


def radius(table):
    return table["width"].to_numpy() / 2


def gaps(table, rows, layer=None):
    """For each of ``rows``: the smallest gap (px) between its circle and any other (of
    ``layer`` only, where given), as a share of the two radii (negative: they overlap)."""
    xy, r = table[["x", "y"]].to_numpy(), radius(table)
    out = []
    for k in np.nonzero(table["row"].isin(rows).to_numpy())[0]:
        d = np.hypot(*(xy - xy[k]).T) - r - r[k]
        d[k] = np.inf
        if layer is not None:
            d[table["layer"].to_numpy() != layer] = np.inf
        out.append(float(np.min(d / (r + r[k]))))
    return np.array(out)


def displacement(before, after):
    m = before.merge(after, on=["layer", "row"], suffixes=("", "_2"))
    return np.hypot(m.x - m.x_2, m.y - m.y_2)


def test_a_second_run_with_no_change_gives_identical_placements(chart, base):
    again = chart.layout()
    pd.testing.assert_frame_equal(again, base.placements)


def test_a_run_with_nothing_changed_returns_the_last_layout_and_shows_its_frame(chart, base):
    shown = []
    again = chart.layout(on_frame=shown.append)
    assert chart.laid is base.laid and again is base.placements, "no new run"
    assert len(shown) == 1 and np.array_equal(shown[0], base.frames[-1])
    progress = []
    chart.layout(on_progress=lambda *a: progress.append(a))
    assert progress == [(base.result.iterations, base.result.stats["loss"],
                         {**base.result.stats, "phase": "finish"})]


@pytest.mark.parametrize("change", ["value", "dtype", "margin", "seed", "device", "fresh"])
def test_a_change_anywhere_runs_the_layout_again(chart, base, change):
    fresh = False
    if change == "value":   # one value of one row, edited in place (in a copy of the shared rows)
        chart.set_data(chart.df.copy())
        chart.df.loc[chart.df.index[7], "v"] += 0.5
    elif change == "dtype":   # equal values, another dtype: a run of its own
        chart.set_data(chart.df.astype({"v": "float32"}))
    elif change == "margin":
        chart.layer("b").set(margin=0.2)
    elif change == "seed":
        chart.seed = 1
    elif change == "device":
        chart._ran = (*chart._ran[:2], "cuda")   # as if the last run was on another device
    else:   # the last run as if warm: a fresh one starts elsewhere
        chart._origin, fresh = chart._snapshot, True
    chart.layout(fresh=fresh)
    assert chart.laid is not base.laid


def test_a_stopped_run_is_not_returned_again(chart):
    chart.seed = 2
    chart.layout(cancel=lambda: True)
    stopped = chart.laid
    assert stopped.result.cancelled
    chart.layout()
    assert chart.laid is not stopped and not chart.result.cancelled


def test_pinned_rows_stay_on_their_pins_and_every_layer_keeps_off_them(chart):
    # rows of layer "a" pinned where layer "b" marks are now ("b" does not block on "a")
    b = chart.placements[chart.placements.layer == "b"]
    rows = [1, 2, 4]
    chart.pin(rows, x=b.x.to_numpy()[:3], y=b.y.to_numpy()[:3])
    table = chart.layout()
    held = table.set_index("row").loc[rows]
    pins = chart.pinned.set_index("row").loc[rows]
    assert np.hypot(held.x - pins.x, held.y - pins.y).max() <= 1.0
    # "b" ignores "a" but keeps off its pins; marks of "a" touch a pin as they touch any mark
    assert gaps(table, rows, layer="b").min() > -0.05, "no mark of 'b' overlaps a pinned one"
    assert gaps(table, rows).min() > -0.1, "no mark overlaps a pinned one by a tenth of their radii"
    assert chart.result.stats["overlap"] < 0.005


def test_a_pin_outside_its_container_is_refused_naming_the_row_and_position(chart):
    with pytest.raises(ValueError, match=r"pin of row 3 at \(5\.0, 5\.0\) is outside"):
        chart.pin(3, x=5, y=5)
    assert chart.pinned.empty
    with pytest.raises(ValueError, match="pin: x has 2 values for 1 rows"):
        chart.pin([3], x=[100, 120], y=150)


def test_pins_default_to_the_current_place_and_are_saved_in_the_design(chart):
    chart.pin([0, 3])
    now = chart.placements.set_index("row").loc[[0, 3]]
    pins = chart.pinned.set_index("row")
    np.testing.assert_allclose(pins[["x", "y"]].to_numpy(), now[["x", "y"]].to_numpy())
    design = json.loads(json.dumps(chart.design()))
    assert [p["row"] for p in design["pins"]] == [0, 3]
    other = Chart.from_design(data(150), design)
    pd.testing.assert_frame_equal(other.pinned, chart.pinned)
    chart.unpin(0)
    assert chart.pinned.row.tolist() == [3]
    chart.unpin()
    assert "pins" not in chart.design(), "a design without pins has no pins field"
    bad = {**design, "pins": [{"layer": "a", "row": 999, "x": 200, "y": 150}]}
    with pytest.raises(ValueError, match="row 999 names a row that layer 'a' does not draw"):
        Chart.from_design(data(150), bad)


def test_added_rows_keep_the_old_marks_in_place(chart, base):
    chart.set_data(pd.concat([data(150), data(8, start=1000)]))
    table = chart.layout()
    moved = displacement(base.placements, table)
    assert len(moved) == 150 and len(table) == 158
    assert np.median(moved) <= np.median(radius(base.placements))
    assert chart.result.stats["overlap"] < 0.005
    # the added rows entered inside the container
    new = table[table.row >= 1000]
    assert (((new.x - 200) / 185) ** 2 + ((new.y - 150) / 135) ** 2 < 1).all()


def test_removed_rows_disappear_and_the_container_fills_again(chart, base):
    chart.set_data(data(150).drop(index=range(0, 150, 20)))
    table = chart.layout()
    assert len(table) == 150 - 8 and not table.row.isin(range(0, 150, 20)).any()
    assert chart.result.stats["fill"] >= base.result.stats["fill"] - 0.02
    assert chart.result.stats["overlap"] < 0.005


def test_fresh_starts_over_and_set_data_drops_pins_of_gone_rows(chart, base):
    chart.pin(0)
    with pytest.warns(UserWarning, match="pinned row"):
        chart.set_data(data(150).drop(index=[0]))
    assert chart.pinned.empty
    chart.set_data(data(150))
    pd.testing.assert_frame_equal(chart.layout(fresh=True), base.placements)


def test_set_data_refuses_bad_frames_and_keeps_the_old_rows(chart):
    with pytest.raises(ValueError, match="duplicate index"):
        chart.set_data(pd.concat([data(3), data(3)]))
    with pytest.raises(TypeError, match="set_data: df must be a pandas DataFrame"):
        chart.set_data([1, 2])
    assert len(chart.df) == 150


def test_the_widget_forwards_pins_set_data_and_fresh_runs():
    w = uw.UnitoPia(data(12), size="v", canvas=(300, 200), iterations=30)
    w.run(wait=True)
    w.pin(2)
    assert w.pinned.row.tolist() == [2] and w.pinned_units == [2] and w.stale
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        w.set_data(data(14))
    w.run(wait=True, fresh=True)
    assert len(w.placements) == 14
    assert w.placements.set_index("row").loc[2, "x"] == pytest.approx(w.pinned.x[0], abs=1.0)
