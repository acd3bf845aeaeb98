"""Mark groups (issue 10): several marks in one layer, the shape= channel, joint packing,
layers sharing a container, design JSON version 4. Layouts are measured from the exported
SVG, every unit rendered alone (tests/ink.py)."""
from __future__ import annotations

import json
import pathlib
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from unitopia_widget.design.scene import VERSION
from ink import ink_metrics
from unitopia_widget.layout.step.atlas import SpriteAtlas
from unitopia_widget.layout.step.raster import (SPRITE_SIDE, RasterGrid, accumulate, plan_groups, render_samples,
                                    sprite_pyramid)

pytestmark = pytest.mark.usefixtures("one_thread")
DATA = pathlib.Path(__file__).parent / "data" / "marks"
NS = {"s": "http://www.w3.org/2000/svg"}
# realistic marks: icons with <style> classes, several colours, strokes, groups, aspect 0.5 to 2
FOURTEEN = ["fa:apple-whole", "fa:fish", str(DATA / "class_styled.svg"), "fa:bicycle",
            str(DATA / "rect_2to1.svg"), "star", "fa:lemon", "fa:carrot", "fa:dove", "fa:feather",
            "fa:regular/star", str(DATA / "multicolor.svg"), "heart",
            uw.Mark.sketch([[(0, 0), (30, 40), (60, 0)], [(0, 40), (60, 40)]], width=6)]
ELLIPSE = (200, 150, 180, 130)


def sized(n, kinds, seed=0):
    rng = np.random.default_rng(seed)
    return pd.DataFrame({"v": rng.lognormal(0, 0.5, n), "kind": [kinds[i % len(kinds)] for i in range(n)]})


def used_defs(svg: str) -> dict:
    """data-row -> id of the definition its unit draws."""
    root = ET.fromstring(svg)
    return {g.get("data-row"): g.find("s:use", NS).get("href")[1:]
            for g in root.findall("s:g[@class='unit']", NS)}


def outline(el) -> list:
    """The element tree as (local tag, attributes) pairs, namespaces dropped."""
    return [(e.tag.rpartition("}")[2], sorted(e.attrib.items())) for e in el.iter()]


def check_packed(chart, values, label):
    svg = chart.to_svg(legend=False)
    m = ink_metrics(svg, chart.canvas, ellipse=ELLIPSE)
    rows = [str(r) for r in chart.placements["row"]]
    # size= encodes the footprint's area: the silhouette (ink with enclosed holes filled)
    ratio = np.array([m["silhouettes"][r] for r in rows]) / values.loc[chart.placements["row"]].to_numpy()
    spread = float(ratio.std() / ratio.mean())
    print(f"{label}: overlap {100 * m['overlap']:.2f}%, outside {100 * m['outside']:.2f}% of the ink, "
          f"silhouette area / value spread {100 * spread:.1f}%, {chart.result.iterations} iterations")
    assert m["overlap"] <= 0.01
    assert m["outside"] <= 0.005
    assert spread < 0.05   # size= stays exact in area whatever the mark
    return svg


def test_two_marks_in_one_layer_pack_jointly():
    df = sized(70, ["apple", "brick"])   # a round icon and a 2:1 block: different silhouettes
    chart = uw.Chart(df, mark={"apple": "fa:apple-whole", "brick": str(DATA / "rect_2to1.svg")},
                     shape="kind", size="v",
                     color="kind", container=uw.Container.ellipse(*ELLIPSE), canvas=(400, 300))
    chart.layout()
    assert len(chart.layers) == 1
    svg = check_packed(chart, df["v"], "2 marks, 70 units")
    assert len(set(used_defs(svg).values())) == 2
    assert "Icons: Font Awesome Free by Fonticons, Inc., CC BY 4.0" in svg   # the icons' licence


def test_fourteen_marks_in_one_layer_pack_jointly():
    df = sized(84, [f"k{i:02d}" for i in range(14)], seed=1)
    chart = uw.Chart(df, mark=FOURTEEN, shape="kind", size="v",
                     container=uw.Container.ellipse(*ELLIPSE), canvas=(400, 300))
    chart.layout()
    svg = check_packed(chart, df["v"], "14 marks, 84 units")
    defs = used_defs(svg)
    kind_of_def = {}
    for row, def_id in defs.items():
        kind_of_def.setdefault(def_id, set()).add(df.loc[int(row), "kind"])
    assert len(kind_of_def) == 14 and all(len(k) == 1 for k in kind_of_def.values())


def test_shape_dict_gives_each_category_its_own_mark():
    df = pd.DataFrame({"kind": ["rose", "tulip", "lily", "rose", "lily", "tulip", "rose"]})
    marks = {"tulip": "drop", "rose": "heart", "lily": "fa:seedling"}
    chart = uw.Chart(df, mark=marks, shape="kind", iterations=20)
    layer = chart.layers[0]
    assert layer.mark_keys == ["tulip", "rose", "lily"] and layer.encodings["shape"] == "kind"
    drawn = [layer.marks[k] for k in chart._units.mark]
    assert drawn == [uw.Mark.from_spec(marks[v]) for v in df["kind"]]
    chart.layout()
    svg = chart.to_svg(legend=False)
    defs = {d.get("id"): outline(d) for d in ET.fromstring(svg).find("s:defs", NS)}
    assert len(defs) == 3
    for row, def_id in used_defs(svg).items():   # each unit draws its category's own design
        expected = uw.Mark.from_spec(marks[df.loc[int(row), "kind"]])
        assert defs[def_id] == outline(ET.fromstring(expected.svg_fragment(def_id)))


def test_a_list_of_marks_goes_to_rows_in_order_and_to_sorted_categories():
    df = pd.DataFrame({"kind": ["b", "c", "a", "b", "a", "c", "b"]})
    rows = uw.Chart(df, mark=["circle", "star", "heart"])
    assert rows._units.mark.tolist() == [0, 1, 2, 0, 1, 2, 0]           # row i draws mark i mod 3
    by_kind = uw.Chart(df, mark=["circle", "star", "heart"], shape="kind")
    assert by_kind._units.mark.tolist() == [1, 2, 0, 1, 0, 2, 1]        # a, b, c take them in turn
    cycling = uw.Chart(df, mark=["circle", "star"], shape="kind")
    assert cycling._units.mark.tolist() == [1, 0, 0, 1, 0, 0, 1]        # like a palette: c takes circle
    per_layer = uw.Chart(df, by="kind", mark=["circle", "star"])        # by=: each layer counts its rows
    assert [(per_layer.layers[li].name, k) for li, k in zip(per_layer._units.layer, per_layer._units.mark)] \
        == [("a", 0), ("a", 1), ("b", 0), ("b", 1), ("b", 0), ("c", 0), ("c", 1)]


def test_missing_categories_are_named_with_the_keys_given():
    df = pd.DataFrame({"kind": ["rose", "tulip", "lily", "iris"]})
    with pytest.raises(ValueError, match=r"shape='kind': mark has no entry for the categories 'iris', "
                                         r"'lily'; the keys given are 'rose', 'tulip'; add a mark"):
        uw.Chart(df, mark={"rose": "heart", "tulip": "drop"}, shape="kind")
    chart = uw.Chart(df, mark={"rose": "heart", "tulip": "drop", "lily": "star", "iris": "circle"},
                     shape="kind")
    with pytest.raises(ValueError, match=r"no entry for the categories 'iris'"):
        chart.layer(0).set(mark={"rose": "heart", "tulip": "drop", "lily": "star"})
    assert len(chart.layer(0).marks) == 4                              # the refused edit changed nothing
    with pytest.raises(ValueError, match=r"mark is a dict of category -> mark \('rose', 'tulip', 'lily', "
                                         r"'iris'\); set shape=<column>"):
        chart.layer(0).set(shape=None)
    with pytest.raises(ValueError, match=r"shape='k': the column's values must be hashable categories"):
        uw.Chart(pd.DataFrame({"k": [[1], [2]]}), mark=["circle", "star"], shape="k")
    with pytest.raises(ValueError, match=r"shape='kind': 1 of 4 rows are missing; fill them"):
        uw.Chart(pd.DataFrame({"kind": ["a", None, "b", "a"]}), mark=["circle", "star"], shape="kind")


def test_layers_sharing_one_container_collide_both_ways():
    df = sized(60, ["banana", "cherry"])
    container = uw.Container.ellipse(*ELLIPSE)
    chart = uw.Chart(df, by="kind", mark={"banana": "drop", "cherry": "circle"}, size="v", color="kind",
                     container=container, canvas=(400, 300))
    chart.layout()
    check_packed(chart, df["v"], "by= two layers, one container")
    # blocks stay one-way: the blocked layer gives way, the blocking one does not see it
    blocks = torch.zeros(2, 2)
    chart.layer("cherry").set(blocks=["banana"])
    problem = uw.layout.engine.build_problem(chart._units, chart.layers, chart.canvas, 0, "cpu")
    blocks[1, 0] = 1
    assert torch.equal(problem.terms.blocks, blocks)
    chart.layer("cherry").set(blocks=[], container=uw.Container.ellipse(201, 150, 180, 130))
    problem = uw.layout.engine.build_problem(chart._units, chart.layers, chart.canvas, 0, "cpu")
    assert not problem.terms.blocks.any()                              # different containers: independent


def test_design_json_round_trip_version_4():
    df = pd.DataFrame({"kind": ["x", "y", "z", 3] * 2, "v": np.arange(1.0, 9.0)})
    chart = uw.Chart(df, mark={"x": "fa:lemon", "y": str(DATA / "class_styled.svg"), "z": "star", 3: "drop"},
                     shape="kind", size="v")
    design = json.loads(json.dumps(chart.design()))
    assert design["version"] == VERSION
    layer = design["layers"][0]
    assert layer["footprint"] == "silhouette" and layer["margin_of"] == "median"
    assert layer["mark_keys"] == ["x", "y", "z", 3] and layer["encodings"]["shape"] == "kind"
    assert layer["marks"][0] == {"kind": "icon", "name": "fa:lemon"} and "mark" not in layer
    other = uw.Chart(df)
    other.apply_design(design)
    assert other.design() == chart.design()
    assert other._units.mark.tolist() == chart._units.mark.tolist() == [0, 1, 2, 3] * 2
    lists = uw.Chart(df, mark=["circle", "fa:regular/star"])
    again = uw.Chart(df)
    again.apply_design(json.loads(json.dumps(lists.design())))
    assert again.layers[0].mark_keys is None and again.layers[0].marks == lists.layers[0].marks


def test_version_1_designs_still_load():
    v1 = {"schema": "unitopia-design", "version": 1, "canvas": [400, 300], "background": None, "seed": 3,
          "layers": [{"name": "only", "rows": None, "mark": {"kind": "shape", "name": "heart"},
                      "encodings": {"size": "v", "color": None, "margin": 0.0}, "boundary": "closed"}]}
    chart = uw.Chart(pd.DataFrame({"v": [1.0, 2.0]}))
    chart.apply_design(v1)
    assert chart.layers[0].marks == [uw.Mark.shape("heart")] and chart.layers[0].encodings["shape"] is None
    saved = chart.design()
    assert saved["version"] == VERSION and saved["layers"][0]["marks"] == [v1["layers"][0]["mark"]]
    assert saved["layers"][0]["footprint"] == "ink"      # as version 1 and 2 laid it out
    assert saved["layers"][0]["margin_of"] == "own"      # as versions 1 to 3 laid it out
    edited = chart.design()   # an editor that knows only version 1 sets "mark": it wins
    edited["layers"][0]["mark"] = {"kind": "shape", "name": "star"}
    chart.apply_design(edited)
    assert chart.layers[0].marks == [uw.Mark.shape("star")]
    v2_layer = {k: v for k, v in v1["layers"][0].items() if k != "mark"}
    bad = dict(v1, version=2, layers=[dict(v2_layer, marks=[{"kind": "shape", "name": "star"}],
                                           mark_keys=["a", "a"])])
    with pytest.raises(ValueError, match=r"mark_keys must be null or a list of 1 distinct categories"):
        chart.apply_design(bad)


def test_icon_names_and_misspelt_ones():
    apple = uw.Mark.from_spec("fa:apple-whole")
    assert apple.kind == "icon" and apple.to_json() == {"kind": "icon", "name": "fa:apple-whole"}
    assert uw.Mark.from_spec("fa:solid/star") == uw.Mark.from_json({"kind": "icon", "name": "fa:solid/star"})
    solid, outline = (uw.Mark.from_spec(n).silhouette(64).sum() for n in ("fa:star", "fa:regular/star"))
    assert solid > 1.5 * outline                                        # the styles differ
    assert uw.Mark.from_spec("fa:github").kind == "icon"                 # brands
    with pytest.raises(ValueError, match=r"mark: no Font Awesome icon named 'fa:aple-whole'; the closest "
                                         r"names are fa:apple-whole"):
        uw.Chart(pd.DataFrame({"v": [1]}), mark="fa:aple-whole")
    with pytest.raises(ValueError, match=r"icon 'fa:light/star': unknown style 'light'; use fa:NAME or "
                                         r"fa:STYLE/NAME with STYLE one of solid, regular, brands"):
        uw.Mark.icon("fa:light/star")


def test_the_widget_answers_icon_queries_and_sends_every_mark():
    df = pd.DataFrame({"kind": ["a", "b", "a", "b"], "c": ["r", "r", "g", "g"]})
    w = uw.UnitoPia(df, mark={"a": "fa:apple-whole", "b": "heart"}, shape="kind", color="c")
    sent = []
    w.send = sent.append
    w._on_message(w, {"type": "icons", "query": "app"}, [])
    assert sent[0]["type"] == "icons" and sent[0]["query"] == "app"
    assert "fa:apple-whole" in sent[0]["names"] and len(sent[0]["names"]) <= 30
    assert [(m["layer"], m["mark"]) for m in w.marks] == [("layer-1", 0), ("layer-1", 1)] * 2
    units = np.frombuffer(w.units, dtype=np.float32).reshape(-1, 4)
    assert [w.marks[int(i)]["mark"] for i in units[:, 1]] == [0, 1, 0, 1]


def test_the_atlas_renders_what_the_separate_sprites_render():
    marks = [uw.Mark.from_spec(m) for m in ("star", "fa:bicycle", str(DATA / "rect_2to1.svg"))]
    pyramids = [sprite_pyramid(m.silhouette(SPRITE_SIDE), "cpu") for m in marks]
    g = torch.Generator().manual_seed(0)
    grid = RasterGrid((200, 150), 1.5, 2)
    center = (torch.rand(30, 2, generator=g) * torch.tensor([200.0, 150.0])).requires_grad_()
    angle = (torch.rand(30, generator=g) * 6).requires_grad_()
    hw, hh = torch.rand(30, generator=g) * 12 + 2, torch.rand(30, generator=g) * 12 + 2
    groups = plan_groups(hw.numpy(), hh.numpy(), np.arange(30) % 3, [SPRITE_SIDE] * 3, np.ones(30, bool), 1.5)
    out = []
    for source in (pyramids, SpriteAtlas(pyramids)):
        values, index, _ = render_samples(center, angle, hw, hh, groups, source, grid)
        cover = accumulate(values, index, grid.size)
        (cover * torch.linspace(0, 1, grid.size)).sum().backward()
        out.append((cover.detach(), center.grad.clone(), angle.grad.clone()))
        center.grad = angle.grad = None
    assert len(SpriteAtlas(pyramids).merge(groups)) < len(groups)
    for a, b in zip(*out):
        torch.testing.assert_close(a, b, rtol=1e-4, atol=1e-3)
