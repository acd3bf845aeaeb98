"""Position channels x= and y= (issue 22, part 3): a beeswarm inside any shape."""
import math

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.distance import pdist, squareform
from scipy.stats import spearmanr

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.prepare.lattice import Region
from unitopia_widget.layout.prepare.positions import BAND_GAP

pytestmark = pytest.mark.usefixtures("one_thread")
CANVAS = (800, 500)


def blob(seed: int = 0, k: int = 60) -> np.ndarray:
    """A hand-drawn-looking closed outline ``(k, 2)``: a wobbly, lopsided loop."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, k, endpoint=False)
    r = 1 + 0.25 * np.sin(3 * t) + 0.1 * np.cos(5 * t) + 0.03 * rng.normal(size=k)
    return np.stack([400 + 330 * r * np.cos(t), 250 + 190 * r * np.sin(t)], 1)


def disc_overlap(table) -> float:
    """Summed lens area of every pair of overlapping discs over the discs' total area."""
    c, r = table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2
    d = squareform(pdist(c))
    np.fill_diagonal(d, np.inf)
    i, j = np.nonzero(np.triu(d < r[:, None] + r[None, :], 1))
    lens = 0.0
    for a, b in zip(i, j):   # lens area of two circles
        dd, ra, rb = d[a, b], r[a], r[b]
        if dd <= abs(ra - rb):
            lens += math.pi * min(ra, rb) ** 2
            continue
        p = ra ** 2 * math.acos((dd ** 2 + ra ** 2 - rb ** 2) / (2 * dd * ra))
        q = rb ** 2 * math.acos((dd ** 2 + rb ** 2 - ra ** 2) / (2 * dd * rb))
        lens += p + q - 0.5 * math.sqrt((-dd + ra + rb) * (dd + ra - rb) * (dd - ra + rb) * (dd + ra + rb))
    return lens / float((math.pi * r ** 2).sum())


def inside_share(container, table, slack: float = 1.0) -> float:
    """Share of discs lying inside ``container`` to within ``slack`` px."""
    region = Region(container.coverage(CANVAS, 2.0), 2.0)
    depth = region.depth_at(table[["x", "y"]].to_numpy())
    return float((depth >= table["width"].to_numpy() / 2 - slack).mean())


@pytest.fixture(scope="module")
def swarm():
    """500 marks, x= a numeric column, in a hand-drawn closed container."""
    rng = np.random.default_rng(1)
    df = pd.DataFrame({"v": rng.normal(0, 1, 500)})
    container = uw.Container.polygon(blob())
    chart = uw.Chart(df, mark="circle", x="v", container=container, canvas=CANVAS)
    chart.layout()
    return chart, container


def test_numeric_x_orders_500_marks_without_overlap_all_inside(swarm):
    chart, container = swarm
    table = chart.placements
    rho = spearmanr(chart.df.loc[table["row"], "v"], table["x"]).correlation
    assert rho >= 0.98
    assert disc_overlap(table) <= 0.01
    assert inside_share(container, table) == 1.0


def test_the_free_axis_spreads_the_marks_as_a_beeswarm(swarm):
    chart, _ = swarm
    table = chart.placements
    radius = float(table["width"].mean()) / 2
    assert table["y"].std() > 5 * radius          # stacked across, not all on one line


def test_the_axis_is_drawn_in_the_export_with_round_ticks(swarm, tmp_path):
    chart, _ = swarm
    svg = chart.to_svg(axes=True)
    assert svg.count('<g class="axis" data-channel="x"') == 1
    chart.save(tmp_path / "swarm.html", axes=True)                 # the page carries the axes
    assert 'class=\\"axis\\" data-channel=\\"x\\"' in (tmp_path / "swarm.html").read_text()
    assert ">0</text>" in svg and ">v</text>" in svg
    assert 'class="axis"' not in chart.to_svg()
    plain = uw.Chart(pd.DataFrame({"v": [1.0, 2.0, 3.0]}), canvas=(200, 200))
    plain.layout()
    with pytest.raises(ValueError, match="axes=True draws the axes of x= and y="):
        plain.to_svg(axes=True)


def targets(chart):
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu")
    return units, problem


def test_a_log_scale_places_values_linearly_in_their_logarithm():
    v = np.array([1.0, 10.0, 100.0, 1000.0, 3.0, 30.0] * 5)
    chart = uw.Chart(pd.DataFrame({"v": v}), x="v", x_scale="log", canvas=CANVAS, boundary="open")
    units, problem = targets(chart)
    tx = problem.anchor.target[:, 0].numpy().astype(float)
    fit = np.polyfit(np.log10(v), tx, 1)
    assert np.abs(np.polyval(fit, np.log10(v)) - tx).max() < 1e-3 * np.ptp(tx)
    axis = problem.anchor.axes[0]
    assert tx.min() == pytest.approx(axis.lo, abs=1e-3) and tx.max() == pytest.approx(axis.hi, abs=1e-3)


def test_categories_make_bands_and_each_mark_stays_in_its_band():
    rng = np.random.default_rng(3)
    df = pd.DataFrame({"k": rng.choice(["low", "mid", "high"], 90), "v": rng.uniform(1, 2, 90)})
    container = uw.Container.polygon(blob(2))
    chart = uw.Chart(df, mark="circle", y="k", x="v", container=container, canvas=CANVAS,
                     boundary="open")
    table = chart.layout()
    axis = next(a for a in chart.result.axes if a.channel == "y")
    assert axis.scale.domain == ("high", "low", "mid")   # sorted categories
    gap = BAND_GAP / 4 * (axis.hi - axis.lo) / 3   # half the gap each band keeps at its ends
    for k, name in enumerate(axis.scale.domain):
        mine = chart.df.loc[table["row"], "k"].to_numpy() == name
        top, bottom = (table["y"] - table["height"] / 2)[mine], (table["y"] + table["height"] / 2)[mine]
        assert top.min() >= axis.at(k / 3) + gap - 1 and bottom.max() <= axis.at((k + 1) / 3) - gap + 1
    assert disc_overlap(table) <= 0.01
    assert ">mid</text>" in chart.to_svg(axes=True)


def test_positions_and_arrangement_are_saved_in_the_design():
    df = pd.DataFrame({"v": [1.0, 2.0, 4.0], "k": list("abc")})
    chart = uw.Chart(df, x="v", x_scale="log", y="k", canvas=CANVAS)
    d = chart.design()
    layer = d["layers"][0]
    assert (layer["encodings"]["x"], layer["encodings"]["y"], layer["x_scale"], layer["y_scale"],
            layer["arrange"]) == ("v", "k", "log", "linear", "free")
    back = uw.Chart.from_design(df, d)
    assert back.design() == d
    assert "'x_scale': 'log'" in chart.to_code()


@pytest.mark.parametrize("kwargs, message", [
    ({"x": "nope"}, r"x='nope': no such column"),
    ({"y": "k", "y_scale": "log"}, r"y='k' with y_scale='log': the column must be numeric"),
    ({"x": "z", "x_scale": "log"}, r"x='z': 1 of 4 rows are missing, infinite or <= 0 .*> 0"),
    ({"x": "gap"}, r"x='gap': 1 of 4 rows are missing.*dropna=True"),
    ({"x_scale": "sqrt"}, r"x_scale must be one of 'linear', 'log'; got 'sqrt'"),
    ({"arrange": "hex"}, r"arrange must be one of 'free', 'grid'; got 'hex'"),
    ({"arrange": "grid", "x": "v"}, r"arrange='grid' .* cannot take x='v'"),
])
def test_bad_position_bindings_name_the_argument_and_what_is_accepted(kwargs, message):
    df = pd.DataFrame({"v": [1.0, 2.0, 3.0, 4.0], "k": list("abcd"), "z": [0.0, 1, 2, 3],
                       "gap": [1.0, np.nan, 2, 3]})
    with pytest.raises(ValueError, match=message):
        uw.Chart(df, canvas=CANVAS, **kwargs)


def test_dropna_drops_rows_whose_position_cannot_be_placed():
    df = pd.DataFrame({"v": [1.0, np.nan, 2.0, 3.0, -1.0]})
    with pytest.warns(UserWarning, match=r"dropped 2 of 5 rows .*x='v'"):
        chart = uw.Chart(df, x="v", x_scale="log", dropna=True, canvas=CANVAS)
    assert list(chart.df.index) == [0, 2, 3]


def test_a_datetime_column_is_a_linear_position_with_date_ticks():
    from unitopia_widget.output.axes import ticks
    df = pd.DataFrame({"d": pd.date_range("2025-01-01", periods=40, freq="7D")})
    units, problem = targets(uw.Chart(df, x="d", canvas=CANVAS, boundary="open"))
    tx = problem.anchor.target[:, 0].numpy().astype(float)
    assert np.allclose(np.diff(tx), np.diff(tx)[0], rtol=1e-3)       # equal steps in time
    labels = [label for _, label in ticks(problem.anchor.axes[0])]
    assert labels == ["Jan 2025", "Apr 2025", "Jul 2025", "Oct 2025"]   # months: the unit


def test_an_axis_stands_outside_its_container_and_its_marks_with_its_labels():
    from unitopia_widget.design.positions import Scale
    from unitopia_widget.layout.prepare.positions import Axis
    from unitopia_widget.output.axes import axes_svg
    bands = Scale("k", "band", ("a", "b"))
    marks = {"l": np.array([[80.0, 60, 120, 100], [300, 420, 340, 470]])}   # x0, y0, x1, y1
    svg, box = axes_svg([Axis("l", "y", bands, 50, 450, cross=100)], marks)
    assert 'x1="74.0"' in svg and 'text-anchor="end"' in svg   # left of the leftmost mark
    assert box[2] == pytest.approx(74.0) and box[0] < 74 - 10   # the labels lie left of it
    svg, box = axes_svg([Axis("l", "x", bands, 50, 750, cross=460)], marks)
    assert 'y1="476.0"' in svg and box[1] == pytest.approx(476.0)   # under the lowest mark
    assert box[3] > 476 + 2 * 11                                 # labels and title under it




def test_an_axis_shared_by_several_layers_stands_clear_of_every_layers_marks():
    from unitopia_widget.design.positions import Scale
    from unitopia_widget.layout.prepare.positions import Axis
    from unitopia_widget.output.axes import axes_svg
    bands = Scale("k", "band", ("a", "b"))
    marks = {"a": np.array([[120.0, 60, 160, 100]]),     # x0, y0, x1, y1
             "b": np.array([[80.0, 420, 120, 470]])}     # lower and further left than a's
    for channel, cross, edge in (("x", 460, 'y1="476.0"'), ("y", 100, 'x1="74.0"')):
        both = [Axis(name, channel, bands, 50, 450, cross=cross) for name in ("a", "b")]
        svg, _ = axes_svg(both, marks)
        assert svg.count('<g class="axis"') == 1 and edge in svg   # drawn once, past b's marks
        other = [Axis("a", channel, bands, 50, 450, cross=cross),
                 Axis("b", channel, bands, 50, 450, cross=cross + 300)]
        assert axes_svg(other, marks)[0].count('<g class="axis"') == 2   # its own extent: its own


def test_the_widget_sends_the_axes_of_the_shown_layout_as_a_sanitised_image():
    import base64
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"v": rng.normal(0, 1, 40), "k": np.repeat(["a", "b"], 20)})
    w = uw.UnitoPia(df, mark="circle", x="v", color="k", canvas=(300, 200), iterations=30)
    assert w.axes_image == {}                                     # no layout yet: no axes
    w.run(wait=True)
    image = w.axes_image
    svg = base64.b64decode(image["src"].removeprefix("data:image/svg+xml;base64,")).decode()
    assert '<g class="axis" data-channel="x"' in svg and ">v</text>" in svg and "<script" not in svg
    assert f'viewBox="{image["x"]:.1f} {image["y"]:.1f} {image["width"]:.1f} {image["height"]:.1f}"' in svg
    lowest = float((w.placements["y"] + w.placements["height"] / 2).max())
    assert image["y"] >= lowest and image["height"] > 2 * 11     # under the marks, labels in it
    w.layer(0).set(x=None)                                        # unbound: cleared at once
    assert w.axes_image == {}
