"""Hostile and careless input, end to end through ``uw.Chart`` / ``uw.UnitoPia``.

Unit-level SVG and raster safety is in test_svgsafe.py and test_marks.py; here
every case goes through the public API and, where it matters, the export:
each ends in a ValueError/TypeError naming what was wrong, quickly, or in the
safe behaviour (hostile content dropped, nothing partially applied).
"""
from __future__ import annotations

import base64
import copy
import json
import os
import re
import struct
import time
import xml.etree.ElementTree as ET
import zlib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from PIL import Image

import unitopia_widget as uw
from unitopia_widget import chart as chart_module
from unitopia_widget.chart import MAX_LAYERS, MAX_UNITS
from unitopia_widget.design.files import load_design
from unitopia_widget.design.scene import VERSION
from unitopia_widget.io.images import image_data_url

DATA = Path(__file__).parent / "data" / "marks"
STATIC = Path(uw.__file__).parent / "static"
SVG = 'xmlns="http://www.w3.org/2000/svg"'
XLINK = 'xmlns:xlink="http://www.w3.org/1999/xlink"'
CIRCLE = uw.Mark.shape("circle")      # shared: its renders are cached once for the module
BOTH = pytest.mark.parametrize("make", [uw.Chart, uw.UnitoPia], ids=["Chart", "UnitoPia"])


@pytest.fixture
def tasks():
    return pd.DataFrame({"Task": ["write", "test", "write", "ship", "test", "write"],
                         "Duration": [3.0, 1.0, 2.0, 5.0, 4.0, 1.5],
                         "Owner": ["ann", "bob", "cy", "ann", "bob", "cy"]})


def quick_layout(chart):
    """The whole layout pipeline, stopped before the first iteration (start positions)."""
    return chart.layout(cancel=lambda: True)


def bomb_png(side: int, bits: int = 1) -> bytes:
    """A real decompression bomb: a ``side`` x ``side`` grey PNG of zeros, a few kB compressed."""
    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    row = b"\x00" * (1 + (side * bits + 7) // 8)
    z = zlib.compressobj(9)
    idat = b"".join(z.compress(row) for _ in range(side)) + z.flush()
    ihdr = struct.pack(">IIBBBBB", side, side, bits, 0, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat)
            + chunk(b"IEND", b""))


@pytest.fixture(scope="module")
def bombs(tmp_path_factory):
    """Two bombs: over PIL's own limit (20000^2 px) and over ours only (7000^2 = 49M px)."""
    folder = tmp_path_factory.mktemp("bombs")
    paths = []
    for side in (20_000, 7_000):
        path = folder / f"bomb{side}.png"
        path.write_bytes(bomb_png(side))
        assert path.stat().st_size < 200_000
        paths.append(path)
    return paths


# --- 1. binding-time checks ------------------------------------------------------

@BOTH
@pytest.mark.parametrize("kwarg, suggestion", [("sise", "size"), ("colour", "color"),
                                               ("drop_na", "dropna"), ("contianer", "container")])
def test_unknown_keyword_is_a_type_error_suggesting_the_closest(make, tasks, kwarg, suggestion):
    name = make.__name__
    with pytest.raises(TypeError, match=rf"{name}\(\) got an unexpected keyword argument "
                                        rf"'{kwarg}' \(did you mean '{suggestion}'\?\)"):
        make(tasks, **{kwarg: "Duration"})


@BOTH
@pytest.mark.parametrize("kwargs, message", [
    (dict(size="Duraton"), r"size='Duraton': no such column \(did you mean 'Duration'\?\); "
                           r"the columns are 'Task', 'Duration', 'Owner'"),
    (dict(by="Tsk"), r"by='Tsk': no such column \(did you mean 'Task'\?\)"),
    (dict(size="Owner"), r"size='Owner': the column must be numeric, got dtype"),
    (dict(height="Task"), r"height='Task': the column must be numeric"),
    (dict(margin="Owner"), r"margin='Owner': the column must be numeric"),
])
def test_misspelled_and_non_numeric_columns_through_both_entry_points(make, tasks, kwargs,
                                                                       message):
    with pytest.raises(ValueError, match=message):
        make(tasks, **kwargs)


@BOTH
@pytest.mark.parametrize("value, bad, missing", [(-2.0, 1, 0), (0.0, 1, 0), (np.inf, 1, 0),
                                                 (np.nan, 1, 1)])
def test_unusable_sizes_name_the_column_and_count_rows_or_drop_with_a_warning(make, tasks, value,
                                                                              bad, missing):
    df = tasks.assign(Duration=tasks["Duration"].where(tasks.index != 2, value))
    with pytest.raises(ValueError, match=rf"size='Duration': {bad} of 6 rows are missing, infinite "
                                         rf"or not > 0 \({missing} missing\).*dropna=True"):
        make(df, size="Duration")
    with pytest.warns(UserWarning, match=r"dropna=True: dropped 1 of 6 rows .*size='Duration'"):
        kept = make(df, size="Duration", dropna=True)
    assert 2 not in kept.df.index and len(kept.df) == 5


def test_every_row_unusable_with_dropna_is_refused(tasks):
    with pytest.warns(UserWarning, match="dropped 6 of 6"), \
            pytest.raises(ValueError, match="dropna=True dropped every row"):
        uw.Chart(tasks.assign(Duration=-1.0), size="Duration", dropna=True)


@BOTH
@pytest.mark.parametrize("df", [pd.DataFrame(), pd.DataFrame({"Duration": []}, dtype=float)],
                         ids=["no-columns", "no-rows"])
def test_empty_frame_is_refused(make, df):
    with pytest.raises(ValueError, match="df is empty"):
        make(df)


@pytest.mark.parametrize("channel, values", [("size", [1e-300, 1.0, 1e300]),
                                             ("width", [1e308, 1e308, 1e308]),
                                             ("height", [9.7e-286, 2.6e38, 1.0])])
@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning",
                            "ignore:invalid value encountered:RuntimeWarning")
def test_values_too_far_apart_to_draw_are_refused(channel, values):
    """Found by test_properties: such factors underflow to zero-size marks (or overflow)."""
    with pytest.raises(ValueError, match=rf"the values bound to {channel}='v' span too wide a range"):
        uw.Chart(pd.DataFrame({"v": values}), mark=CIRCLE, **{channel: "v"})


def test_margin_none_means_no_margin(tasks):
    assert uw.Chart(tasks, margin=None, mark=CIRCLE)._units.margin.tolist() == [0.0] * len(tasks)


def test_not_a_frame_is_a_type_error():
    with pytest.raises(TypeError, match="df must be a pandas DataFrame, got list"):
        uw.Chart([{"a": 1}])


def test_missing_category_in_by_is_counted_or_dropped(tasks):
    df = tasks.assign(Task=tasks["Task"].where(tasks.index != 1, None))
    with pytest.raises(ValueError, match=r"by='Task': 1 of 6 rows are missing.*dropna=True"):
        uw.Chart(df, by="Task")
    with pytest.warns(UserWarning, match=r"dropped 1 of 6 rows .*by='Task'"):
        chart = uw.Chart(df, by="Task", dropna=True)
    assert sorted(layer.name for layer in chart.layers) == ["ship", "test", "write"]


def test_by_a_column_of_ids_is_refused_before_any_work():
    df = pd.DataFrame({"id": np.arange(MAX_LAYERS + 1)})
    start = time.perf_counter()
    with pytest.raises(ValueError, match=rf"by='id' has {MAX_LAYERS + 1} distinct values.*"
                                         rf"at most {MAX_LAYERS} layers.*color='id'"):
        uw.Chart(df, by="id")
    assert time.perf_counter() - start < 5


def test_unhashable_categories_are_a_type_error():
    df = pd.DataFrame({"tags": [["a"], ["b"]]})
    with pytest.raises(TypeError, match=r"by='tags': the column's values must be hashable"):
        uw.Chart(df, by="tags")


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(boundary="clsed"), ValueError, r"boundary must be one of 'closed', 'open'; got 'clsed'"),
    (dict(orientation="to_centre"), ValueError, r"orientation must be one of None, 'to_center', "
                                                r"'along_emitter'"),
    (dict(mark="strr"), ValueError, r"mark: unknown mark spec 'strr' \(did you mean 'star'\?\)"),
    (dict(device="gpu"), ValueError, r"device must be None, 'auto', 'cpu' or 'cuda', got 'gpu'"),
    (dict(emitter={"kind": "spiral"}), ValueError, r"unknown kind 'spiral'; expected 'grid' or "
                                                   r"'curve'"),
    (dict(container={"kind": "blob"}), ValueError, r"unknown container kind 'blob'; valid kinds "
                                                   r"are 'canvas', 'rect'"),
    (dict(forces={"kind": "point"}), ValueError, r"a 'point' force dict lacks the key 'x'"),
    (dict(seed="x"), TypeError, r"seed must be an integer, got 'x'"),
    (dict(seed=1.5), TypeError, r"seed must be an integer, got 1.5"),
    (dict(seed=10 ** 40), ValueError, r"seed must be an integer in \[-2\*\*63, 2\*\*64 - 1\], got 1000"),
    (dict(rotate="no"), TypeError, r"rotate must be True or False, got 'no'"),
    (dict(iterations=5), ValueError, r"iterations must be an integer between 20 and 100000, got 5"),
    (dict(canvas=(0, 100)), ValueError, r"canvas must be between 16 and 10000 pixels"),
])
def test_unknown_enum_values_and_bad_options_list_what_is_accepted(tasks, kwargs, error, message):
    with pytest.raises(error, match=message):
        uw.Chart(tasks, **kwargs)


def test_emitter_modes_are_listed():
    with pytest.raises(ValueError, match=r"mode must be one of 'free', 'line', 'band'; got 'fre'"):
        uw.CurveEmitter([[0, 0], [10, 0], [20, 0], [30, 10]], mode="fre")


@pytest.mark.parametrize("build", [
    lambda: uw.Container.rect(10, 10, 0, 50),
    lambda: uw.Container.ellipse(10, 10, 5, 0),
    lambda: uw.Container.polygon([[0, 0], [10, 10], [20, 20]]),
    lambda: uw.Container.path("M 0 0 L 10 10 L 0 0 Z"),
], ids=["zero-width-rect", "flat-ellipse", "collinear-polygon", "retracing-path"])
def test_zero_area_containers_are_refused(build):
    with pytest.raises(ValueError, match=r"(w|ry) must be > 0, got 0|zero area"):
        build()


def test_zero_width_rectangle_through_the_chart_and_the_design(tasks):
    with pytest.raises(ValueError, match=r"Container.rect: w must be > 0, got 0"):
        uw.Chart(tasks, container={"kind": "rect", "x": 0, "y": 0, "w": 0, "h": 50})
    chart = uw.Chart(tasks)
    with pytest.raises(ValueError, match=r"w must be > 0, got 0"):
        chart.layer(0).set(container={"kind": "rect", "x": 0, "y": 0, "w": 0, "h": 50})
    assert chart.layer(0).container is None


def test_a_container_off_the_canvas_is_refused_at_binding_time(tasks):
    with pytest.raises(ValueError, match=r"layer 'layer-1': its container Container.rect\(900, 0, "
                                         r"50, 50\) has no area inside the 800 x 500 canvas"):
        uw.Chart(tasks, container=uw.Container.rect(900, 0, 50, 50))


@pytest.mark.parametrize("pixels", [np.full((40, 60, 3), 255, np.uint8),
                                    np.zeros((40, 60, 4), np.uint8)], ids=["white", "transparent"])
def test_image_container_without_inside_pixels_is_refused(tasks, pixels):
    with pytest.raises(ValueError, match=r"Container.image: no pixel is inside \(all 2400 pixels"):
        uw.Chart(tasks, container=uw.Container.image(pixels))
    url = image_data_url(Image.fromarray(pixels))
    with pytest.raises(ValueError, match=r"no pixel is inside"):
        uw.Chart(tasks, container={"kind": "image", "image": url})


@pytest.mark.parametrize("count", [1, 2, 3, 5, 6, 8])
def test_emitters_with_the_wrong_number_of_control_points(tasks, count):
    points = np.column_stack([np.arange(count) * 10.0, np.zeros(count)]).tolist()
    message = r"points must be cubic Bezier control points of shape \(3k \+ 1, 2\).*4, 7, 10"
    with pytest.raises(ValueError, match=message):
        uw.CurveEmitter(points)
    with pytest.raises(ValueError, match=message):
        uw.Chart(tasks, emitter={"kind": "curve", "points": points})


def test_block_cycles_are_named_and_the_refused_edit_is_undone(tasks):
    chart = uw.Chart(tasks, by="Task", mark=CIRCLE)
    chart.layer("ship").set(blocks=["test"])
    chart.layer("test").set(blocks=["write"])
    with pytest.raises(ValueError, match=r"block cycle: 'ship' -> 'test' -> 'write' -> 'ship'"):
        chart.layer("write").set(blocks=["ship"])
    assert chart.layer("write").blocks == []
    with pytest.raises(ValueError, match=r"block cycle: layer 'ship' blocks on itself"):
        chart.layer("ship").set(blocks=["ship"])
    with pytest.raises(ValueError, match=r"blocks on 'tset': no such layer \(did you mean 'test'\?\)"):
        chart.layer("ship").set(blocks=["tset"])
    assert chart.layer("ship").blocks == ["test"]
    quick_layout(chart)                               # the kept design still lays out


def test_a_refused_layer_edit_or_new_layer_changes_nothing(tasks):
    chart = uw.Chart(tasks, by="Task", mark=CIRCLE)
    before = json.dumps(chart.design())
    with pytest.raises(ValueError, match=r"size='Duraton': no such column"):
        chart.layer("ship").set(size="Duraton", color="Owner")
    with pytest.raises(ValueError, match=r"a layer named 'test' exists already"):
        chart.layer("ship").set(name="test")
    with pytest.raises(ValueError, match=r"size='Owner': the column must be numeric"):
        chart.add_layer("extra", data=tasks.iloc[:2], size="Owner")
    assert json.dumps(chart.design()) == before


def test_too_many_units_added_by_a_layer_are_refused_and_undone():
    df = pd.DataFrame({"v": np.ones(MAX_UNITS // 2 + 1)})
    chart = uw.Chart(df, mark=CIRCLE)
    with pytest.raises(ValueError, match=rf"{2 * len(df)} units is more than this widget lays out "
                                         rf"\({MAX_UNITS}\)"):
        chart.add_layer("again", data=df)
    assert [layer.name for layer in chart.layers] == ["layer-1"]


# --- 2. hostile SVG and images, through the chart and its export --------------------

HOSTILE_WORDS = ("<script", "onload", "onclick", "onmouseover", "foreignobject", "javascript:",
                 "file:", "/etc/", "evil.example", "@import")


def assert_clean(text: str) -> None:
    lowered = text.lower()
    for word in HOSTILE_WORDS:
        assert word not in lowered, word
    root = ET.fromstring(text)                        # the export is well-formed XML
    for el in root.iter():
        for name, value in el.attrib.items():
            if name.rsplit("}", 1)[-1] == "href":
                assert value.startswith(("#", "data:image/")), value
    for url in re.findall(r"url\(\s*['\"]?([^'\")]*)", text):
        assert url.startswith(("#", "data:image/")), url


def widget_mark_svgs(w) -> list[str]:
    """The SVG documents the widget sends to the front end (as data URLs, never markup)."""
    out = []
    for mark in w.marks:
        assert mark["src"].startswith(("data:image/svg+xml;base64,", "data:image/png;base64,"))
        if mark["src"].startswith("data:image/svg+xml;base64,"):
            out.append(base64.b64decode(mark["src"].split(",", 1)[1]).decode())
    return out


def test_scripts_handlers_and_external_references_never_reach_the_export(tasks, tmp_path):
    hostile = (DATA / "hostile.svg").read_text()
    w = uw.UnitoPia(tasks, mark=hostile, size="Duration", color="Task", iterations=20)
    quick_layout(w._chart)
    svg = w.to_svg()
    assert_clean(svg)
    assert svg.count('class="unit"') == len(tasks)
    w.save(tmp_path / "chart.svg")
    assert_clean((tmp_path / "chart.svg").read_text())
    w.save(tmp_path / "design.json")
    assert_clean(json.loads((tmp_path / "design.json").read_text())["layers"][0]["marks"][0]["svg"])
    for doc in widget_mark_svgs(w):
        assert_clean(doc)


def red_secret(tmp_path) -> Path:
    path = tmp_path / "secret.png"
    Image.new("RGBA", (16, 16), (255, 0, 0, 255)).save(path)
    return path


def local_reference_svg(secret: Path) -> str:
    return (f'<svg {SVG} {XLINK} viewBox="0 0 100 100">'
            f'<rect x="30" y="30" width="40" height="40" fill="#000"/>'
            f'<image href="file://{secret}" x="0" y="0" width="100" height="100"/>'
            f'<image xlink:href="{secret}" x="0" y="0" width="100" height="100"/>'
            f'<rect x="0" y="0" width="100" height="100" fill="url({secret})" '
            f'style="fill: url(&quot;file://{secret}&quot;)"/></svg>')


def test_an_svg_referencing_a_local_image_never_reads_it(tasks, tmp_path):
    secret = red_secret(tmp_path)
    chart = uw.Chart(tasks, mark=local_reference_svg(secret), canvas=(200, 150), iterations=20)
    quick_layout(chart)
    svg = chart.to_svg()
    assert str(secret) not in svg and "secret" not in svg
    assert_clean(svg)
    chart.save(tmp_path / "chart.png")
    rgba = np.asarray(Image.open(tmp_path / "chart.png").convert("RGBA")).astype(int)
    red = (rgba[..., 0] > 200) & (rgba[..., 1] < 60) & (rgba[..., 2] < 60) & (rgba[..., 3] > 0)
    assert not red.any()                               # the secret's pixels are nowhere
    assert (rgba[..., 3] > 0).any()                    # but the chart itself is drawn


@pytest.mark.parametrize("body", [
    "<script>alert(1)</script>",
    '<foreignObject width="50" height="50"><div xmlns="http://www.w3.org/1999/xhtml">'
    'hi</div></foreignObject>',
    '<image href="file:///etc/passwd" width="50" height="50"/>',
    '<image href="https://evil.example/a.png" width="50" height="50"/>',
    '<rect width="0" height="0" onclick="alert(1)"/>',
], ids=["script", "foreignObject", "local-file", "remote", "handler-only"])
def test_marks_empty_after_cleaning_are_refused(tasks, body):
    with pytest.raises(ValueError, match=r"mark: SVG mark is empty: nothing is visible after "
                                         r"sanitising"):
        uw.Chart(tasks, mark=f"<svg {SVG} viewBox='0 0 50 50'>{body}</svg>")


@BOTH
def test_xml_bomb_is_refused_in_well_under_a_second(make, tasks):
    bomb = (DATA / "billion_laughs.svg").read_text()
    start = time.perf_counter()
    with pytest.raises(ValueError, match=r"mark: SVG refused: .*entity"):
        make(tasks, mark=bomb)
    with pytest.raises(ValueError, match=r"mark: SVG refused: .*entity"):
        make(tasks, mark=str(DATA / "billion_laughs.svg"))
    if make is uw.Chart:
        assert time.perf_counter() - start < 1


def test_xml_bomb_in_a_design_is_refused_fast(tasks):
    chart = uw.Chart(tasks, mark=CIRCLE)
    design = chart.design()
    design["layers"][0]["marks"] = [{"kind": "svg", "svg": (DATA / "billion_laughs.svg").read_text()}]
    before = json.dumps(chart.design())
    start = time.perf_counter()
    with pytest.raises(ValueError, match=r"entity"):
        chart.apply_design(design)
    assert time.perf_counter() - start < 1
    assert json.dumps(chart.design()) == before


@pytest.mark.parametrize("text, message", [
    ("<svg", "not well-formed"),
    (f"<svg {SVG}><rect></svg>", "not well-formed"),
    (f"<svg {SVG}><rect width='1' height='1'/>", "not well-formed"),
    ("<html><body/></html>", r"root element is <html>, not <svg>"),
    ("<svg xmlns='http://www.w3.org/2000/svg'>\x00</svg>", "not well-formed"),
    (f"<svg {SVG}>" + "<g>" * 400 + "</g>" * 400 + "</svg>", "deeper than"),
], ids=["unclosed", "mismatched", "no-end", "html", "nul", "deep"])
def test_malformed_svg_marks_are_a_clear_value_error(tasks, text, message):
    with pytest.raises(ValueError, match=rf"mark: .*{message}"):
        uw.Chart(tasks, mark=text)


def test_decompression_bomb_png_is_refused_quickly_everywhere(tasks, bombs):
    for path in bombs:
        start = time.perf_counter()
        with pytest.raises(ValueError, match=r"too large"):
            uw.Chart(tasks, mark=str(path))
        with pytest.raises(ValueError, match=r"too large"):
            uw.Container.image(path)
        with pytest.raises(ValueError, match=r"background: .*too large"):
            uw.Chart(tasks, background=path)
        url = "data:image/png;base64," + base64.b64encode(path.read_bytes()).decode()
        with pytest.raises(ValueError, match=r"too large"):
            uw.Chart(tasks, mark={"kind": "image", "image": url})
        with pytest.raises(ValueError, match=r"too large"):
            uw.Chart(tasks, container={"kind": "image", "image": url})
        assert time.perf_counter() - start < 5


def test_a_design_only_holds_inline_data_never_file_paths(tasks, tmp_path):
    secret = red_secret(tmp_path)
    svg_file = tmp_path / "icon.svg"
    svg_file.write_text(f'<svg {SVG}><rect width="4" height="4"/></svg>')
    chart = uw.Chart(tasks, mark=CIRCLE)
    before = json.dumps(chart.design())
    cases = [
        (("layers", 0, "marks", 0), {"kind": "svg", "svg": str(svg_file)}, r"svg mark must hold SVG text"),
        (("layers", 0, "container"), {"kind": "image", "image": str(secret)},
         r"image container must hold a data:image/png"),
        (("background",), {"image": str(secret)}, r"background must be null or \{\"image\": "
                                                   r"\"data:image/png"),
        (("background",), {"image": f"file://{secret}"}, r"background must be null"),
    ]
    for path, value, message in cases:
        design = copy.deepcopy(chart.design())
        target = design
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value
        with pytest.raises(ValueError, match=message):
            chart.apply_design(design)
        assert json.dumps(chart.design()) == before


def test_front_end_edits_with_hostile_svg_are_sanitised(tasks):
    w = uw.UnitoPia(tasks, mark=CIRCLE)
    design = copy.deepcopy(w.design)
    design["layers"][0]["marks"] = [{"kind": "svg", "svg": (DATA / "hostile.svg").read_text()}]
    w.design = design                                  # as the front end would
    assert w.error == ""
    assert w.layers[0].mark.kind == "svg"
    assert_clean(w.design["layers"][0]["marks"][0]["svg"])
    for doc in widget_mark_svgs(w):
        assert_clean(doc)


def test_the_front_end_never_inserts_markup():
    bundle = (STATIC / "widget.js").read_text()
    for sink in ("innerHTML", "outerHTML", "insertAdjacentHTML", "DOMParser", "srcdoc",
                 "createContextualFragment", "document.write", "parseFromString"):
        assert sink not in bundle, sink


def test_control_characters_in_the_data_keep_the_export_well_formed(tmp_path):
    df = pd.DataFrame({"name": ["a\x00b", "c\x0bd", "<script>alert(1)</script>", "]]>&'\""],
                       "v": [1.0, 2.0, 3.0, 4.0]})
    chart = uw.Chart(df, size="v", by="name", mark=CIRCLE)
    quick_layout(chart)
    svg = chart.to_svg()
    ET.fromstring(svg)
    assert "<script" not in svg
    chart.save(tmp_path / "chart.png")
    assert (tmp_path / "chart.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --- 3. the design file: round trip, atomic write, corrupt or newer files -------------

def rich_chart(df) -> uw.Chart:
    chart = uw.Chart(df, by="Task", size="Duration", color="Owner", seed=7,
                     mark={"write": "star", "test": uw.Mark.sketch([[[0, 0], [10, 5], [0, 10]]]),
                           "ship": "heart"})
    chart.layer("write").set(container=uw.Container.rect(20, 20, 400, 300).cut([[30, 30], [90, 60]], 8),
                             emitter=uw.CurveEmitter.from_stroke([[30, 200], [200, 120], [380, 200]]),
                             forces=[uw.PointForce(200, 150)], boundary="open", fill=0.4)
    chart.layer("ship").set(blocks=["write"], rotate=True, orientation="to_center")
    return chart


def test_design_json_round_trip(tasks, tmp_path):
    chart = rich_chart(tasks)
    path = tmp_path / "design.json"
    chart.save(path)
    d = load_design(path)
    assert d == json.loads(json.dumps(chart.design()))
    other = uw.Chart(tasks)
    other.apply_design(d)
    assert json.dumps(other.design()) == json.dumps(chart.design())
    assert other._units.rows == chart._units.rows
    w = uw.UnitoPia.load(path, tasks)
    assert w.design == json.loads(json.dumps(chart.design()))
    assert w.layer("test").mark.kind == "sketch" and w.layer("write").container._cuts


def test_design_json_round_trip_with_numeric_and_datetime_categories(tmp_path):
    df = pd.DataFrame({"k": [1, 2, 1, 2], "b": [True, False, True, False],
                       "t": pd.to_datetime(["2020-01-01", "2020-01-01", "2021-05-01", "2021-05-01"]),
                       "v": [1.0, 2.0, 3.0, 4.0]})
    for by in ("k", "b", "t"):
        chart = uw.Chart(df, by=by, mark=CIRCLE)
        chart.save(tmp_path / "d.json")
        other = uw.Chart(df, mark=CIRCLE)
        other.apply_design(load_design(tmp_path / "d.json"))
        assert other._units.rows == chart._units.rows
        assert [layer.name for layer in other.layers] == [layer.name for layer in chart.layers]


def test_the_design_is_written_atomically(tasks, tmp_path, monkeypatch):
    path = tmp_path / "design.json"
    uw.Chart(tasks).save(path)
    good = path.read_bytes()
    renames = []
    real_replace = os.replace

    def record(src, dst):
        renames.append((src, dst))
        assert Path(src).parent == Path(dst).parent and Path(src).read_bytes()
        return real_replace(src, dst)
    monkeypatch.setattr(chart_module.os, "replace", record)
    chart = rich_chart(tasks)
    chart.save(path)
    assert len(renames) == 1 and renames[0][1] == str(path)
    assert load_design(path)["seed"] == 7

    def crash(src, dst):
        raise OSError("disk full")
    monkeypatch.setattr(chart_module.os, "replace", crash)
    with pytest.raises(OSError, match="disk full"):
        uw.Chart(tasks).save(path)
    assert load_design(path)["seed"] == 7             # the old file is whole
    assert sorted(p.name for p in tmp_path.iterdir()) == ["design.json"]   # no temp left
    assert good != path.read_bytes()


def test_an_unserialisable_design_leaves_the_old_file(tasks, tmp_path, monkeypatch):
    path = tmp_path / "design.json"
    uw.Chart(tasks).save(path)
    good = path.read_bytes()
    chart = uw.Chart(tasks)
    monkeypatch.setattr(chart, "design", lambda: {"bad": object()})
    with pytest.raises(TypeError):
        chart.save(path)
    assert path.read_bytes() == good
    assert sorted(p.name for p in tmp_path.iterdir()) == ["design.json"]


def corrupt_files(good: str) -> dict:
    newer = json.loads(good)
    newer["version"] = 99
    bad_layer = json.loads(good)
    bad_layer["layers"][0]["boundary"] = "leaky"
    no_mark = json.loads(good)
    del no_mark["layers"][0]["marks"]
    return {
        "truncated": (good[: len(good) // 2], r"is not valid JSON"),
        "empty": ("", r"is not valid JSON"),
        "binary": (b"\xff\xfe\x00\x89PNG garbage", r"is not valid JSON"),
        "list": ("[1, 2, 3]", r"not a unitopia design"),
        "other-schema": ('{"schema": "vega", "version": 1}', r"not a unitopia design"),
        "newer": (json.dumps(newer), r"version 99 is newer than this unitopia-widget reads "
                                     rf"\(up to {VERSION}\); upgrade"),
        "bad-field": (json.dumps(bad_layer), r"boundary must be one of 'closed', 'open'; got 'leaky'"),
        "no-mark": (json.dumps(no_mark), r"design layer .*missing 'marks'"),
        "deep": ("[" * 100_000 + "]" * 100_000, r"is not valid JSON|not a unitopia design"),
    }


def test_corrupt_or_newer_design_files_are_clear_errors_not_partial_loads(tasks, tmp_path):
    chart = rich_chart(tasks)
    chart.save(tmp_path / "good.json")
    good = (tmp_path / "good.json").read_text()
    target = uw.Chart(tasks, mark=CIRCLE)
    before = json.dumps(target.design())
    for name, (content, message) in corrupt_files(good).items():
        path = tmp_path / f"{name}.json"
        path.write_bytes(content if isinstance(content, bytes) else content.encode())
        with pytest.raises(ValueError, match=message):
            target.apply_design(load_design(path))
        with pytest.raises(ValueError, match=message):
            uw.UnitoPia.load(path, tasks)
        assert json.dumps(target.design()) == before, name


def test_a_design_that_fails_late_changes_nothing(tasks):
    chart = rich_chart(tasks)
    before = json.dumps(chart.design())
    for edit, message in [
        (lambda d: d.update(seed="seven"), r"seed must be an integer"),
        (lambda d: d["layers"][2].update(blocks=["ship"]), r"block cycle: 'ship' -> 'write' -> 'ship'"),
        (lambda d: d["layers"][0]["encodings"].update(size="Durration"), r"did you mean 'Duration'"),
        (lambda d: d["layers"][-1].update(name=d["layers"][0]["name"]), r"layer names must be unique"),
        (lambda d: d["layers"][0].update(container={"kind": "rect", "x": 5000, "y": 0, "w": 9,
                                                     "h": 9}), r"no area inside the 800 x 500"),
        (lambda d: d["layers"][0].update(rows={"index": [99]}), r"rows are not in the DataFrame"),
        (lambda d: d["layers"][0].update(rows=7), r"layer rows must be None"),
        (lambda d: d.update(canvas=[800]), r"canvas must be \(width, height\)"),
    ]:
        design = copy.deepcopy(chart.design())
        edit(design)
        with pytest.raises((ValueError, TypeError), match=message):
            chart.apply_design(design)
        assert json.dumps(chart.design()) == before


def test_front_end_design_edits_that_fail_report_and_keep_the_design(tasks):
    w = uw.UnitoPia(tasks, by="Task", mark=CIRCLE)
    good = copy.deepcopy(w.design)
    bad = copy.deepcopy(good)
    bad["layers"][0]["blocks"] = [bad["layers"][1]["name"]]
    bad["layers"][1]["blocks"] = [bad["layers"][0]["name"]]
    w.design = bad
    assert w.error.startswith("ValueError: block cycle:")
    assert w.design == good and all(layer.blocks == [] for layer in w.layers)
    w.design = {"schema": "unitopia-design", "version": 7, "layers": []}
    assert "newer than this unitopia-widget reads" in w.error and w.design == good


# --- 4. under load --------------------------------------------------------------------

@BOTH
def test_more_than_max_units_is_refused_quickly(make):
    df = pd.DataFrame({"v": np.linspace(1, 2, MAX_UNITS + 1)})
    start = time.perf_counter()
    with pytest.raises(ValueError, match=rf"{MAX_UNITS + 1} units is more than this widget lays "
                                         rf"out \({MAX_UNITS}\); sample or aggregate"):
        make(df, size="v", mark=CIRCLE)
    assert time.perf_counter() - start < 5


def test_max_units_lay_out_and_export():
    """20,000 marks go through the whole pipeline (stopped before the first iteration:
    an iteration takes about a second at this size on two cores)."""
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"v": rng.uniform(1, 5, MAX_UNITS), "c": rng.integers(0, 7, MAX_UNITS)})
    chart = uw.Chart(df, size="v", color="c", mark=CIRCLE, iterations=20)
    table = quick_layout(chart)
    assert len(table) == MAX_UNITS and np.isfinite(table[["x", "y", "width", "height"]]).all().all()
    assert table["x"].between(0, 800).all() and table["y"].between(0, 500).all()
    assert chart.to_svg().count('class="unit"') == MAX_UNITS


def test_saved_files_get_ordinary_permissions(tmp_path):
    import os
    chart = uw.Chart(pd.DataFrame({"v": [1.0, 2.0]}), mark="circle", size="v", iterations=20)
    chart.layout()
    old = os.umask(0o022)
    try:
        chart.save(tmp_path / "chart.svg")
    finally:
        os.umask(old)
    assert oct(os.stat(tmp_path / "chart.svg").st_mode & 0o777) == oct(0o644)


def test_odd_inputs_are_named_with_bounded_quotes(tmp_path, tasks):
    with pytest.raises(ValueError, match=r"layer rows: 1 label\(s\) listed more than once in 'index', e\.g\. 0"):
        uw.Chart(tasks).add_layer("dup", rows={"index": [0, 0, 0, 1]})
    big = tmp_path / "big.svg"
    with open(big, "wb") as f:
        f.write(b"<svg")
        f.truncate(50_000_000)
    with pytest.raises(ValueError, match=r"is 50,000,000 bytes, over the limit of 5,000,000"):
        uw.Mark.svg(big)
    with pytest.raises(ValueError, match=r"cannot read SVG file '.{59}…': "):
        uw.Mark.svg(str(tmp_path / ("x" * 10_000)))
