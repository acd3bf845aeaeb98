"""Tests for unitopia_widget.design.containers: constructors, coverage, measures, JSON, errors."""
import io
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from PIL import Image

from unitopia_widget.design.containers import KINDS, Container
from unitopia_widget.io.images import image_data_url
from unitopia_widget.design.regions import evenodd_area

CANVAS = (800, 500)
TRIANGLE = [[100.3, 80.7], [650.2, 140.1], [380.9, 460.4]]
HOLED = ("M 100 100 L 700 100 L 700 400 L 100 400 Z "
         "M 200 200 L 300 200 L 300 300 L 200 300 Z")


def white_with_black_block(h=100, w=120):
    """(h, w, 3) uint8 white image with a black block on rows 20:60, columns 30:90."""
    img = np.full((h, w, 3), 255, np.uint8)
    img[20:60, 30:90] = 0
    return img


def test_each_constructor_builds_its_kind():
    built = [Container.canvas(), Container.rect(1, 2, 3, 4), Container.ellipse(5, 6, 7, 8),
             Container.polygon(TRIANGLE), Container.path(HOLED),
             Container.image(white_with_black_block())]
    assert [c.kind for c in built] == list(KINDS)


@pytest.mark.parametrize("rho", [1, 2])
@pytest.mark.parametrize("container, exact", [
    (Container.rect(40.25, 60.6, 300.3, 380.15), 300.3 * 380.15),
    (Container.ellipse(400.4, 250.3, 200.7, 150.2), math.pi * 200.7 * 150.2),
    (Container.polygon(TRIANGLE), 0.5 * abs((650.2 - 100.3) * (460.4 - 80.7)
                                            - (380.9 - 100.3) * (140.1 - 80.7))),
])
def test_coverage_sums_to_the_analytic_area(container, exact, rho):
    cov = container.coverage(CANVAS, rho)
    assert cov.shape == (500 * rho, 800 * rho) and cov.dtype == np.float32
    assert cov.sum() / rho ** 2 == pytest.approx(exact, rel=0.005)
    assert container.area(CANVAS) == pytest.approx(exact, rel=1e-9)
    assert cov.min() >= 0 and cov.max() <= 1


def test_coverage_shape_is_ceil_of_canvas_times_rho():
    assert Container.canvas().coverage((801, 333), 1.5).shape == (500, 1202)


def test_coverage_maps_raster_pixels_to_canvas_squares():
    cov = Container.rect(10, 20, 5, 5).coverage((40, 40), 2)
    assert cov[40:50, 20:30].min() == 1 and cov.sum() == 100
    half = Container.rect(10.5, 0, 2, 40).coverage((40, 40), 1)
    assert half[7, 10] == pytest.approx(0.5) and half[7, 11] == 1 and half[7, 12] == pytest.approx(0.5)


def test_coverage_is_cached_and_read_only():
    c = Container.ellipse(50, 50, 20, 10)
    cov = c.coverage((100, 100), 1)
    assert c.coverage((100, 100), 1) is cov
    with pytest.raises(ValueError):
        cov[0, 0] = 1


def test_canvas_is_the_whole_canvas():
    c = Container.canvas()
    assert c.coverage(CANVAS, 0.5).min() == 1
    assert c.area(CANVAS) == 400_000 and c.centroid(CANVAS) == (400, 250)
    assert c.bbox(CANVAS) == (0, 0, 800, 500)
    assert c.svg_path(CANVAS) == "M0 0H800V500H0Z"


def test_measures_of_a_rect_and_an_ellipse():
    r = Container.rect(40, 60, 300, 380)
    assert r.centroid(CANVAS) == (190, 250) and r.bbox(CANVAS) == (40, 60, 300, 380)
    assert r.svg_path(CANVAS) == "M40 60h300v380h-300Z"
    e = Container.ellipse(400, 250, 200, 150)
    assert e.centroid(CANVAS) == (400, 250) and e.bbox(CANVAS) == (200, 100, 400, 300)
    assert e.svg_path(CANVAS) == "M200 250A200 150 0 1 0 600 250A200 150 0 1 0 200 250Z"


def test_measures_are_clipped_to_the_canvas():
    half_out = Container.ellipse(0, 250, 100, 100)
    assert half_out.area(CANVAS) == pytest.approx(math.pi * 100 ** 2 / 2, rel=1e-3)
    assert half_out.centroid(CANVAS)[0] == pytest.approx(400 / (3 * math.pi), rel=1e-3)
    assert half_out.bbox(CANVAS) == pytest.approx((0, 150, 100, 200), abs=1e-3)
    corner = Container.rect(-10, -20, 100, 100)
    assert corner.bbox(CANVAS) == (0, 0, 90, 80) and corner.area(CANVAS) == 90 * 80
    assert corner.centroid(CANVAS) == (45, 40)
    gone = Container.rect(900, 0, 10, 10)
    assert gone.area(CANVAS) == 0
    with pytest.raises(ValueError, match="does not overlap the 800 x 500 canvas"):
        gone.centroid(CANVAS)


def test_self_intersecting_polygon_fills_even_odd():
    bowtie = Container.polygon([[0, 0], [100, 100], [100, 0], [0, 100]])
    assert bowtie.area(CANVAS) == pytest.approx(5000)
    assert bowtie.coverage(CANVAS, 1).sum() == pytest.approx(5000, rel=1e-3)
    assert bowtie.coverage(CANVAS, 1)[10, 50] == 0 and bowtie.coverage(CANVAS, 1)[50, 10] == 1


def test_path_with_a_hole_removes_the_hole():
    c = Container.path(HOLED)
    assert c.area(CANVAS) == pytest.approx(600 * 300 - 100 * 100)
    cov = c.coverage(CANVAS, 2)
    assert cov.sum() / 4 == pytest.approx(170_000, rel=1e-4)
    assert cov[500, 500] == 0 and cov[300, 300] == 1
    assert c.svg_path(CANVAS) == HOLED


def test_path_curves_are_flattened_finely():
    circle = Container.path("M 300 250 A 100 100 0 1 0 500 250 A 100 100 0 1 0 300 250 Z")
    assert circle.area(CANVAS) == pytest.approx(math.pi * 100 ** 2, rel=2e-4)
    blob = Container.path("M 100 250 C 100 50 700 50 700 250 C 700 450 100 450 100 250 Z")
    assert blob.coverage(CANVAS, 1).sum() == pytest.approx(blob.area(CANVAS), rel=1e-4)


def test_path_relative_moveto_and_open_subpaths():
    two = Container.path("M 0 0 L 10 0 L 10 10 Z m 20 0 l 10 0 l 0 10 z")
    assert two.area(CANVAS) == pytest.approx(100)
    # each subpath closes on its own start, even when the next one starts at its end
    assert Container.path("M0 0 L10 0 L10 10 M10 10 L0 10 L0 20").area(CANVAS) == pytest.approx(100)


def test_image_dark_pixels_are_inside_a_white_image():
    c = Container.image(white_with_black_block())
    scale = (800 / 120) * (500 / 100)
    assert c.area(CANVAS) == pytest.approx(40 * 60 * scale)
    assert c.bbox(CANVAS) == pytest.approx((200, 100, 400, 200))
    assert c.coverage(CANVAS, 1.37).sum() / 1.37 ** 2 == pytest.approx(40 * 60 * scale, rel=1e-4)
    assert c.svg_path(CANVAS) is None


def test_image_opaque_pixels_are_inside_when_there_is_transparency():
    rgba = np.zeros((50, 50, 4), np.uint8)
    rgba[10:20, 10:40] = [255, 255, 255, 255]     # a white shape: opaque wins over light
    c = Container.image(rgba, box=(0, 0, 50, 50))
    assert c.area(CANVAS) == 300 and c.bbox(CANVAS) == (10, 10, 30, 10)


def _ring_png(tmp_path, name, ink, paper, *, alpha_paper=255, faint=0, fmt="PNG", aa=False):
    """A 200 x 160 picture of a thick ring (outer radius 60, inner 30) in colour ``ink``
    on ``paper`` with alpha ``alpha_paper``; ``faint`` random pixels get alpha 200..250;
    ``aa`` draws it at 4x and shrinks it (antialiased edges). Returns (path, true mask)."""
    from PIL import ImageDraw
    k = 4 if aa else 1
    img = Image.new("RGBA", (200 * k, 160 * k), (*paper, alpha_paper))
    draw = ImageDraw.Draw(img)
    draw.ellipse([40 * k, 20 * k, 160 * k, 140 * k], fill=(*ink, 255))
    draw.ellipse([70 * k, 50 * k, 130 * k, 110 * k], fill=(*paper, alpha_paper))
    if aa:
        img = img.resize((200, 160), Image.Resampling.LANCZOS)
    rgba = np.asarray(img).copy()
    rng = np.random.default_rng(0)
    idx = rng.choice(rgba.shape[0] * rgba.shape[1], faint, replace=False)
    rgba.reshape(-1, 4)[idx, 3] = rng.integers(200, 251, faint)
    yy, xx = np.mgrid[:160, :200] + 0.5
    r = np.hypot(xx - 100, yy - 80)
    truth = (r <= 60) & (r >= 30)
    path = tmp_path / f"{name}.{fmt.lower()}"
    if fmt == "PNG16":   # 16 bits of grey a sample (scientific and print tools)
        Image.fromarray(rgba[..., 0].astype(np.uint16) * 257).save(path, format="PNG")
        return path, truth
    out = Image.fromarray(rgba)
    (out.convert("RGB") if fmt == "JPEG" else out).save(path, format=fmt)
    return path, truth


@pytest.mark.parametrize("variant", ["black_on_white", "black_on_white_alpha_faint",
                                     "coloured_on_transparent", "white_on_black_invert",
                                     "antialiased", "jpeg", "grey_16_bit"])
def test_image_is_read_as_a_person_sees_it(tmp_path, variant):
    black, white, gold = (0, 0, 0), (255, 255, 255), (240, 200, 40)
    kw = {"black_on_white": dict(ink=black, paper=white),
          # 0.4% of the pixels slightly transparent, as antialiased corners of real PNGs
          "black_on_white_alpha_faint": dict(ink=black, paper=white, faint=128),
          "coloured_on_transparent": dict(ink=gold, paper=white, alpha_paper=0),
          "white_on_black_invert": dict(ink=white, paper=black),
          "antialiased": dict(ink=black, paper=white, aa=True, faint=64),
          "jpeg": dict(ink=black, paper=white, fmt="JPEG"),
          # dark grey on light grey: 8,995 and 60,395 of 65,535
          "grey_16_bit": dict(ink=(35, 35, 35), paper=(235, 235, 235), fmt="PNG16")}[variant]
    path, truth = _ring_png(tmp_path, variant, **kw)
    c = Container.image(path, invert=variant == "white_on_black_invert")
    mask = np.asarray(c.preview()) == 0
    assert np.mean(mask != truth) < 0.01, variant
    assert c.inside_share() == pytest.approx(truth.mean(), abs=0.01)


def test_implausible_inside_warns_naming_invert_and_threshold():
    img = np.zeros((50, 50, 3), np.uint8)                 # all dark: all inside
    with pytest.warns(UserWarning, match=r"covers 100.00%.*invert=True.*threshold="):
        Container.image(img)
    img = np.full((100, 100, 3), 255, np.uint8)
    img[0, 0] = 0                                        # 0.01% inside
    with pytest.warns(UserWarning, match=r"covers 0.01%.*invert=True.*threshold="):
        Container.image(img)


def test_container_shows_what_was_read():
    c = Container.image(white_with_black_block())
    png = Image.open(io.BytesIO(c._repr_png_()))
    assert png.size == (120, 100) and np.asarray(png)[40, 60] == 0 and np.asarray(png)[5, 5] == 255
    assert Container.rect(0, 0, 400, 250).inside_share(CANVAS) == pytest.approx(0.25)
    assert Container.rect(0, 0, 400, 250).preview(CANVAS).size == (400, 250)
    with pytest.raises(ValueError, match="canvas_size"):
        Container.canvas().inside_share()


def test_image_threshold_box_and_invert():
    img = np.full((10, 10, 3), 255, np.uint8)
    img[:5] = 100                                   # luminance ~0.39
    assert Container.image(img, threshold=0.5, box=(0, 0, 10, 10)).area(CANVAS) == 50
    with pytest.raises(ValueError, match="no pixel is inside"):
        Container.image(img, threshold=0.3)
    boxed = Container.image(img, box=(100, 200, 40, 20))
    assert boxed.bbox(CANVAS) == (100, 200, 40, 10)
    inverted = Container.image(img, box=(100, 200, 40, 20), invert=True)
    assert inverted.bbox(CANVAS) == (100, 210, 40, 10) and inverted.area(CANVAS) == 400


def test_image_sources_file_data_url_pil_and_bool_mask(tmp_path):
    pil = Image.fromarray(white_with_black_block())
    pil.save(tmp_path / "mask.png")
    expected = Container.image(white_with_black_block())
    assert Container.image(str(tmp_path / "mask.png")) == expected
    assert Container.image(image_data_url(pil)) == expected
    assert Container.image(pil) == expected
    mask = np.zeros((100, 120), bool)
    mask[20:60, 30:90] = True
    assert Container.image(mask) == expected


def test_magic_wand_selects_the_painted_region_not_its_neighbour():
    bg = np.full((50, 80, 3), 240, np.uint8)
    bg[10:30, 5:35] = [200, 30, 30]
    bg[10:30, 35:70] = [30, 30, 200]
    red = Container.from_background(bg, (200, 200), canvas_size=CANVAS)  # 10 canvas px per image px
    assert red.kind == "image"
    assert red.bbox(CANVAS) == (50, 100, 300, 200) and red.area(CANVAS) == 60_000
    native = Container.from_background(bg, (20, 20))                      # image px = canvas px
    assert native.bbox(CANVAS) == (5, 10, 30, 20)
    boxed = Container.from_background(bg, (150, 120), box=(100, 100, 80, 50))
    assert boxed.bbox(CANVAS) == (135, 110, 35, 20)
    with pytest.warns(UserWarning, match="tolerance="):
        everything = Container.from_background(bg, (20, 20), tolerance=1.0)
    assert everything.area(CANVAS) == 80 * 50


def test_magic_wand_is_4_connected():
    bg = np.full((20, 20, 3), 255, np.uint8)
    bg[5:10, 5:10] = 0
    bg[10:15, 10:15] = 0                       # touches the first block only at a corner
    c = Container.from_background(bg, (7, 7))
    assert c.area((20, 20)) == 25


def test_cut_removes_about_the_stroke_area_and_accumulates():
    rect = Container.rect(100, 100, 400, 300)
    once = rect.cut([[50, 250], [550, 250]], 20)
    assert rect.area(CANVAS) - once.area(CANVAS) == pytest.approx(400 * 20, rel=0.01)
    twice = once.cut([[300, 50], [300, 450]], 10)
    assert rect.area(CANVAS) - twice.area(CANVAS) == pytest.approx(8000 + 3000 - 200, rel=0.01)
    assert rect.area(CANVAS) == 120_000 and len(twice.to_json()["cuts"]) == 2
    assert twice.coverage(CANVAS, 1)[250, 200] == 0 and twice.svg_path(CANVAS) is None


def test_a_one_point_cut_removes_a_disc():
    e = Container.ellipse(400, 250, 200, 150)
    dotted = e.cut([[400, 250]], 40)
    assert e.area(CANVAS) - dotted.area(CANVAS) == pytest.approx(math.pi * 20 ** 2, rel=0.01)


def test_cut_through_the_edge_shrinks_the_bbox_and_works_on_images():
    cut = Container.rect(100, 100, 200, 200).cut([[0, 100], [400, 100]], 100)
    assert cut.bbox(CANVAS) == pytest.approx((100, 150, 200, 150), abs=0.1)
    img = Container.image(white_with_black_block())
    stripe = img.cut([[0, 250], [800, 250]], 10)
    assert img.area(CANVAS) - stripe.area(CANVAS) == pytest.approx(400 * 10, rel=0.01)


@pytest.mark.parametrize("container", [
    Container.canvas(), Container.rect(40, 60, 300, 380), Container.ellipse(400, 250, 200, 150),
    Container.polygon(TRIANGLE), Container.path(HOLED),
    Container.image(white_with_black_block(), box=(10, 20, 300, 200)),
    Container.ellipse(400, 250, 200, 150).cut([[300, 250], [500, 250]], 12).cut([[1, 1]], 3),
    Container.image(white_with_black_block(), threshold=0.8).cut([[0, 0], [800, 500]], 30),
])
def test_json_round_trip(container):
    d = container.to_json()
    assert d["kind"] == container.kind and isinstance(d["cuts"], list)
    back = Container.from_json(d)
    assert back == container
    assert back.area(CANVAS) == pytest.approx(container.area(CANVAS))


def test_json_matches_the_protocol():
    assert Container.ellipse(400, 250, 200, 150).cut([[0, 0], [5, 5]], 12).to_json() == {
        "kind": "ellipse", "cx": 400, "cy": 250, "rx": 200, "ry": 150,
        "cuts": [{"points": [[0, 0], [5, 5]], "width": 12}]}
    d = Container.image(white_with_black_block()).to_json()
    assert d["image"].startswith("data:image/png;base64,") and d["box"] is None


def test_from_json_applies_the_threshold_to_an_uploaded_image():
    gray = Image.fromarray(np.full((10, 10, 3), 100, np.uint8))
    d = {"kind": "image", "image": image_data_url(gray), "threshold": 0.5, "box": [0, 0, 10, 10]}
    with pytest.warns(UserWarning, match="invert="):
        assert Container.from_json(d).area(CANVAS) == 100
    with pytest.raises(ValueError, match="no pixel is inside"):
        Container.from_json({**d, "threshold": 0.2})


@pytest.mark.parametrize("build, message", [
    (lambda: Container.rect(0, 0, 0, 5), r"Container.rect: w must be > 0, got 0"),
    (lambda: Container.rect(0, 0, 5, -2), r"Container.rect: h must be > 0, got -2"),
    (lambda: Container.ellipse(0, 0, 3, 0), r"Container.ellipse: ry must be > 0, got 0"),
    (lambda: Container.rect(float("nan"), 0, 1, 1), r"Container.rect: x must be finite, got nan"),
    (lambda: Container.ellipse(0, float("inf"), 1, 1), r"cy must be finite, got inf"),
    (lambda: Container.polygon([[0, 0], [1, 1]]), r"points must be a \(k, 2\) array with k >= 3, got shape \(2, 2\)"),
    (lambda: Container.polygon([[0, 0], [1, 1], [2, 2]]), r"Container.polygon: the shape of points has zero area"),
    (lambda: Container.polygon([[0, 0], [1, float("nan")], [2, 0]]), r"points must be finite, got nan"),
    (lambda: Container.polygon([[0, 0], [1e12, 0], [0, 1]]), r"points must lie within"),
    (lambda: Container.path("hello"), r"Container.path: d is not valid SVG path data"),
    (lambda: Container.path("M 0 0 L 10"), r"Container.path: d is not valid SVG path data"),
    (lambda: Container.path(""), r"Container.path: d is empty"),
    (lambda: Container.path("M 0 0 L 10 10"), r"Container.path: the shape of d has zero area"),
    (lambda: Container.image(np.full((100, 120, 3), 255, np.uint8)),
     r"Container.image: no pixel is inside \(all 12000 pixels are lighter than threshold 0.5\); "
     r"use invert=True or a higher threshold"),
    (lambda: Container.image(np.zeros((4, 4, 4), np.uint8)), r"all 16 pixels are transparent"),
    (lambda: Container.image(np.zeros((4, 4), bool)), r"no pixel is inside"),
    (lambda: Container.image(white_with_black_block(), threshold=0), r"threshold must be in \(0, 1\], got 0"),
    (lambda: Container.image(white_with_black_block(), box=(0, 0, 10)), r"box must be None or \(x, y, w, h\)"),
    (lambda: Container.image(white_with_black_block(), box=(0, 0, 10, 0)), r"box h must be > 0, got 0"),
    (lambda: Container.from_background(white_with_black_block(), (500, 10)),
     r"point \(500, 10\) is outside the image, which covers x 0..120, y 0..100"),
    (lambda: Container.from_background(white_with_black_block(), (5, 5), tolerance=-0.1),
     r"tolerance must be in \[0, 1\]"),
    (lambda: Container.rect(0, 0, 5, 5).cut([[0, 0]], 0), r"Container.cut: width must be > 0, got 0"),
    (lambda: Container.rect(0, 0, 5, 5).cut([], 3), r"Container.cut: points must be a \(k, 2\) array"),
    (lambda: Container.from_json({"kind": "blob"}),
     r"unknown container kind 'blob'; valid kinds are 'canvas', 'rect', 'ellipse', 'polygon', 'path', 'image'"),
    (lambda: Container.from_json({"kind": "rect", "x": 1, "y": 2}), r"needs x, y, w, h; missing w, h"),
    (lambda: Container.rect(0, 0, 5, 5).coverage((800, 0), 1), r"canvas height must be > 0, got 0"),
    (lambda: Container.rect(0, 0, 5, 5).coverage(CANVAS, -1), r"rho must be > 0, got -1"),
])
def test_errors_name_the_argument_and_value(build, message):
    with pytest.raises(ValueError, match=message):
        build()


class FakeIpyCanvas:
    """The part of ipycanvas.Canvas that Container.from_ipycanvas uses."""

    def __init__(self, rgba):
        self.height, self.width = (0, 0) if rgba is None else rgba.shape[:2]
        self._rgba = rgba

    def get_image_data(self):
        if self._rgba is None:
            raise RuntimeError("No image data, please be sure that ``sync_image_data`` is set to True")
        return self._rgba


def test_from_ipycanvas_reads_the_drawing():
    rgba = np.zeros((30, 40, 4), np.uint8)
    rgba[5:15, 10:30] = [20, 120, 200, 255]
    c = Container.from_ipycanvas(FakeIpyCanvas(rgba))
    assert c.kind == "image" and c.bbox(CANVAS) == (10, 5, 20, 10) and c.area(CANVAS) == 200


def test_from_ipycanvas_without_image_data_says_how_to_fix_it():
    with pytest.raises(ValueError, match="sync_image_data=True"):
        Container.from_ipycanvas(FakeIpyCanvas(None))


def test_from_ipycanvas_with_a_real_canvas():
    ipycanvas = pytest.importorskip("ipycanvas")
    try:
        canvas = ipycanvas.Canvas(width=40, height=30, sync_image_data=True)
    except Exception as exc:  # pragma: no cover - depends on the widget stack
        pytest.skip(f"ipycanvas.Canvas cannot be built without a front end: {exc}")
    with pytest.raises(ValueError, match="sync_image_data=True"):
        Container.from_ipycanvas(canvas)
    rgba = np.zeros((30, 40, 4), np.uint8)
    rgba[5:15, 10:30] = [0, 0, 0, 255]
    png = io.BytesIO()
    Image.fromarray(rgba).save(png, "PNG")
    canvas.set_trait("image_data", png.getvalue())   # what the front end syncs back
    assert Container.from_ipycanvas(canvas).bbox((80, 60)) == (10, 5, 20, 10)


coordinate = st.one_of(st.floats(-60, 260, allow_nan=False), st.integers(-2, 6).map(float))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(coordinate, coordinate), min_size=3, max_size=9))
def test_random_polygons_build_or_raise_value_error(points):
    try:
        c = Container.polygon(points)
    except ValueError as exc:
        assert "zero area" in str(exc)
        return
    size = (200, 100)
    area = c.area(size)
    assert math.isfinite(area) and area >= 0
    assert evenodd_area([np.asarray(points, float)]) > 0
    for rho in (1, 0.7):
        cov = c.coverage(size, rho)
        assert cov.shape == (math.ceil(100 * rho), math.ceil(200 * rho))
        assert np.isfinite(cov).all() and cov.min() >= 0 and cov.max() <= 1
    # sampling error: at most a 1/16-px row band per unit of horizontal edge travel
    travel = np.abs(np.diff(np.asarray(points + points[:1])[:, 0])).sum()
    assert abs(c.coverage(size, 1).sum() - area) <= travel / 16 + 1e-3
