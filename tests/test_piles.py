"""Piles: the layers of by= without a container of their own lie side by side, one labelled
container per category, areas proportional to their totals (design/piles.py, piling.py)."""
import io
import json
import re
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest
from palmerpenguins import load_penguins
from PIL import Image

import unitopia_widget as uw
from unitopia_widget.design.piles import LABEL_FONT
from unitopia_widget.design.scene import VERSION
from unitopia_widget.output.legend_draw import text_width

SVG = "{http://www.w3.org/2000/svg}"
pytestmark = [pytest.mark.usefixtures("one_thread"),
              pytest.mark.filterwarnings("ignore:color='sex'")]   # grey for the birds of no sex


@pytest.fixture(scope="module")
def penguins():
    """The Palmer penguins, one circle per bird, area by body mass, piled by species."""
    pen = load_penguins()
    with pytest.warns(UserWarning):   # rows without a body mass or sex are dropped or grey
        chart = uw.Chart(pen, mark="circle", size="body_mass_g", color="sex", by="species",
                         dropna=True)
    chart.layout()
    return chart


def rect(layer):
    d = layer.container.to_json()
    return d["x"], d["y"], d["x"] + d["w"], d["y"] + d["h"]


def mark_boxes(chart) -> pd.DataFrame:
    """The placements with each mark's drawn box (x0, y0, x1, y1), canvas px."""
    table = chart.placements.copy()
    size = chart.boxes(chart.laid.units)
    table["x0"], table["x1"] = table["x"] - size[:, 0] / 2, table["x"] + size[:, 0] / 2
    table["y0"], table["y1"] = table["y"] - size[:, 1] / 2, table["y"] + size[:, 1] / 2
    return table


def labels(svg):
    """``[(text, x0, y0, x1, y1)]``: the pile labels and their boxes (DejaVu advances)."""
    out = []
    for t in ET.fromstring(svg).iter(f"{SVG}text"):
        if t.get("class") != "pile-label":
            continue
        x, y, w = float(t.get("x")), float(t.get("y")), text_width(t.text, LABEL_FONT)
        x0 = {"middle": x - w / 2, "end": x - w, "start": x}[t.get("text-anchor")]
        out.append((t.text, x0, y - 0.8 * LABEL_FONT, x0 + w, y + 0.25 * LABEL_FONT))
    return out


def test_by_without_a_container_gives_one_pile_per_species_in_the_legends_order(penguins):
    names = [layer.name for layer in penguins.layers]
    assert names == ["Adelie", "Chinstrap", "Gentoo"] and penguins.piles == "columns"
    boxes = [rect(layer) for layer in penguins.layers]
    # side by side on one base line, left to right in the legend's order, none overlapping
    assert len({round(b[3], 6) for b in boxes}) == 1
    assert all(a[2] < b[0] for a, b in zip(boxes, boxes[1:]))
    assert all(layer.forces == [uw.DirectionalForce(90)] for layer in penguins.layers)


def test_no_mark_lies_in_another_categorys_pile(penguins):
    table = mark_boxes(penguins)
    for layer in penguins.layers:
        x0, y0, x1, y1 = rect(layer)
        inside = (table["x1"] > x0) & (table["x0"] < x1) & (table["y1"] > y0) & (table["y0"] < y1)
        assert set(table.loc[inside, "layer"]) == {layer.name}
        mine = table[table["layer"] == layer.name]
        assert (mine["x"].between(x0, x1) & mine["y"].between(y0, y1)).all()


def test_pile_areas_are_proportional_to_their_totals_within_five_percent(penguins):
    pen = penguins.df
    total = pen.groupby("species")["body_mass_g"].sum()
    table = mark_boxes(penguins)
    for measure in ("container", "marks"):
        areas = []
        for layer in penguins.layers:
            if measure == "container":
                areas.append(layer.container.area(penguins.canvas))
            else:   # the box the pile's marks span
                mine = table[table["layer"] == layer.name]
                areas.append((mine["x1"].max() - mine["x0"].min()) * (mine["y1"].max() - mine["y0"].min()))
        ratio = np.array(areas) / total[[layer.name for layer in penguins.layers]].to_numpy()
        assert ratio.max() / ratio.min() < 1.05, (measure, ratio)


def test_each_pile_is_labelled_under_it_touching_no_mark_and_no_other_label(penguins, tmp_path):
    svg = penguins.to_svg()
    found = labels(svg)
    assert [t for t, *_ in found] == ["Adelie", "Chinstrap", "Gentoo"]
    table = mark_boxes(penguins)
    for (text, x0, y0, x1, y1), layer in zip(found, penguins.layers):
        bx0, by0, bx1, by1 = rect(layer)
        assert by1 < y0 and bx0 < (x0 + x1) / 2 < bx1 and y1 <= penguins.canvas[1]
        hits = (table["x1"] > x0) & (table["x0"] < x1) & (table["y1"] > y0) & (table["y0"] < y1)
        assert not hits.any(), text
    for a, b in zip(found, found[1:]):
        assert a[3] < b[1]
    # the PNG draws the labels (dark text where the SVG puts them), the HTML page holds them
    vx, vy = (float(v) for v in re.search(r'viewBox="([-\d.]+) ([-\d.]+)', svg).groups())
    image = np.asarray(Image.open(io.BytesIO(penguins.to_png(1.0))).convert("RGBA"))
    for text, x0, y0, x1, y1 in found:
        box = image[int(y0 - vy):int(y1 - vy) + 1, int(x0 - vx):int(x1 - vx) + 1]
        assert ((box[..., 3] > 128) & (box[..., :3].max(-1) < 160)).sum() > 15, text
    penguins.save(tmp_path / "piles.html")
    assert (tmp_path / "piles.html").read_text().count('class=\\"pile-label\\"') == 3


def test_the_design_saves_the_piles_and_loads_them_back(penguins, tmp_path):
    path = tmp_path / "piles.json"
    penguins.save(path)
    saved = json.loads(path.read_text())
    assert saved["version"] == VERSION and saved["piles"] == "columns"
    assert [x["container"]["kind"] for x in saved["layers"]] == ["rect"] * 3
    again = uw.Chart.load(path, penguins.df)
    assert again.piles == "columns" and again.design() == penguins.design()
    assert [rect(a) for a in again.layers] == [rect(b) for b in penguins.layers]


def test_a_version_4_design_keeps_its_layers_on_the_whole_canvas_unlabelled():
    df = pd.DataFrame({"k": list("aabbb"), "v": [1.0, 2.0, 1.0, 1.0, 3.0]})
    old = uw.Chart(df, by="k", size="v", piles=None).design()
    old["version"] = 4
    del old["piles"]
    chart = uw.Chart(df, by="k", size="v", iterations=20)
    assert chart.piles == "columns"
    chart.apply_design(old)
    assert chart.piles is None and all(layer.container is None for layer in chart.layers)
    chart.layout()
    assert "pile-label" not in chart.to_svg()


def small(n=(12, 24, 6), **kw):
    k = np.repeat(["ant", "bee", "cat"], n)
    df = pd.DataFrame({"k": k, "v": np.linspace(1, 2, len(k))})
    return uw.Chart(df, by="k", size="v", canvas=(400, 300), iterations=60, **kw)


def test_rows_lie_one_under_another_labelled_on_their_left():
    chart = small(piles="rows")
    boxes = [rect(layer) for layer in chart.layers]
    assert len({b[0] for b in boxes}) == 1 and all(a[3] < b[1] for a, b in zip(boxes, boxes[1:]))
    assert all(layer.forces == [uw.DirectionalForce(180)] for layer in chart.layers)
    chart.layout()
    for (text, x0, y0, x1, y1), box in zip(labels(chart.to_svg()), boxes):
        assert x1 < box[0] and x0 >= 0 and box[1] < (y0 + y1) / 2 < box[3]


def test_a_grid_wraps_the_piles_into_rows_of_small_multiples():
    k = np.repeat(list("abcdef"), [4, 8, 12, 16, 20, 24])
    chart = uw.Chart(pd.DataFrame({"k": k}), by="k", canvas=(600, 400), piles="grid")
    boxes = np.array([rect(layer) for layer in chart.layers])
    assert len(np.unique(boxes[:, 3].round(3))) == 2      # two rows of piles, bottoms aligned
    areas = (boxes[:, 2] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 1])
    np.testing.assert_allclose(areas / areas[-1], np.array([4, 8, 12, 16, 20, 24]) / 24, rtol=1e-9)


def test_layers_that_block_on_one_another_share_a_pile_and_rest_in_it():
    chart = small(boundary="open", fill=0.5)
    chart.layer("cat").set(blocks=["ant"])       # cat rests on ant: one pile, two left
    assert chart.layer("cat").container == chart.layer("ant").container
    assert chart.layer("bee").container != chart.layer("ant").container
    chart.layout()
    table = chart.placements
    assert table[table["layer"] == "cat"]["y"].mean() < table[table["layer"] == "ant"]["y"].mean()
    assert [t for t, *_ in labels(chart.to_svg())] == ["ant / cat", "bee"]
    # a pile edited by hand is kept when blocks change, with a warning saying how to re-pile
    chart.layer("bee").set(container=uw.Container.rect(300, 100, 90, 120))
    with pytest.warns(UserWarning, match=r"edited by hand.*set piles='columns' again"):
        chart.layer("cat").set(blocks=[])
    assert chart.layer("cat").container == chart.layer("ant").container


def test_the_piles_setter_lays_the_layers_out_again_or_back_on_the_canvas():
    chart = small()
    chart.piles = "rows"
    assert chart.piles == "rows" and len({rect(layer)[0] for layer in chart.layers}) == 1
    assert all(layer.forces == [uw.DirectionalForce(180)] for layer in chart.layers)
    chart.piles = None
    assert all(layer.container is None and layer.forces == [] for layer in chart.layers)
    with pytest.raises(ValueError, match=r"piles must be one of 'columns', 'rows', 'grid'; got 'stack'"):
        chart.piles = "stack"


@pytest.mark.parametrize("kwargs, match", [
    (dict(piles="rows"), r"piles='rows' lays out the layers of by=<column>.*by= is not set"),
    (dict(by="k", piles="rows", container=uw.Container.rect(0, 0, 100, 100)),
     r"piles='rows'.*container= places the layers already"),
    (dict(by="k", piles="heap"), r"piles must be one of 'columns', 'rows', 'grid'; got 'heap'"),
])
def test_bad_piles_are_refused_naming_the_argument(kwargs, match):
    with pytest.raises(ValueError, match=match):
        uw.Chart(pd.DataFrame({"k": list("ab")}), **kwargs)


def test_by_with_a_container_or_piles_none_packs_the_layers_together_as_before():
    for kw in (dict(piles=None), dict(container=uw.Container.rect(10, 10, 380, 280))):
        chart = small(**kw)
        assert chart.piles is None and all(layer.forces == [] for layer in chart.layers)


def test_icons_in_a_grid_inside_rows_of_piles_make_an_isotype_chart():
    k = np.repeat(["cats", "dogs"], [10, 25])
    chart = uw.Chart(pd.DataFrame({"k": k}), mark="fa:person", by="k", piles="rows",
                     arrange="grid", canvas=(500, 200))
    chart.layout()
    table = chart.placements
    assert (table["angle"] == 0).all()
    step = np.diff(np.sort(table[table["layer"] == "dogs"]["x"].unique()))
    assert np.allclose(step, step[0])   # one lattice: the icons stand in rows and columns
    for layer in chart.layers:
        x0, y0, x1, y1 = rect(layer)
        mine = table[table["layer"] == layer.name]
        assert mine["x"].between(x0, x1).all() and mine["y"].between(y0, y1).all()
        assert mine["x"].min() - x0 < step[0]   # filled from the left


def test_the_widget_sends_the_pile_labels():
    k = np.repeat(["ant", "bee"], [3, 5])
    w = uw.UnitoPia(pd.DataFrame({"k": k}), by="k", canvas=(300, 200))
    assert [x["text"] for x in w.pile_labels] == ["ant", "bee"]
    assert all(x["anchor"] == "middle" and x["y"] > 150 for x in w.pile_labels)
    w.piles = None
    assert w.pile_labels == [] and re.search(r'"piles": null', json.dumps(w.design))


def test_a_pile_of_one_large_mark_is_narrower_and_deep_enough_to_hold_it():
    df = pd.DataFrame({"k": ["few"] + ["many"] * 200, "v": [4.0] + [1.0] * 200})
    chart = uw.Chart(df, by="k", size="v", canvas=(400, 300), iterations=80)
    few, many = (rect(layer) for layer in chart.layers)
    assert few[2] - few[0] < many[2] - many[0]          # narrower, so deep enough
    areas = [(b[2] - b[0]) * (b[3] - b[1]) for b in (few, many)]
    assert areas[0] / areas[1] == pytest.approx(4 / 200, rel=1e-6)
    chart.layout()
    size = mark_boxes(chart).set_index("layer")
    big = size.loc["few"]
    small_ones = size.loc["many"]
    # the one large mark does not cap the shared scale: the small marks keep their size
    across = (small_ones["x1"] - small_ones["x0"]).median()
    assert big["x1"] - big["x0"] == pytest.approx(2 * across, rel=0.02) and across > 10


def test_more_categories_than_columns_fit_wrap_into_a_grid():
    df = pd.DataFrame({"k": np.arange(120) % 40})
    chart = uw.Chart(df, by="k", canvas=(400, 300))
    assert chart.piles == "grid"
    with pytest.raises(ValueError, match=r"piles='columns': 40 piles do not fit a 400 x 300 canvas"):
        uw.Chart(df, by="k", canvas=(400, 300), piles="columns")


def test_a_grid_laid_out_again_in_other_piles_stands_in_the_new_cells_on_a_warm_run():
    k = np.repeat(["cats", "dogs"], [10, 25])
    chart = uw.Chart(pd.DataFrame({"k": k}), mark="square", by="k", piles="rows",
                     arrange="grid", canvas=(500, 300))
    chart.layout()
    chart.piles = "columns"
    table = chart.layout()             # warm: starts from the rows' layout
    for layer in chart.layers:
        x0, y0, x1, y1 = rect(layer)
        mine = table[table["layer"] == layer.name]
        assert mine["x"].between(x0, x1).all() and mine["y"].between(y0, y1).all()
        steps = np.diff(np.sort(mine["x"].unique()))
        assert np.allclose(steps, steps[0], rtol=1e-3)   # still a lattice
