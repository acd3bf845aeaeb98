"""Grid arrangement (issue 22, part 4): arrange="grid" is a waffle in any shape."""
import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.layout.prepare.lattice import Region

pytestmark = pytest.mark.usefixtures("one_thread")
CANVAS = (600, 400)


def hand_drawn(seed: int = 4, k: int = 48) -> np.ndarray:
    """A closed freehand outline ``(k, 2)``: a lopsided loop with a jittery pen."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, k, endpoint=False)
    r = 1 + 0.2 * np.sin(2 * t + 1) + 0.1 * np.cos(5 * t) + 0.04 * rng.normal(size=k)
    return np.stack([300 + 240 * r * np.cos(t), 200 + 150 * r * np.sin(t)], 1)


def rows_of(table) -> list[np.ndarray]:
    """The unit indices of each row: centres closer in height than half a mark."""
    order = np.argsort(table["y"].to_numpy(), kind="stable")
    y, h = table["y"].to_numpy()[order], float(table["height"].mean())
    cuts = np.nonzero(np.diff(y) > h / 2)[0] + 1
    return np.split(order, cuts)


@pytest.fixture(scope="module")
def waffle():
    rng = np.random.default_rng(5)
    df = pd.DataFrame({"k": rng.choice(["a", "b", "c"], 240), "v": rng.uniform(1, 3, 240)})
    container = uw.Container.polygon(hand_drawn())
    chart = uw.Chart(df, mark="square", color="k", order="k", arrange="grid", margin=0.1,
                     container=container, canvas=CANVAS)
    chart.layout()
    return chart, container


def test_a_grid_in_a_hand_drawn_container_has_aligned_rows(waffle):
    chart, _ = waffle
    table = chart.placements
    rows = rows_of(table)
    assert len(rows) >= 8
    h = float(table["height"].mean())
    for row in rows:
        assert np.ptp(table["y"].to_numpy()[row]) <= 0.1 * h
    w = float(table["width"].mean())
    steps = np.diff(np.sort(table["x"].to_numpy())) / (w * 1.1)   # the cell: the mark and its margin
    assert np.allclose(steps, np.round(steps), atol=0.01)        # columns on one lattice


def test_the_grid_does_not_overlap_stays_inside_and_fills_sensibly(waffle):
    chart, container = waffle
    table = chart.placements
    c, w, h = table[["x", "y"]].to_numpy(), table["width"].to_numpy(), table["height"].to_numpy()
    dx = np.abs(c[:, None, 0] - c[None, :, 0]) - (w[:, None] + w[None, :]) / 2
    dy = np.abs(c[:, None, 1] - c[None, :, 1]) - (h[:, None] + h[None, :]) / 2
    apart = (dx >= -1e-6) | (dy >= -1e-6)
    np.fill_diagonal(apart, True)
    assert apart.all()                                          # no two squares overlap
    region = Region(container.coverage(CANVAS, 2.0), 2.0)
    corners = np.concatenate([c + np.stack([sx * w / 2, sy * h / 2], 1)
                              for sx in (-1, 1) for sy in (-1, 1)])
    assert (region.depth_at(corners) > 0).all()                 # every corner inside
    density = float((w * h).sum()) / container.area(CANVAS)
    assert density > 0.45                                       # squares with a 10% margin


def test_the_grid_follows_order_row_by_row(waffle):
    chart, _ = waffle
    table = chart.placements
    rank = {k: i for i, k in enumerate("abc")}
    keys = np.array([rank[k] for k in chart.df.loc[table["row"], "k"]])
    reading = np.concatenate([row[np.argsort(table["x"].to_numpy()[row])] for row in rows_of(table)])
    assert (np.diff(keys[reading]) >= 0).all()


def test_a_downward_force_fills_the_grid_from_the_bottom():
    df = pd.DataFrame({"v": np.arange(30)})
    container = uw.Container.rect(100, 50, 400, 300)
    chart = uw.Chart(df, mark="circle", order="v", arrange="grid", boundary="open", fill=0.2,
                     forces=[uw.DirectionalForce(90)], container=container, canvas=CANVAS)
    table = chart.layout()
    first = table.set_index("row").loc[0]
    assert table["y"].min() > 200                               # gathered at the bottom
    assert first["y"] == pytest.approx(table["y"].max())        # the first row is the lowest
    assert chart.result.iterations <= 20                        # nothing moves: no long settle


def test_arrange_is_saved_in_the_design(waffle):
    chart, _ = waffle
    d = chart.design()
    assert d["layers"][0]["arrange"] == "grid"
    assert uw.Chart.from_design(chart.df, d).layers[0].arrange == "grid"
    layer = uw.Chart(pd.DataFrame({"v": [1, 2]})).layers[0]
    assert layer.arrange == "free"
    with pytest.raises(ValueError, match=r"arrange must be one of 'free', 'grid'; got 'rows'"):
        layer.set(arrange="rows")
