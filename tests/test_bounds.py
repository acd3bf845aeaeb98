"""Bounds on a design's lists (unitopia_widget/design/bounds.py, docs/protocol.md "Bounds"):
checked when a design is built and when it is loaded, refused quickly naming the field."""
import json
import re
import time
from pathlib import Path

import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.design import bounds

PROTOCOL = Path(__file__).parent.parent / "docs" / "protocol.md"


@pytest.fixture
def df():
    return pd.DataFrame({"v": [1.0, 2.0, 3.0]})


def test_a_design_file_with_100000_forces_is_refused_at_load_within_5_s(df, tmp_path):
    design = uw.Chart(df).design()
    design["layers"][0]["forces"] = [{"kind": "point", "x": 400, "y": 450, "strength": 1}] * 100_000
    path = tmp_path / "forces.json"
    path.write_text(json.dumps(design))
    for load in (lambda: uw.Chart.load(path, df), lambda: uw.UnitoPia(df, design_path=path)):
        start = time.perf_counter()
        with pytest.raises(ValueError, match=r"design layer 'layer-1': forces has 100,000 entries; "
                                             r"at most 50 are allowed"):
            load()
        assert time.perf_counter() - start < 5


def test_forces_in_python_stop_at_the_bound(df):
    force = uw.PointForce(400, 250)
    assert len(uw.Chart(df, forces=[force] * bounds.MAX_FORCES).layer(0).forces) == bounds.MAX_FORCES
    chart = uw.Chart(df)
    with pytest.raises(ValueError, match="forces has 51 entries; at most 50"):
        chart.layer(0).set(forces=[force] * 51)
    assert chart.layer(0).forces == []


@pytest.mark.parametrize("build, message", [
    (lambda: uw.Container.polygon([[0, 0], [9, 0], [9, 9]] * 7_000),
     r"Container.polygon: points has 21,000 vertices; at most 20,000"),
    (lambda: uw.Container.path("M 0 0 " + "L 9 9 " * 40_000 + "Z"),
     r"Container.path: d has 240,\d+ characters; at most 200,000"),
    (lambda: uw.Container.rect(0, 0, 9, 9).cut([[1, 1]] * 20_001, 1),
     r"Container.cut: points has 20,001 entries"),
    (lambda: uw.CurveEmitter([[0, 0], [1, 1], [2, 0], [3, 1]] * 751),
     r"CurveEmitter: points has 3,004 entries; at most 3,001"),
    (lambda: uw.Mark.sketch([[[0, 0], [1, 1]]] * 1_001),
     r"sketch strokes has 1,001 entries; at most 1,000"),
    (lambda: uw.Mark.sketch([[[0, 0], [1, 1]] * 25_001]),
     r"sketch strokes has 50,002 points; at most 50,000"),
    (lambda: uw.Layer("a", blocks=["b"] * 101), r"blocks has 101 entries; at most 100"),
    (lambda: uw.Layer("a", size="c" * 1_001), r"size \(a column name\) has 1,001 characters"),
    (lambda: uw.Layer("a", rows={"index": list(range(20_001))}),
     r"layer rows index has 20,001 labels; at most 20,000"),
], ids=["polygon", "path", "cut", "emitter", "strokes", "sketch points", "blocks", "column",
        "rows"])
def test_every_list_built_in_python_is_bounded(build, message):
    with pytest.raises(ValueError, match=message):
        build()


def test_container_cuts_in_a_design_are_bounded():
    cut = {"points": [[1, 1], [5, 5]], "width": 1}
    d = {"kind": "rect", "x": 0, "y": 0, "w": 9, "h": 9, "cuts": [cut] * 101}
    with pytest.raises(ValueError, match=r"Container.from_json: cuts has 101 entries; at most 100"):
        uw.Container.from_json(d)


def test_a_story_file_with_too_many_slides_is_refused_before_any_chart_is_built(df, tmp_path):
    slide = {"title": "", "rows": [0, 1, 2], "design": uw.Chart(df).design()}
    story = {"schema": "unitopia-story", "version": 1, "seconds": 1.0, "slides": [slide] * 101}
    start = time.perf_counter()
    with pytest.raises(ValueError, match=r"story: slides has 101 entries; at most 100"):
        uw.Story.from_json(story, df)
    assert time.perf_counter() - start < 1


def test_the_protocol_documents_every_bound():
    text = PROTOCOL.read_text()
    for name in ("MAX_FORCES", "MAX_CONTAINER_POINTS", "MAX_PATH_CHARS", "MAX_CUTS",
                 "MAX_EMITTER_POINTS", "MAX_STROKES", "MAX_SKETCH_POINTS", "MAX_BLOCKS",
                 "MAX_ROW_LABELS", "MAX_SLIDES", "MAX_COLUMN_NAME"):
        assert re.search(rf"\b{getattr(bounds, name):,}\b", text), name
