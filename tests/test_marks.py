"""Marks: constructors, silhouettes, fragments, recolouring, JSON."""
import base64
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest
import resvg_py
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from PIL import Image

from unitopia_widget.design.marks import SHAPES, Mark

DATA = Path(__file__).parent / "data" / "marks"
SVG = 'xmlns="http://www.w3.org/2000/svg"'
REQUIRED_SHAPES = ["circle", "square", "triangle", "star", "drop", "heart", "hexagon", "diamond"]


def render(svg_text: str) -> np.ndarray:
    """uint8 (h, w, 4) RGBA of an SVG document, rendered by resvg."""
    png = resvg_py.svg_to_bytes(svg_string=svg_text)
    return np.asarray(Image.open(io.BytesIO(bytes(png))).convert("RGBA"))


def render_fragment(mark: Mark, color=None, px=100) -> np.ndarray:
    """Render ``mark.svg_fragment`` on its own, ``px`` pixels per box unit scaled to fit."""
    w, h = mark.box_size
    scale = px / max(w, h)
    return render(f'<svg {SVG} width="{round(w * scale)}" height="{round(h * scale)}" '
                  f'viewBox="0 0 {w} {h}">{mark.svg_fragment("t", color)}</svg>')


def close(pixel, rgb, tol=6):
    return pixel[3] == 255 and all(abs(int(a) - b) <= tol for a, b in zip(pixel[:3], rgb))


# --- shapes and silhouettes ---------------------------------------------------

@pytest.mark.parametrize("name", REQUIRED_SHAPES)
def test_required_shapes_exist_with_sane_geometry(name):
    mark = Mark.shape(name)
    assert mark.kind == "shape" and name in SHAPES
    assert 0.6 < mark.aspect < 1.5
    assert 0.25 < mark.fill_fraction <= 1.0


def test_circle_and_square_fill_fractions():
    assert Mark.shape("circle").fill_fraction == pytest.approx(math.pi / 4, rel=0.01)
    assert Mark.shape("square").fill_fraction == pytest.approx(1.0, abs=1e-3)
    assert Mark.shape("diamond").fill_fraction == pytest.approx(0.5, rel=0.01)
    assert Mark.shape("triangle").aspect == pytest.approx(2 / math.sqrt(3), rel=1e-4)


@pytest.mark.parametrize("max_side", [1, 7, 64, 300])
def test_silhouette_shape_range_and_cache(max_side):
    mark = Mark.shape("triangle")                       # wider than tall
    sil = mark.silhouette(max_side)
    assert sil.dtype == np.float32 and max(sil.shape) == max_side
    assert sil.shape[1] == max_side                     # the long side is the width
    assert sil.min() >= 0.0 and sil.max() <= 1.0
    sil[:] = 0.123                                      # callers get their own copy
    again = mark.silhouette(max_side)
    assert again.flags.writeable and not np.all(again == np.float32(0.123))


def test_silhouette_is_antialiased_and_tight():
    sil = Mark.shape("circle").silhouette(200)
    partial = (sil > 0.02) & (sil < 0.98)
    assert partial.sum() > 100                          # a soft edge, not a binary mask
    assert sil[0].max() > 0 and sil[-1].max() > 0 and sil[:, 0].max() > 0 and sil[:, -1].max() > 0
    assert sil[100, 100] == 1.0


def test_tall_silhouette_has_long_side_as_height():
    sil = Mark.shape("drop").silhouette(128)
    assert sil.shape == (128, round(128 * 0.7))


# --- SVG marks ------------------------------------------------------------------

def test_svg_from_path_text_and_pathlike_agree():
    by_path = Mark.svg(DATA / "rect_2to1.svg")
    by_str = Mark.svg(str(DATA / "rect_2to1.svg"))
    by_text = Mark.svg((DATA / "rect_2to1.svg").read_text())
    assert by_path.kind == "svg" and by_path == by_str == by_text
    assert by_path.aspect == pytest.approx(2.0, rel=5e-3)
    assert by_path.box_size == pytest.approx((200, 100), rel=5e-3)
    assert by_path.fill_fraction == pytest.approx(1.0, abs=0.01)


def test_svg_box_is_tight_around_visible_content_only():
    text = (f'<svg {SVG} width="10mm" height="10mm"><circle cx="20" cy="20" r="5"/>'
            '<rect x="100" y="0" width="50" height="50"/></svg>')   # the rect is off the viewport
    mark = Mark.svg(text)
    assert mark.box_size == pytest.approx((10, 10), rel=0.01)
    assert mark.fill_fraction == pytest.approx(math.pi / 4, rel=0.02)


def test_style_class_rules_shape_the_silhouette():
    mark = Mark.svg(DATA / "class_styled.svg")         # fill="none" overridden by a class rule
    assert mark.box_size == pytest.approx((48, 48), rel=0.01)
    assert mark.fill_fraction == pytest.approx(math.pi / 4, rel=0.02)
    assert close(render_fragment(mark)[50, 50], (0x2C, 0xA0, 0x2C))


def test_scoped_fragments_keep_their_own_colours_in_one_document():
    red, blue = Mark.svg(DATA / "class_a_red.svg"), Mark.svg(DATA / "class_a_blue.svg")
    frag_red, frag_blue = red.svg_fragment("m0", None), blue.svg_fragment("m1", None)
    assert 'id="m0"' in frag_red and "m0-a" in frag_red and "url(#m0-g)" in frag_red
    for layout in ("use", "inline"):
        if layout == "use":
            body = (f"<defs>{frag_red}{frag_blue}</defs>"
                    '<use href="#m0" x="0" y="0"/><use href="#m1" x="20" y="0"/>')
        else:
            body = f'{frag_red}<g transform="translate(20 0)">{frag_blue}</g>'
        doc = render(f'<svg {SVG} width="400" height="200" viewBox="0 0 40 20">{body}</svg>')
        for x0, rgb in ((0, (255, 0, 0)), (200, (0, 0, 255))):
            for x, y in ((x0 + 100, 50), (x0 + 50, 150), (x0 + 150, 150)):  # class, gradient, circle
                assert close(doc[y, x], rgb), (layout, x, y, doc[y, x])


def test_recolouring_a_one_colour_icon_replaces_it():
    mark = Mark.svg(DATA / "class_a_red.svg")
    img = render_fragment(mark, "#00aa00")
    for x, y in ((50, 25), (25, 75), (75, 75)):
        assert close(img[y, x], (0, 0xAA, 0))


def lum(pixel) -> float:
    return 0.2126 * int(pixel[0]) + 0.7152 * int(pixel[1]) + 0.0722 * int(pixel[2])


def test_recolouring_a_multicolour_icon_tints_it_and_keeps_black_and_white_details():
    mark = Mark.svg(DATA / "multicolor.svg")
    img = render_fragment(mark, "#9467bd", px=400)      # 4 squares of 100 px
    orange, blue = img[50, 50], img[50, 150]           # luminance 146 and 105: the median, 125.5
    assert lum(orange) > lum(blue) + 20                 # their shading stays
    for pixel in (orange, blue):                        # both the target's hue: purple
        assert pixel[2] > pixel[0] > pixel[1]
    assert close(img[50, 250], (255, 255, 255))         # white kept
    assert close(img[50, 350], (0, 0, 0))               # black kept
    original = render_fragment(mark, None, px=400)
    assert close(original[50, 50], (0xFF, 0x7F, 0x0E))


SHADED = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 60 10"><defs>'
          '<linearGradient id="g"><stop offset="0" stop-color="#1f3f7f"/>'
          '<stop offset="1" stop-color="#cfdfff"/></linearGradient></defs>'
          + "".join(f'<rect x="{10 * i}" width="10" height="10" fill="{c}"/>' for i, c in
                    enumerate(("#1f3f7f", "#3f5f9f", "#6f8fcf", "#9fbfff", "#cfdfff")))
          + '<rect x="50" width="10" height="10" fill="url(#g)"/></svg>')


def test_a_tint_keeps_every_luminance_level_of_a_shaded_mark_in_order():
    """A blue mark shaded in five tones and a gradient, tinted red: five distinct, ordered
    luminances, all red; the gradient still runs dark to light."""
    img = render_fragment(Mark.svg(SHADED), "#e15759", px=600)   # 6 bands of 100 px
    levels = [lum(img[50, 100 * i + 50]) for i in range(5)]
    assert all(b - a > 12 for a, b in zip(levels, levels[1:])), levels
    for i in range(5):
        r, g, b = (int(v) for v in img[50, 100 * i + 50][:3])
        assert r > g and r > b, (i, r, g, b)
    assert lum(img[50, 590]) - lum(img[50, 510]) > 60   # the gradient's shading


@pytest.mark.parametrize("body", [
    '<path d="M0 0 H10 V10 H0 Z"/>',                                        # default black fill
    '<path d="M1 1 H9 V9 H1 Z" fill="none" stroke="currentColor" stroke-width="2"/>',
    '<rect width="10" height="10" fill="#111"/><rect x="3" y="3" width="4" height="4" fill="#fff"/>',
])
def test_recolouring_black_icons(body):
    mark = Mark.svg(f'<svg {SVG} viewBox="0 0 10 10">{body}</svg>')
    img = render_fragment(mark, "#d62728")
    assert close(img[2, 50], (0xD6, 0x27, 0x28)), img[2, 50]


def test_shapes_and_sketches_are_drawn_in_the_given_colour():
    assert close(render_fragment(Mark.shape("square"), "#123456")[50, 50], (0x12, 0x34, 0x56))
    sketch = Mark.sketch([[(0, 5), (10, 5)]], width=10, color="#222")
    img = render_fragment(sketch, "orange")
    assert close(img[img.shape[0] // 2, 50], (255, 165, 0))


def test_data_url_is_a_self_contained_svg_with_the_box_as_viewbox():
    mark = Mark.svg(DATA / "rect_2to1.svg")
    url = mark.data_url()
    assert url.startswith("data:image/svg+xml;base64,")
    text = base64.b64decode(url.split(",", 1)[1]).decode()
    assert 'viewBox="0 0 200' in text and "href" not in text
    img = render(text)
    assert img.shape[1] == 2 * img.shape[0] and img[..., 3].min() == 255


def test_empty_svg_mark_is_refused():
    for text in (f"<svg {SVG}/>", f'<svg {SVG}><script>x()</script><rect width="0" height="5"/></svg>',
                 f'<svg {SVG}><rect width="5" height="5" fill="none"/></svg>'):
        with pytest.raises(ValueError, match="mark is empty"):
            Mark.svg(text)


def test_unreadable_svg_path_is_named():
    with pytest.raises(ValueError, match="missing-icon.svg"):
        Mark.svg("missing-icon.svg")


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(
    st.text(max_size=60),
    st.binary(max_size=60),
    st.lists(st.sampled_from(["<svg", f" {SVG}", ">", "</svg>", "<rect", ' width="4"', ' height="3"',
                              "/>", "<!ENTITY", "&a;", "<g>", "</g>", ' fill="red"', "<circle r='2'/>",
                              ' viewBox="0 0 0 5"', "<style>rect{fill:none}</style>"]), max_size=12)
    .map("".join),
))
def test_arbitrary_input_to_svg_raises_only_value_error(source):
    try:
        mark = Mark.svg(source)
    except ValueError:
        return
    assert mark.aspect > 0 and 0 < mark.fill_fraction <= 1


# --- raster marks ---------------------------------------------------------------

def test_white_background_is_keyed_but_inner_white_kept():
    mark = Mark.image(DATA / "figure_on_white.png")
    assert mark.kind == "image"
    assert mark.box_size == (30, 30)                    # the disc, not the 60 x 40 canvas
    assert mark.fill_fraction == pytest.approx(math.pi / 4, rel=0.05)
    sil = mark.silhouette(30)
    assert sil[15, 15] == 1.0                           # the white eye is inside: kept
    assert sil[0, 0] == 0.0
    unkeyed = Mark.image(DATA / "figure_on_white.png", key=None)
    assert unkeyed.box_size == (60, 40) and unkeyed.fill_fraction == 1.0


def test_alpha_is_used_when_present():
    rgba = np.zeros((20, 40, 4), np.uint8)
    rgba[5:15, 10:20] = (255, 255, 255, 255)            # a white square on transparent black
    mark = Mark.image(rgba)
    assert mark.box_size == (10, 10) and mark.fill_fraction == 1.0


@pytest.mark.parametrize("make", [
    lambda a: a[..., 0],                                            # (H, W) uint8
    lambda a: a[..., :3].astype(np.float64) / 255,                  # (H, W, 3) float
    lambda a: Image.fromarray(a[..., :3]),                          # PIL
])
def test_image_from_arrays_and_pil(make):
    arr = np.full((30, 50, 4), 255, np.uint8)
    arr[10:20, 5:45, :3] = 0                                        # black bar on white
    mark = Mark.image(make(arr))
    assert mark.box_size == (40, 10) and mark.aspect == 4.0


def test_explicit_key_colour_and_empty_image():
    arr = np.zeros((10, 10, 3), np.uint8)
    arr[2:4, 2:8] = (0, 255, 0)
    mark = Mark.image(arr, key="#00ff00")                           # green screen
    assert mark.box_size == (10, 10)
    assert mark.silhouette(10)[3, 5] == 0.0 and mark.silhouette(10)[8, 5] == 1.0
    with pytest.raises(ValueError, match="mark is empty"):
        Mark.image(np.zeros((5, 5, 4), np.uint8))


def test_raster_tint_keeps_alpha_and_luminance_detail():
    arr = np.zeros((10, 20, 4), np.uint8)
    arr[:, :10] = (0, 0, 0, 255)                                    # dark half
    arr[:, 10:] = (200, 200, 200, 128)                              # light, half-transparent half
    mark = Mark.image(arr)
    frag = mark.svg_fragment("r", "#ff0000")
    png = base64.b64decode(frag.split("base64,")[1].split('"')[0])
    tinted = np.asarray(Image.open(io.BytesIO(png)).convert("RGBA")).astype(int)
    assert (tinted[..., 3] == arr[..., 3]).all()
    dark, light = tinted[5, 2], tinted[5, 15]
    assert dark[1] == dark[2] == 0 and light[1] == light[2] == 0   # red hue only
    assert light[0] == 255 and 0 < dark[0] < light[0]              # detail kept
    assert frag.startswith('<g id="r"><image') and 'width="20"' in frag
    assert mark.data_url().startswith("data:image/png;base64,")


# --- sketches ---------------------------------------------------------------------

def test_sketch_box_includes_round_caps():
    mark = Mark.sketch([np.array([[0, 0], [100, 0]]), [[50, 50]]], width=10)
    assert mark.kind == "sketch" and mark.box_size == (110, 60)
    sil = mark.silhouette(110)
    assert sil.shape == (60, 110)
    assert sil[5, 55] == 1.0 and sil[55, 55] == 1.0 and sil[30, 55] == 0.0
    assert sil[0, 0] < 0.5                                          # a round cap, not a square one


def test_sketch_rejects_bad_input():
    for strokes in ([], [[]], [[(0, float("nan"))]], "abc"):
        with pytest.raises(ValueError, match="sketch"):
            Mark.sketch(strokes)
    with pytest.raises(ValueError, match="width"):
        Mark.sketch([[(0, 0)]], width=0)


# --- JSON, equality, from_spec ------------------------------------------------------

def test_json_round_trip_for_every_kind():
    marks = [Mark.shape("star"), Mark.svg(DATA / "hostile.svg"),
             Mark.image(DATA / "figure_on_white.png"),
             Mark.sketch([[(0, 0), (3.25, 1e-3)]], width=2.5, color="#abc")]
    for mark in marks:
        d = json.loads(json.dumps(mark.to_json()))
        again = Mark.from_json(d)
        assert again == mark and hash(again) == hash(mark) and again.kind == mark.kind
        assert again.box_size == pytest.approx(mark.box_size)
    assert marks[0].to_json() == {"kind": "shape", "name": "star"}
    assert marks[3].to_json() == {"kind": "sketch", "strokes": [[[0.0, 0.0], [3.25, 0.001]]],
                                  "width": 2.5, "color": "#abc"}
    assert marks[2].to_json()["image"].startswith("data:image/png;base64,")
    assert "script" not in marks[1].to_json()["svg"]
    assert Mark.shape("star") != Mark.shape("circle")


def test_marks_are_immutable():
    mark = Mark.shape("circle")
    with pytest.raises(AttributeError):
        mark.kind = "svg"
    mark.to_json()["name"] = "square"
    assert mark.to_json()["name"] == "circle"


def test_from_spec_dispatch(tmp_path):
    star = Mark.shape("star")
    assert Mark.from_spec(star) is star
    assert Mark.from_spec("heart") == Mark.shape("heart")
    assert Mark.from_spec((DATA / "rect_2to1.svg").read_text()).kind == "svg"
    assert Mark.from_spec(DATA / "rect_2to1.svg").kind == "svg"
    assert Mark.from_spec(str(DATA / "figure_on_white.png")).kind == "image"
    jpg = tmp_path / "photo.JPEG"
    Image.new("RGB", (8, 4), (255, 255, 255)).save(jpg, format="JPEG")
    blank = Mark.from_spec(jpg)                         # a uniform image is kept whole
    assert blank.kind == "image" and blank.box_size == (8, 4) and blank.fill_fraction == 1.0
    assert Mark.from_spec(np.zeros((4, 4), np.uint8)).kind == "image"
    assert Mark.from_spec(Image.new("L", (3, 3))).kind == "image"
    assert Mark.from_spec({"kind": "shape", "name": "drop"}) == Mark.shape("drop")


@pytest.mark.parametrize("spec, extra", [
    ("circel", "did you mean 'circle'"),
    ("chart.gif", "chart.gif"),
    (42, "42"),
    ({"kind": "video"}, "video"),
])
def test_from_spec_errors_name_the_value_and_the_choices(spec, extra):
    with pytest.raises(ValueError) as info:
        Mark.from_spec(spec)
    message = str(info.value)
    assert extra in message
    for word in ("shape", "svg", "image", "sketch", *REQUIRED_SHAPES):
        assert word in message


@pytest.mark.parametrize("d", [
    {"kind": "shape", "name": ["circle"]}, {"kind": "shape"}, {"kind": "svg", "svg": 5},
    {"kind": "image", "image": 5}, {"kind": "image", "image": "data:text/html;base64,PGI+"},
    {"kind": "sketch", "strokes": [[[0, 0]]], "color": 7}, {"kind": "sketch", "strokes": 3},
])
def test_from_json_rejects_malformed_dicts_with_value_error(d):
    with pytest.raises(ValueError):
        Mark.from_json(d)


def test_fragment_rejects_bad_ids_and_colours():
    mark = Mark.shape("circle")
    with pytest.raises(ValueError, match="def_id"):
        mark.svg_fragment('x" onload="alert(1)', None)
    with pytest.raises(ValueError, match="colour"):
        mark.svg_fragment("ok", "not-a-colour")


def test_translucent_paint_occupies_its_whole_footprint():
    opaque = Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
                      '<circle cx="5" cy="5" r="5" fill="#e0457b"/></svg>')
    faint = Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
                     '<g opacity="0.4"><circle cx="5" cy="5" r="5" fill="#e0457b" '
                     'fill-opacity="0.5"/></g></svg>')
    assert np.allclose(faint.silhouette(64), opaque.silhouette(64), atol=0.02)
    assert 'opacity="0.4"' in faint.svg_fragment("m0")   # the drawing keeps its translucency
