"""Property-based tests: random DataFrames, bindings, polygons, emitters and designs
never raise anything but the documented ValueError / TypeError, and a refused
change leaves the chart as it was."""
from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import unitopia_widget as uw

CIRCLE = uw.Mark.shape("circle")      # shared: renders cached once, so examples stay cheap
DOCUMENTED = (ValueError, TypeError)
FAST = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])

floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
texts = st.text(st.characters(min_codepoint=0, max_codepoint=0x2FF), max_size=6)
cells = st.one_of(floats, st.integers(-10**6, 10**6), texts, st.none(), st.booleans())


@st.composite
def frames(draw):
    """A small DataFrame with columns of mixed, often hostile, dtypes."""
    n = draw(st.integers(0, 12) if draw(st.integers(0, 9)) == 0 else st.integers(1, 12))
    columns = {}
    for name in draw(st.lists(st.sampled_from(["a", "b", "Size", "size", "c d", "é", "0"]),
                              min_size=0, max_size=4, unique=True)):
        kind = draw(st.sampled_from(["float", "int", "text", "mixed", "bool", "nullable", "date",
                                     "category"]))
        if kind == "float":
            col = draw(st.lists(floats, min_size=n, max_size=n))
        elif kind == "int":
            col = draw(st.lists(st.integers(-5, 10**9), min_size=n, max_size=n))
        elif kind == "text":
            col = draw(st.lists(texts, min_size=n, max_size=n))
        elif kind == "mixed":
            col = pd.Series(draw(st.lists(cells, min_size=n, max_size=n)), dtype=object)
        elif kind == "bool":
            col = draw(st.lists(st.booleans(), min_size=n, max_size=n))
        elif kind == "nullable":
            col = pd.array(draw(st.lists(st.one_of(st.none(), st.integers(-3, 9)), min_size=n,
                                         max_size=n)), dtype="Int64")
        elif kind == "date":
            col = pd.to_datetime(draw(st.lists(st.integers(0, 10**9), min_size=n, max_size=n)),
                                 unit="s")
        else:
            col = pd.Categorical(draw(st.lists(st.sampled_from(["x", "y", "z"]), min_size=n,
                                               max_size=n)))
        columns[name] = col
    return pd.DataFrame(columns, index=range(n)) if columns else pd.DataFrame(index=range(n))


@st.composite
def bindings(draw, df):
    names = list(df.columns)
    column = st.sampled_from(names) if names else st.just("missing")
    wrong = st.sampled_from(["missing", "Sise", "red", "#00ff00"]) | st.none() | st.integers(-1, 3) \
        | st.floats(-1, 3)
    out = {}
    for channel in ("size", "width", "height", "color", "margin", "order", "by"):
        if draw(st.integers(0, 2)) == 0:   # a third of the channels bound, mostly to columns
            out[channel] = draw(column if draw(st.integers(0, 3)) else wrong)
    if draw(st.booleans()):
        out["dropna"] = draw(st.booleans())
    if draw(st.integers(0, 7)) == 0:
        out[draw(st.sampled_from(["sise", "colour", "canvas", "seed", "iterations", "boundary",
                                  "fill", "rotate", "orientation"]))] = draw(cells)
    return out


@FAST
@pytest.mark.filterwarnings("ignore:dropna=True")
@given(data=st.data())
def test_random_frames_and_bindings_build_or_raise_a_documented_error(data):
    df = data.draw(frames())
    kwargs = data.draw(bindings(df))
    try:
        chart = uw.Chart(df, mark=CIRCLE, **kwargs)
    except DOCUMENTED as exc:
        assert str(exc)                                  # every refusal says something
        return
    units = chart._units
    assert 0 < len(units.rows) <= len(df)
    for arr in (units.half_w, units.half_h, units.area, units.margin):
        assert np.isfinite(arr).all() and (arr >= 0).all()
    assert (units.half_w > 0).all() and (units.half_h > 0).all()
    json.dumps(chart.design())                         # the design is always valid JSON


coords = st.floats(-2000, 2000, allow_nan=False) | st.sampled_from([0.0, 1e-9, 800.0, 500.0, 1e12,
                                                                     math.nan, math.inf])


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(points=st.lists(st.tuples(coords, coords), min_size=0, max_size=9))
def test_random_polygons_as_containers_lay_out_or_raise_a_documented_error(points):
    df = pd.DataFrame({"v": [1.0, 2.0, 3.0]})
    try:
        chart = uw.Chart(df, mark=CIRCLE, container=uw.Container.polygon(points), iterations=20)
    except DOCUMENTED as exc:
        assert str(exc)
        return
    try:
        table = chart.layout(cancel=lambda: True)     # the full pipeline up to the solver
    except ValueError as exc:                          # e.g. a sliver with no raster pixel inside
        assert "container" in str(exc)
        return
    assert np.isfinite(table[["x", "y", "width", "height"]].to_numpy()).all()


@settings(max_examples=60, deadline=None)
@given(points=st.one_of(st.lists(st.tuples(coords, coords), max_size=11),
                        st.lists(coords, max_size=8), cells))
def test_random_emitter_points_build_or_raise_a_documented_error(points):
    try:
        emitter = uw.CurveEmitter(points)
    except DOCUMENTED as exc:
        assert str(exc)
        return
    assert (len(emitter.points) - 1) % 3 == 0 and np.isfinite(emitter.points).all()


def fresh_chart():
    df = pd.DataFrame({"Task": ["a", "b", "a", "c"], "Duration": [1.0, 2.0, 3.0, 4.0]})
    return uw.Chart(df, by="Task", size="Duration", mark=CIRCLE)


layer_keys = st.sampled_from(["name", "rows", "mark", "encodings", "container", "emitter", "forces",
                              "boundary", "fill", "orientation", "rotate", "blocks", "iterations"])
junk = st.recursive(cells | st.just({"kind": "rect"}) | st.just({"kind": "svg", "svg": "/etc/passwd"}),
                    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(texts, inner, max_size=3),
                    max_leaves=6)


@settings(max_examples=80, deadline=None)
@given(edits=st.lists(st.tuples(st.integers(0, 2), layer_keys | st.sampled_from(["encodings.size",
                                                                              "encodings.margin"]),
                                junk), min_size=1, max_size=3),
       top=st.one_of(st.none(), st.tuples(st.sampled_from(["canvas", "seed", "background", "version",
                                                            "layers", "schema"]), junk)))
def test_random_design_edits_apply_whole_or_not_at_all(edits, top):
    chart = fresh_chart()
    before = json.dumps(chart.design())
    design = json.loads(before)
    for i, key, value in edits:
        layer = design["layers"][i]
        if key.startswith("encodings."):
            if not isinstance(layer.get("encodings"), dict):
                layer["encodings"] = {}
            layer["encodings"][key.split(".")[1]] = value
        else:
            layer[key] = value
    if top is not None:
        design[top[0]] = top[1]
    try:
        chart.apply_design(design)
    except DOCUMENTED as exc:
        assert str(exc)
        assert json.dumps(chart.design()) == before
        return
    json.dumps(chart.design())


@settings(max_examples=60, deadline=None)
@given(field=st.sampled_from(["size", "width", "color", "margin", "order", "boundary", "fill",
                              "orientation", "rotate", "blocks", "iterations", "name", "container",
                              "emitter", "forces", "mark"]),
       value=junk | st.sampled_from(["Duration", "Task", "b", "c", "star", "open"]))
def test_random_layer_edits_apply_or_leave_the_layer_unchanged(field, value):
    chart = fresh_chart()
    before = json.dumps(chart.design())
    try:
        chart.layer("a").set(**{field: value})
    except DOCUMENTED as exc:
        assert str(exc)
        assert json.dumps(chart.design()) == before
        return
    chart.bind_check()                                   # an accepted edit binds
    json.dumps(chart.design())
