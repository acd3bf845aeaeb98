"""Tests for unitopia_widget.output.export: SVG structure, recolouring, PNG, and the exported layout's
quality measured independently from the SVG itself."""
import io
import math
import re
import xml.etree.ElementTree as ET
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from PIL import Image
from svgpathtools import parse_path

import unitopia_widget as uw
from unitopia_widget.design.encodings import CATEGORICAL
from unitopia_widget.chart import MAX_UNITS
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.output.export import png_array, to_svg

NS = {"svg": "http://www.w3.org/2000/svg"}
SVG = "{http://www.w3.org/2000/svg}"
XLINK_HREF = "{http://www.w3.org/1999/xlink}href"


pytestmark = pytest.mark.usefixtures("one_thread")


@pytest.fixture(scope="module")
def small_chart():
    df = pd.DataFrame({"Duration": [1.0, 2.5, 4.0, 1.5, 3.0],
                       "Task": ["write", "test", "write", "review", "test & fix"]},
                      index=["t1", "t2", "t3", 40, "t<5>"])
    chart = uw.Chart(df, mark="star", size="Duration", color="Task", iterations=30,
                     background=np.full((10, 16, 3), 200, np.uint8))
    chart.add_layer("extra", data=df.iloc[:2], mark="circle", color="tomato",
                    container=uw.Container.rect(0, 0, 300, 200))
    chart.layout()
    return chart


def parse(svg_text):
    return ET.fromstring(svg_text)


def href(el):
    return el.get("href") or el.get(XLINK_HREF)


# --- structure ----------------------------------------------------------------------

def test_root_size_and_view_box(small_chart):
    root = parse(small_chart.to_svg(legend=False))   # the legend grows the SVG (test_legend.py)
    assert root.tag == f"{SVG}svg"
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("800", "500", "0 0 800 500")


def test_one_unit_group_per_row_with_its_index_label_and_layer(small_chart):
    root = parse(small_chart.to_svg())
    units = [g for g in root.iter(f"{SVG}g") if g.get("class") == "unit"]
    table = small_chart.placements
    assert len(units) == len(table) == 7
    assert [g.get("data-row") for g in units] == [str(r) for r in table["row"]]
    assert [g.get("data-row") for g in units][:5] == ["t1", "t2", "t3", "40", "t<5>"]
    assert [g.get("data-layer") for g in units] == ["layer-1"] * 5 + ["extra"] * 2
    for g in units:
        assert g.get("transform")
        assert list(g) and all(child.tag in (f"{SVG}title", f"{SVG}use") for child in g)


def test_each_unit_has_a_title_with_its_row_values(small_chart):
    root = parse(small_chart.to_svg())
    units = [g for g in root.iter(f"{SVG}g") if g.get("class") == "unit"]
    df = small_chart.df
    for g, row in zip(units, small_chart.placements["row"]):
        title = g.find("svg:title", NS).text
        assert title == f"Duration: {df.loc[row, 'Duration']}\nTask: {df.loc[row, 'Task']}"
    assert units[4].find("svg:title", NS).text.endswith("Task: test & fix")   # escaped, parsed back


def test_every_use_resolves_to_a_definition(small_chart):
    root = parse(small_chart.to_svg(legend=False))   # the legend's own uses: test_legend.py
    defs = root.find("svg:defs", NS)
    ids = {el.get("id"): el for el in defs.iter() if el.get("id")}
    uses = [u for u in root.iter(f"{SVG}use")]
    assert len(uses) == 7
    for u in uses:
        ref = href(u)
        assert ref.startswith("#") and ref[1:] in ids
        assert ids[ref[1:]].find(".//svg:path", NS) is not None     # the vector content
    # one definition per (layer mark, colour): 4 task colours for stars, 1 tomato circle
    assert len([c for c in defs if c.tag == f"{SVG}g"]) == 5


def test_background_is_an_image_with_class_background(small_chart):
    root = parse(small_chart.to_svg())
    assert root[0].tag == f"{SVG}image" and root[0].get("class") == "background"
    assert href(root[0]).startswith("data:image/png;base64,")
    assert (root[0].get("width"), root[0].get("height")) == ("800", "500")


def test_no_background_element_without_a_background():
    chart = uw.Chart(pd.DataFrame({"v": [1.0, 2.0]}), size="v", iterations=20)
    chart.layout()
    root = parse(chart.to_svg())
    assert not [el for el in root.iter() if el.get("class") == "background"]


def test_recolouring_is_visible_in_the_defs(small_chart):
    root = parse(small_chart.to_svg())
    defs = root.find("svg:defs", NS)
    fills = {}
    for g in defs:
        colours = {p.get("fill") for p in g.iter(f"{SVG}path")}
        assert len(colours) == 1
        fills[g.get("id")] = colours.pop().lower()
    palette = {"review": CATEGORICAL[0], "test": CATEGORICAL[1], "test & fix": CATEGORICAL[2],
               "write": CATEGORICAL[3]}
    units = [g for g in root.iter(f"{SVG}g") if g.get("class") == "unit"]
    df = small_chart.df
    for g, row in zip(units[:5], small_chart.placements["row"][:5]):
        assert fills[href(g.find("svg:use", NS))[1:]] == palette[df.loc[row, "Task"]]
    for g in units[5:]:
        assert fills[href(g.find("svg:use", NS))[1:]] == "#ff6347"          # tomato


def test_svg_before_layout_is_a_clear_error():
    with pytest.raises(RuntimeError, match=r"no layout yet"):
        uw.Chart(pd.DataFrame({"v": [1.0]})).to_svg()


def test_save_svg_writes_the_same_text(small_chart, tmp_path):
    small_chart.save(tmp_path / "c.svg")
    assert (tmp_path / "c.svg").read_text() == small_chart.to_svg()
    with pytest.raises(ValueError, match=r"unknown file type '.pdf'"):
        small_chart.save(tmp_path / "c.pdf")


def test_png_export_renders_at_twice_the_canvas(small_chart, tmp_path):
    path = tmp_path / "c.png"
    small_chart.save(path, legend=False)
    img = np.asarray(Image.open(path).convert("RGBA"))
    assert img.shape == (1000, 1600, 4)
    # the background is grey 200 everywhere a mark is not; marks add their colours
    assert (img[..., 3] == 255).all()
    differs = np.abs(img[..., :3].astype(int) - 200).sum(-1) > 30
    assert 0.002 < differs.mean() < 0.9
    with pytest.raises(ValueError, match=r"to_png: scale must be a number in \(0, 8\], got 0"):
        small_chart.to_png(0)


# --- the exported layout, measured from the SVG alone ---------------------------------

def matrix(transform: str) -> np.ndarray:
    """3 x 3 matrix of an SVG transform list (translate, rotate, scale, matrix)."""
    out = np.eye(3)
    for name, args in re.findall(r"(\w+)\s*\(([^)]*)\)", transform):
        v = [float(a) for a in re.split(r"[\s,]+", args.strip()) if a]
        m = np.eye(3)
        if name == "translate":
            m[:2, 2] = [v[0], v[1] if len(v) > 1 else 0.0]
        elif name == "scale":
            m[0, 0], m[1, 1] = v[0], v[1] if len(v) > 1 else v[0]
        elif name == "rotate":
            a = math.radians(v[0])
            m[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
            if len(v) == 3:
                m = matrix(f"translate({v[1]} {v[2]})") @ m @ matrix(f"translate({-v[1]} {-v[2]})")
        elif name == "matrix":
            m[:2, :] = [[v[0], v[2], v[4]], [v[1], v[3], v[5]]]
        else:
            raise AssertionError(f"unexpected transform {name}")
        out = out @ m
    return out


def viewport(el) -> np.ndarray:
    """Matrix of a nested <svg x y width height viewBox preserveAspectRatio="none">."""
    x, y = float(el.get("x", 0)), float(el.get("y", 0))
    w, h = float(el.get("width")), float(el.get("height"))
    vx, vy, vw, vh = (float(t) for t in re.split(r"[\s,]+", el.get("viewBox").strip()))
    assert el.get("preserveAspectRatio") == "none"
    return matrix(f"translate({x} {y}) scale({w / vw} {h / vh}) translate({-vx} {-vy})")


def outlines(svg_text: str) -> list[np.ndarray]:
    """Per unit, the canvas-space polygon(s) of its mark, from the SVG text only."""
    root = parse(svg_text)
    defs = {el.get("id"): el for el in root.find("svg:defs", NS).iter() if el.get("id")}
    shapes = []
    for g in root.iter(f"{SVG}g"):
        if g.get("class") != "unit":
            continue
        unit = matrix(g.get("transform"))
        definition = defs[href(g.find("svg:use", NS))[1:]]
        polys = []

        def walk(el, m):
            if el.tag == f"{SVG}svg":
                m = m @ viewport(el)
            if el.get("transform"):
                m = m @ matrix(el.get("transform"))
            if el.tag == f"{SVG}path":
                pts = []
                for seg in parse_path(el.get("d")):      # vertices of lines, samples of curves
                    steps = 1 if type(seg).__name__ == "Line" else 32
                    pts += [seg.point(t) for t in np.arange(steps) / steps]
                pts = np.array(pts)
                xy = np.stack([pts.real, pts.imag, np.ones(len(pts))])
                polys.append((m @ xy)[:2].T)
            for child in el:
                walk(child, m)

        walk(definition, unit)
        shapes.append(polys)
    return shapes


def inside_polygon(px, py, poly) -> np.ndarray:
    """Even-odd point-in-polygon test of points (px, py) against a closed polygon (k, 2)."""
    inside = np.zeros(px.shape, dtype=bool)
    x0, y0 = poly[:, 0], poly[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    for a, b, c, d in zip(x0, y0, x1, y1):
        if b == d:
            continue
        cross = (b > py) != (d > py)
        xs = a + (py - b) * (c - a) / (d - b)
        inside ^= cross & (px < xs)
    return inside


def rasterise(shapes, canvas, scale=2, sub=4, ellipse=None):
    """Coverage ``(H, W)`` at ``scale`` px per canvas px, ``sub x sub`` samples a pixel, and the
    summed alpha of the marks outside ``ellipse = (cx, cy, rx, ry)``, in canvas px^2."""
    w, h = int(canvas[0] * scale), int(canvas[1] * scale)
    coverage = np.zeros((h, w))
    outside = 0.0
    offsets = (np.arange(sub) + 0.5) / sub
    for polys in shapes:
        pts = np.concatenate(polys)
        x0, y0 = np.floor(pts.min(0) * scale).astype(int)
        x1, y1 = np.ceil(pts.max(0) * scale).astype(int)
        x0, y0, x1, y1 = max(x0, 0), max(y0, 0), min(x1, w), min(y1, h)
        sx = ((np.arange(x0, x1)[:, None] + offsets[None]).reshape(-1)) / scale
        sy = ((np.arange(y0, y1)[:, None] + offsets[None]).reshape(-1)) / scale
        px, py = np.meshgrid(sx, sy)
        hit = np.zeros(px.shape, dtype=bool)
        for poly in polys:
            hit ^= inside_polygon(px, py, poly)
        alpha = hit.reshape(y1 - y0, sub, x1 - x0, sub).mean(axis=(1, 3))
        coverage[y0:y1, x0:x1] += alpha
        if ellipse is not None:
            cx, cy, rx, ry = ellipse
            out = ((px - cx) / rx) ** 2 + ((py - cy) / ry) ** 2 > 1
            outside += (hit & out).sum() / (sub * scale) ** 2
    return coverage, outside


@pytest.fixture(scope="module")
def stars_in_an_ellipse():
    df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1, 3, 100)})
    chart = uw.Chart(df, mark="star", size="v", container=uw.Container.ellipse(400, 250, 300, 200))
    chart.layout()
    return chart, chart.to_svg(legend=False)


def test_exported_layout_has_little_overlap_and_stays_inside(stars_in_an_ellipse):
    chart, svg = stars_in_an_ellipse
    shapes = outlines(svg)
    assert len(shapes) == 100
    coverage, outside = rasterise(shapes, chart.canvas, ellipse=(400, 250, 300, 200))
    mark_area = coverage.sum() / 4                              # canvas px^2 at 2x
    overlap = np.maximum(coverage - 1, 0).sum() / 4 / mark_area
    print(f"100 stars in an ellipse, from the SVG: overlap {100 * overlap:.3f}% and outside "
          f"{100 * outside / mark_area:.3f}% of the mark area, {chart.result.iterations} iterations")
    assert overlap < 0.01
    assert outside / mark_area < 0.005
    # the exported stars keep their data: silhouette areas proportional to the values
    areas = np.array([abs(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])) / 2
                      for p in (s[0] for s in shapes)])                  # shoelace
    ratio = areas / chart.df.loc[chart.placements["row"], "v"].to_numpy()
    np.testing.assert_allclose(ratio, ratio.mean(), rtol=2e-3)
    assert mark_area / (math.pi * 300 * 200) > 0.35               # a closed container is filled


def test_independent_raster_agrees_with_the_png_render(stars_in_an_ellipse):
    # the measure above reads the SVG the way a renderer does: compare with resvg's picture
    chart, svg = stars_in_an_ellipse
    coverage, _ = rasterise(outlines(svg), chart.canvas)
    alpha = png_array(svg, chart.canvas, 2.0)[..., 3] / 255.0
    union = np.minimum(coverage, 1.0)
    assert alpha.shape == union.shape
    assert np.abs(alpha - union).sum() / union.sum() < 0.03
    assert ((alpha > 0.5) & (union > 0.5)).sum() / ((alpha > 0.5) | (union > 0.5)).sum() > 0.97
    # the PNG export composites one sprite per distinct mark: the same picture, but for
    # each mark's size and place rounded to whole px (half a px on 20 to 40 px stars)
    png = np.asarray(Image.open(io.BytesIO(chart.to_png(2.0, legend=False))).convert("RGBA"))
    composed = png[..., 3] / 255.0
    assert composed.shape == union.shape
    assert np.abs(composed - union).sum() / union.sum() < 0.04
    assert abs(composed.sum() / alpha.sum() - 1) < 0.01
    assert ((composed > 0.5) & (union > 0.5)).sum() / ((composed > 0.5) | (union > 0.5)).sum() > 0.97


# --- PNG at the largest supported size ---------------------------------------------------

def dotted_icon(dots: int = 50) -> str:
    """An SVG icon of ``dots`` circles in one group: 51 elements under the root."""
    body = "".join(f'<circle cx="{2 + i % 10 * 2}" cy="{2 + i // 10 * 4}" r="0.8"/>' for i in range(dots))
    return f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 22 22"><g fill="#333">{body}</g></svg>'


def place_on_grid(chart) -> None:
    """Placements of every unit on a grid, turned a little each, as a run would leave
    them (no solve: the export is what is tested)."""
    units = bind(chart.df, chart.layers)
    n, (w, h) = len(units.rows), chart.canvas
    cols = int(np.ceil(np.sqrt(n * w / h)))
    cell, k = w / cols, np.arange(n)
    scale = 0.4 * cell / units.half_w.max()
    result = SimpleNamespace(center=np.stack([(k % cols + 0.5) * cell, (k // cols + 0.5) * cell], 1),
                             angle=(k * 37.0) % 360, unit_scale=np.full(n, scale), scale=scale,
                             cancelled=False)
    chart._units = units
    chart.laid = engine.Layout(placements=engine.placements(units, chart.layers, result), units=units,
                               scale=scale, canvas=chart.canvas, frames=None, result=result)


def test_twenty_thousand_icons_export_a_png_like_the_svg_draws_them(tmp_path):
    # resvg expands each <use> into its own tree: 20,000 x 51 nodes passes its limit, so
    # the units are composited from one rendered sprite per distinct mark
    chart = uw.Chart(pd.DataFrame({"v": np.ones(MAX_UNITS)}), mark=uw.Mark.svg(dotted_icon()),
                     canvas=(800, 500))
    place_on_grid(chart)
    chart.save(tmp_path / "x.png")
    img = np.asarray(Image.open(tmp_path / "x.png").convert("RGBA")).astype(float)
    assert img.shape == (1000, 1600, 4)
    # the first rows of units, drawn by resvg from the SVG, match the composite
    table = chart.placements
    first = table[table.y < 30]
    part = to_svg(chart.canvas, first, chart.layers, chart._units.colors[:len(first)], [""] * len(first))
    truth = png_array(part, chart.canvas, 2.0).astype(float)[:50, :, 3]
    drawn = img[:50, :, 3]
    assert abs(drawn.sum() / truth.sum() - 1) < 0.03
    # and every unit is drawn: ink within 2 px of each centre
    x, y = (np.rint(table[["x", "y"]].to_numpy() * 2).astype(int) + 2).T
    ink = np.pad(img[..., 3], 2).cumsum(0).cumsum(1)   # box sums over 5 x 5 px
    assert (ink[y + 2, x + 2] - ink[y - 3, x + 2] - ink[y + 2, x - 3] + ink[y - 3, x - 3] > 0).all()
