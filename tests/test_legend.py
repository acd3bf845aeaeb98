"""The export's legend, title, caption and container outlines, read back from the SVG."""
import re
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.output.legend import round_values

SVG = "{http://www.w3.org/2000/svg}"
pytestmark = pytest.mark.usefixtures("one_thread")


@pytest.fixture(scope="module")
def chart():
    rng = np.random.default_rng(1)
    df = pd.DataFrame({"Task": rng.choice(["write", "test", "review & fix"], 40),
                       "Duration": rng.uniform(2, 38, 40), "Year": rng.choice([2024, 2025], 40)})
    c = uw.Chart(df, mark="star", size="Duration", color="Task", by="Year", iterations=30,
                 container=uw.Container.ellipse(400, 250, 300, 200), title="Tasks <2025> & co")
    c.layout()
    return c


def entries(svg, channel):
    root = ET.fromstring(svg)
    return [g for g in root.iter(f"{SVG}g")
            if "legend-entry" in (g.get("class") or "") and g.get("data-channel") == channel]


def scale_of(transform):
    """(sx, sy) of the first scale() in a transform."""
    sx, sy = re.search(r"scale\(([-\d.e]+) ([-\d.e]+)\)", transform).groups()
    return float(sx), float(sy)


def test_colour_entries_are_the_categories_drawn_with_the_layer_mark(chart):
    svg = chart.to_svg()
    found = entries(svg, "color")
    assert [g.get("data-value") for g in found] == sorted(chart.df["Task"].unique())
    colors = dict(zip(chart.df.loc[chart._units.rows, "Task"], chart._units.colors))
    defs = {d.get("id"): d for d in ET.fromstring(svg).iter(f"{SVG}g") if d.get("id")}
    for g in found:
        use = g.find(f"{SVG}use")
        fragment = ET.tostring(defs[use.get("href")[1:]], encoding="unicode")
        assert colors[g.get("data-value")] in fragment          # the category's own colour
        assert g.find(f"{SVG}text").text == g.get("data-value")
    assert "review &amp; fix" in svg


def test_size_legend_is_area_true_against_the_units(chart):
    svg = chart.to_svg()
    root = ET.fromstring(svg)
    bw, bh = chart.layers[0].mark.box_size
    per_value = []   # box area per unit of value, measured from each unit's transform
    for g, value in zip([g for g in root.iter(f"{SVG}g") if g.get("class") == "unit"],
                        chart.df.loc[chart.placements["row"], "Duration"]):
        sx, sy = scale_of(g.get("transform"))
        per_value.append(sx * sy * bw * bh / value)
    sizes = entries(svg, "size")
    assert 2 <= len(sizes) <= 4
    values = [float(g.get("data-value")) for g in sizes]
    lo, hi = chart.df["Duration"].min(), chart.df["Duration"].max()
    assert all(lo <= v <= hi for v in values) and values == sorted(values)
    assert all(v == round(v) for v in values)                   # round numbers
    for g, v in zip(sizes, values):
        sx, sy = scale_of(g.find(f"{SVG}use").get("transform"))
        assert sx * sy * bw * bh / v == pytest.approx(np.median(per_value), rel=0.05)
    titles = [t.text for t in ET.fromstring(svg).iter(f"{SVG}text") if t.get("class") == "legend-title"]
    assert [t for t in titles if t.startswith("Size")] == ["Size: Duration (area)"]  # one, all layers


def test_unit_key_counts_rows_and_names_each_layer(chart):
    svg = chart.to_svg()
    assert "1 mark = 1 row (40 rows)" in svg
    keys = entries(svg, "unit")
    assert [g.get("data-value") for g in keys] == ["2024", "2025"]
    counts = chart.df["Year"].value_counts()
    for g in keys:
        assert g.find(f"{SVG}text").text == \
            f"{g.get('data-value')} (Year): {counts[int(g.get('data-value'))]} rows"


def test_legend_grows_the_svg_beside_the_canvas_and_can_be_left_out(chart):
    def view(svg):
        return [float(v) for v in ET.fromstring(svg).get("viewBox").split()]
    assert view(chart.to_svg(legend=False, title=""))[2:] == [800, 500]
    assert 'class="legend"' not in chart.to_svg(legend=False)
    border = 8   # the quiet border around a page with a legend
    x, y, w, h = view(chart.to_svg(legend="right", title=""))
    assert x == -border and w > 800 + 2 * border
    x, y, w, h = view(chart.to_svg(legend="left", title=""))
    assert x < -border and x + w == pytest.approx(800 + border, abs=0.01)
    x, y, w, h = view(chart.to_svg(legend="bottom", title=""))
    assert y == -border and h > 500 + 2 * border
    x, y, w, h = view(chart.to_svg(legend="top", title=""))
    assert y < 0
    root = ET.fromstring(chart.to_svg(legend=[20, 30], title=""))
    assert root.find(f"{SVG}g[@class='legend']").get("transform") == "translate(20 30)"
    with pytest.raises(ValueError, match="legend must be True, False, None, 'right'.*got 'middle'"):
        chart.to_svg(legend="middle")


def test_default_legend_only_when_a_channel_is_bound():
    c = uw.Chart(pd.DataFrame({"v": [1.0, 2.0, 3.0]}), iterations=20)
    c.layout()
    assert 'class="legend"' not in c.to_svg()
    svg = c.to_svg(legend=True)
    # one layer: the title does not repeat its entry's count
    assert "1 mark = 1 row<" in svg and [g.find(f"{SVG}text").text
                                          for g in entries(svg, "unit")] == ["3 rows"]


def test_title_and_caption_are_escaped_text_and_bounded(chart):
    root = ET.fromstring(chart.to_svg(caption="Each star: one task."))
    title = root.find(f"{SVG}text[@class='title']")
    assert title.text == "Tasks <2025> & co"
    assert float(title.get("x")) == chart.canvas[0] / 2        # centred over the chart
    caption = root.find(f"{SVG}text[@class='caption']")
    assert "".join(caption.itertext()) == "Each star: one task."
    assert float(root.get("viewBox").split()[1]) < 0           # the title sits above the canvas
    assert ET.fromstring(chart.to_svg(title="")).find(f"{SVG}text[@class='title']") is None
    with pytest.raises(ValueError, match="title is 201 characters long; at most 200"):
        chart.to_svg(title="x" * 201)
    with pytest.raises(TypeError, match="caption must be a string or None, got int"):
        uw.Chart(chart.df, caption=3)


def test_title_caption_and_legend_travel_in_the_design(chart):
    d = chart.design()
    assert d["title"] == "Tasks <2025> & co" and d["caption"] is None
    assert d["legend"] == {"visible": True, "position": "right"}
    other = uw.Chart(chart.df)
    other.apply_design({**d, "legend": {"visible": False, "position": [10, 20]}, "caption": "c"})
    assert other.title == d["title"] and other.caption == "c"
    assert other.legend == {"visible": False, "position": [10.0, 20.0]}
    with pytest.raises(ValueError, match="design: legend position must be"):
        other.apply_design({**d, "legend": {"visible": True, "position": "nowhere"}})
    assert other.caption == "c"                                 # a refused design changes nothing


def test_numeric_colour_is_a_bar_with_round_ticks():
    df = pd.DataFrame({"v": np.linspace(3, 97, 30)})
    c = uw.Chart(df, color="v", iterations=20)
    c.layout()
    svg = c.to_svg()
    assert 'class="legend-bar"' in svg and "linearGradient" in svg
    assert [float(g.get("data-value")) for g in entries(svg, "color")] == [25, 50, 75]


def test_outline_draws_each_container_as_a_path(chart):
    assert 'class="container"' not in chart.to_svg()
    root = ET.fromstring(chart.to_svg(outline=True))
    paths = [p for p in root.iter(f"{SVG}path") if p.get("class") == "container"]
    assert len(paths) == 2 and paths[0].get("d").startswith("M100 250A300 200")


def test_outline_of_an_image_mask_is_traced():
    mask = np.zeros((100, 160), bool)
    yy, xx = np.mgrid[:100, :160]
    mask[(xx - 80) ** 2 + (yy - 50) ** 2 < 40 ** 2] = True
    mask[(xx - 80) ** 2 + (yy - 50) ** 2 < 15 ** 2] = False        # a hole
    c = uw.Chart(pd.DataFrame({"v": [1.0] * 10}), iterations=20,
                 container=uw.Container.image(mask, box=(0, 0, 800, 500)),
                 background=np.full((10, 16, 3), 200, np.uint8))
    c.layout()
    root = ET.fromstring(c.to_svg(outline=True))
    assert root.find(f"{SVG}image[@class='background']") is not None   # the background is kept
    d = next(p for p in root.iter(f"{SVG}path") if p.get("class") == "container").get("d")
    rings = [np.array([[float(v) for v in pt.split()] for pt in ring.split("L")])
             for ring in re.findall(r"M([^MZ]+)Z", d)]
    assert len(rings) == 2                                          # outline and hole
    outer = max(rings, key=len)
    radius = np.hypot(outer[:, 0] - 400, (outer[:, 1] - 250) * 800 / 500 * 100 / 160)
    assert np.abs(radius - 200).max() < 8                           # 40 mask px = 200 canvas px


def test_round_values():
    assert round_values(1, 1000) == [250, 500, 750, 1000]
    assert round_values(12, 13.5) == [12, 12.5, 13, 13.5]
    assert 2 <= len(round_values(0.003, 0.0071)) <= 4


def test_a_size_legend_of_big_marks_keeps_to_the_ends_of_the_range():
    c = uw.Chart(pd.DataFrame({"v": [1.0, 2.0, 3.0, 4.0, 1.5, 2.5]}), size="v", iterations=20)
    c.layout()
    svg = c.to_svg()
    assert [float(g.get("data-value")) for g in entries(svg, "size")] == [1, 4]


def test_shape_legend_draws_each_category_with_its_own_mark():
    df = pd.DataFrame({"fruit": ["pear", "apple", "plum"] * 8, "kg": np.linspace(1, 9, 24)})
    c = uw.Chart(df, mark={"apple": "circle", "pear": "triangle", "plum": "star"}, shape="fruit",
                 color="fruit", size="kg", iterations=30)
    c.layout()
    svg = c.to_svg()
    found = entries(svg, "shape")
    assert [g.get("data-value") for g in found] == ["apple", "pear", "plum"]
    defs = {d.get("id"): ET.tostring(d, encoding="unicode")
            for d in ET.fromstring(svg).iter(f"{SVG}g") if d.get("id")}
    drawn = [defs[g.find(f"{SVG}use").get("href")[1:]] for g in found]
    assert len(set(drawn)) == 3                                    # three distinct marks
    colors = dict(zip(df.loc[c._units.rows, "fruit"], c._units.colors))
    for g, fragment in zip(found, drawn):
        assert colors[g.get("data-value")] in fragment               # shape and colour agree
    # the size legend stays area-true when the units draw marks of different shapes
    units = c._units
    silhouette = c.placements["width"] * c.placements["height"] * units.fill_fraction
    per_value = np.median(silhouette / df.loc[c.placements["row"], "kg"].to_numpy())
    for g in entries(svg, "size"):
        sx, sy = scale_of(g.find(f"{SVG}use").get("transform"))
        mark = c.layers[0].mark
        bw, bh = mark.box_size
        area = sx * sy * bw * bh * mark.fill_fraction
        assert area / float(g.get("data-value")) == pytest.approx(per_value, rel=0.05)


def test_colour_of_another_column_is_keyed_with_a_plain_disc_when_a_layer_draws_several_marks():
    df = pd.DataFrame({"fruit": ["pear", "apple"] * 6, "ripe": ["yes", "no", "no"] * 4})
    c = uw.Chart(df, mark=["triangle", "star"], shape="fruit", color="ripe", iterations=20)
    c.layout()
    svg = c.to_svg()
    assert [g.get("data-value") for g in entries(svg, "color")] == ["no", "yes"]
    assert [g.get("data-value") for g in entries(svg, "shape")] == ["apple", "pear"]
    defs = {d.get("id"): ET.tostring(d, encoding="unicode")
            for d in ET.fromstring(svg).iter(f"{SVG}g") if d.get("id")}
    disc = re.search(r' d="([^"]+)"', uw.Mark.shape("circle").svg_fragment("p", "#000")).group(1)
    for g in entries(svg, "color"):
        fragment = defs[g.find(f"{SVG}use").get("href")[1:]]
        assert f' d="{disc}"' in fragment                              # drawn as the disc


def colour_section(svg):
    """(the colour section's ``(value, label)`` entries, its bar's ``<rect>``)."""
    root = ET.fromstring(svg)
    found = [(g.get("data-value"), "".join(g.find(f"{SVG}text").itertext()))
             for g in root.iter(f"{SVG}g") if (g.get("class") or "") == "legend-entry"
             and g.get("data-channel") == "color"]
    return found, root.find(f".//{SVG}rect[@class='legend-bar']")


def test_a_numeric_colour_with_missing_values_gets_a_grey_swatch_last_and_one_warning():
    df = pd.DataFrame({"hp": [50.0, np.nan, 120.0, 90.0, np.nan, 200.0] * 5})
    with pytest.warns(UserWarning) as caught:
        w = uw.UnitoPia(df, mark="circle", color="hp", iterations=20)
    assert [str(x.message) for x in caught] == [
        "color='hp': 10 of 30 rows are missing; they are drawn as the category 'missing' in grey"]
    with pytest.warns(UserWarning) as caught:
        w.run(wait=True)
    assert len([x for x in caught if "missing" in str(x.message)]) == 1   # once per call
    found, bar = colour_section(w.to_svg())
    assert bar is not None and found[-1] == ("missing", "missing")
    swatch = ET.fromstring(w.to_svg()).find(f".//{SVG}g[@data-value='missing']")
    assert swatch.find(f"{SVG}use") is not None   # a swatch, drawn after the bar's ticks


def test_date_ticks_are_labelled_at_their_step_and_never_touch():
    from unitopia_widget.output.legend import date_ticks, spaced_ticks
    from unitopia_widget.output.text import text_width
    years = pd.Series(pd.to_datetime([f"{y}-01-01" for y in range(1970, 1983)]))
    df = pd.DataFrame({"Year": years})
    c = uw.Chart(df, mark="circle", color="Year", iterations=20)
    c.layout()
    found, _ = colour_section(c.to_svg())
    assert [label for _, label in found] == ["1970", "1975", "1980"]
    seconds = lambda s: pd.Timestamp(s).value / 1e9   # noqa: E731
    assert [lab for _, lab in date_ticks(seconds("2024-01-01"), seconds("2024-09-01"))] == \
        ["Jan 2024", "Apr 2024", "Jul 2024"]
    ticks = spaced_ticks(seconds("2024-01-01"), seconds("2024-01-20"), True, 160)
    assert [lab for _, lab in ticks] == ["4 Jan 2024", "18 Jan 2024"]
    (t1, l1), (t2, l2) = ticks
    gap = (t2 - t1) / (seconds("2024-01-20") - seconds("2024-01-01")) * 160
    assert gap >= (text_width(l1) + text_width(l2)) / 2   # apart, not touching


def test_no_colour_bar_label_is_clipped_at_the_page_edge():
    from unitopia_widget.output.text import text_width
    df = pd.DataFrame({"Year": pd.to_datetime([f"{y}-01-01" for y in range(1970, 1983)])})
    c = uw.Chart(df, mark="circle", color="Year", iterations=20)
    c.layout()
    for legend in ("bottom", "left", "top"):
        root = ET.fromstring(c.to_svg(legend=legend))
        vx = float(root.get("viewBox").split()[0])
        block = root.find(f".//{SVG}g[@class='legend']")
        dx = float(re.search(r"translate\(([-\d.]+)", block.get("transform")).group(1))
        first = block.find(f".//{SVG}g[@class='legend-entry']/{SVG}text")
        left = dx + float(first.get("x")) - text_width(first.text) / 2
        assert left >= vx, (legend, left, vx)


def test_the_caption_stands_under_the_chart_and_a_bottom_legend_under_it(chart):
    root = ET.fromstring(chart.to_svg(legend="bottom", caption="One star per task."))
    caption = root.find(f"{SVG}text[@class='caption']")
    block = root.find(f".//{SVG}g[@class='legend']")
    top = float(re.search(r"translate\([-\d.]+ ([-\d.]+)", block.get("transform")).group(1))
    assert 500 < float(caption.get("y")) < 500 + 16   # right under the 500 px canvas
    assert top > float(caption.get("y")) + 12          # the legend below the caption's line
