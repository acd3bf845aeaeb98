"""Data conventions of the ecosystem: missing colour values, natural and Categorical order,
many categories, datetime colour scales, the legend's name and its caps."""
import warnings
import xml.etree.ElementTree as ET
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.design.encodings import (CATEGORICAL, MISSING_COLOR, encode, sorted_unique,
                                              warn_small_marks)

SVG = "{http://www.w3.org/2000/svg}"
pytestmark = pytest.mark.usefixtures("one_thread")


def colour_entries(svg):
    return [g for g in ET.fromstring(svg).iter(f"{SVG}g")
            if g.get("data-channel") == "color" and "legend-entry" in (g.get("class") or "")]


def laid_out(df, **kwargs):
    c = uw.Chart(df, iterations=20, container=uw.Container.rect(10, 10, 300, 200), **kwargs)
    c.layout()
    return c


def test_categories_sort_naturally_and_a_categorical_keeps_its_order():
    assert sorted_unique(pd.Series(["cat10", "cat2", "cat1", "cat2"])) == ["cat1", "cat2", "cat10"]
    ordered = pd.Series(pd.Categorical(["low", "high", "mid"], categories=["low", "mid", "high"]))
    assert sorted_unique(ordered) == ["low", "mid", "high"]
    enc = encode(pd.DataFrame({"g": ["cat10", "cat2", "cat1"]}), color="g")
    assert enc.colors == [CATEGORICAL[2], CATEGORICAL[1], CATEGORICAL[0]]


def test_missing_colour_values_are_a_grey_category_listed_last_with_a_warning():
    df = pd.DataFrame({"g": ["B", None, "A", np.nan, "B"]})
    with pytest.warns(UserWarning, match=r"color='g': 2 of 5 rows are missing.*'missing'"):
        c = laid_out(df, mark="circle", color="g")
    colors = dict(zip(c._units.rows, c._units.colors))
    assert colors[1] == colors[3] == MISSING_COLOR
    assert [g.get("data-value") for g in colour_entries(c.to_svg())] == ["A", "B", "missing"]


def test_twenty_categories_are_distinct_and_more_warn_naming_the_repeats():
    assert len(set(CATEGORICAL)) >= 20
    df = pd.DataFrame({"g": [f"k{i}" for i in range(23)]})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        encode(df.iloc[:20], color="g")
    with pytest.warns(UserWarning, match=r"23 categories but 20 distinct.*'k20', 'k21', 'k22'"):
        encode(df, color="g")


def test_the_legend_lists_the_first_categories_and_counts_the_rest():
    df = pd.DataFrame({"g": [f"k{i}" for i in range(60)]})
    with pytest.warns(UserWarning, match="60 categories"):
        c = laid_out(df, mark="circle", color="g")
    svg = c.to_svg()
    assert len(colour_entries(svg)) == 20
    more = [t for t in ET.fromstring(svg).iter(f"{SVG}text") if t.get("class") == "legend-more"]
    assert more[0].text == "\u2026 and 40 more"


def test_a_datetime_colour_is_a_continuous_scale_with_date_labels():
    days = pd.Series(pd.date_range("2024-01-01", periods=20, freq="D"))
    enc = encode(pd.DataFrame({"day": days}), color="day")
    assert enc.colors[0] != enc.colors[10] and len(set(enc.colors)) == 20   # not a cycle of 10
    c = laid_out(pd.DataFrame({"day": days}), mark="circle", color="day")
    labels = [g.find(f"{SVG}text").text for g in colour_entries(c.to_svg())]
    assert labels == ["4 Jan 2024", "18 Jan 2024"]   # days: the most whose labels stay apart
    assert 'class="legend-bar"' in c.to_svg()


def test_shape_with_a_single_mark_is_an_error_that_says_so():
    df = pd.DataFrame({"kind": ["a", "b", "a"]})
    with pytest.raises(ValueError, match=r"shape='kind'.*single mark.*list of marks"):
        uw.Chart(df, mark="circle", shape="kind").layout()


def test_tooltip_picks_and_formats_columns_in_the_svg_and_the_widget():
    df = pd.DataFrame({"Task": ["a", "b"], "Duration": [1.234, 5.0], "Secret": ["x", "y"]})
    for tooltip in (["Task", ("Duration", ".1f")], {"Task": None, "Duration": ".1f"}):
        c = laid_out(df, mark="circle", tooltip=tooltip)
        tips = sorted(t.text for t in ET.fromstring(c.to_svg()).iter(f"{SVG}title"))
        assert tips == ["Task: a\nDuration: 1.2", "Task: b\nDuration: 5.0"]
    w = uw.UnitoPia(df, iterations=20, tooltip="Task")
    w.run(wait=True)
    assert sorted(w.titles) == ["Task: a", "Task: b"]
    w.tooltip = [("Duration", ".2f")]
    assert sorted(w.titles) == ["Duration: 1.23", "Duration: 5.00"]
    with pytest.raises(ValueError, match=r"tooltip='Tsk': no such column"):
        w.tooltip = ["Tsk"]
    with pytest.raises(ValueError, match=r"tooltip: format '\.1f' does not apply to column 'Task'"):
        uw.Chart(df, tooltip=[("Task", ".1f")])


def test_legend_is_one_name_in_the_constructor_the_attribute_and_save(tmp_path):
    df = pd.DataFrame({"g": ["a", "b"]})
    w = uw.UnitoPia(df, color="g", legend="bottom", iterations=20)
    assert w.legend == {"visible": True, "position": "bottom"}
    w.legend = False
    assert w.legend["visible"] is False and w.legend_image == {}
    w.run(wait=True)
    w.save(tmp_path / "x.svg", legend=True)
    assert 'class="legend"' in (tmp_path / "x.svg").read_text()


def test_marks_drawn_under_two_pixels_warn_and_suggest_a_log_scale():
    df = pd.DataFrame({"v": [1.0] * 5 + [30_000.0]})
    with pytest.warns(UserWarning, match=r"5 of 6 marks are drawn under 2 px.*size='v'.*log"):
        laid_out(df, mark="circle", size="v")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        laid_out(pd.DataFrame({"v": [1.0, 3.0, 5.0]}), mark="circle", size="v")


def test_the_small_mark_warning_names_the_spread_of_the_side_that_varies():
    # strands: one width, heights over 200x; the spread is the heights', not the widths' 1x
    table = pd.DataFrame({"width": [1.5] * 3, "height": [3.0, 30.0, 600.0]})
    layer = SimpleNamespace(encodings={"size": None, "width": None, "height": "len"})
    with pytest.warns(UserWarning, match=r"3 of 3 marks .*height='len' spans 200x in extent"):
        warn_small_marks(table, [layer])


def legend_titles(svg):
    return [t.text for t in ET.fromstring(svg).iter(f"{SVG}text") if t.get("class") == "legend-title"]


def test_layers_sharing_a_shape_legend_get_one_and_labels_hold_no_internal_names():
    df = pd.DataFrame({"kind": ["a", "b"] * 4, "site": ["X"] * 4 + ["Y"] * 4})
    c = laid_out(df, mark=["circle", "square"], shape="kind", by="site")
    svg = c.to_svg()
    assert [t for t in legend_titles(svg) if t.startswith("Shape")] == ["Shape: kind"]
    one = laid_out(df, mark="circle", color="kind")
    svg = one.to_svg()
    legend = ET.fromstring(svg).find(f".//{SVG}g[@class='legend']")
    text = " ".join(legend.itertext())
    assert "layer-1" not in text and "Colour" not in text and "Color: kind" in legend_titles(svg)


def test_the_legend_strip_is_as_wide_as_its_text():
    from unitopia_widget.output import legend_draw
    from PIL import ImageFont
    font = ImageFont.truetype("DejaVuSans.ttf", 12)
    for text in ("Duration (hours)", "iiiiiii", "WWW MMM", "cat10: 1,234 rows"):
        assert legend_draw.text_width(text, 12) == pytest.approx(font.getlength(text), rel=0.03)


@pytest.fixture(scope="module")
def sketched():
    """A small chart with a drawn polygon container and a sketched mark, laid out briefly."""
    df = pd.DataFrame({"v": [1.0, 2.0, 3.0, 4.0], "g": ["a", "b", "a", "b"]})
    mark = uw.Mark.sketch([[[0, 0], [10, 12], [20, 0]], [[0, 5], [20, 5]]])
    c = uw.Chart(df, mark=mark, size="v", color="g", iterations=20, seed=3, title="T",
                 container=uw.Container.polygon([[50, 50], [400, 60], [300, 400], [60, 300]]))
    c.layout()
    return df, c


def test_to_code_rebuilds_the_same_design_and_placements(sketched):
    df, c = sketched
    code = c.to_code()
    assert "uw.Chart.from_design(df, design)" in code and "'sketch'" in code
    scope = {"df": df}
    exec(code, scope)
    rebuilt = scope["chart"]
    assert rebuilt.design() == c.design()
    rebuilt.layout()
    pd.testing.assert_frame_equal(rebuilt.placements, c.placements)
    with pytest.raises(ValueError, match="df_name must be a Python identifier"):
        c.to_code("my df")


def test_chart_load_reads_a_saved_design(sketched, tmp_path):
    df, c = sketched
    c.save(tmp_path / "d.json")
    assert uw.Chart.load(tmp_path / "d.json", df).design() == c.design()


def test_the_widget_copies_its_design_as_code(sketched):
    df, c = sketched
    w = uw.UnitoPia.from_design(df, c.design())
    scope = {"df": df}
    exec(w.to_code(), scope)
    assert scope["w"].design == w.design == c.design()
    sent = []
    w.send = sent.append   # the "copy as Python" button asks; the kernel answers with the code
    w._on_message(w, {"type": "code"}, [])
    assert sent == [{"type": "code", "code": w.to_code()}]


SHADED = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 30 10">'
          '<rect width="10" height="10" fill="#1f3f7f"/><rect x="10" width="10" height="10" '
          'fill="#6f8fcf"/><rect x="20" width="10" height="10" fill="#cfdfff"/></svg>')


def test_color_tints_a_shaded_mark_alike_in_the_export_the_widget_and_the_legend():
    import base64
    import re
    df = pd.DataFrame({"g": ["a", "b", "a"]})
    w = uw.UnitoPia(df, mark=uw.Mark.svg(SHADED), color="g", iterations=20)
    w.run(wait=True)
    a = CATEGORICAL[0]
    fills = lambda svg: set(re.findall(r'fill="(#[0-9a-f]{6})"', svg))   # noqa: E731
    tinted = fills(uw.Mark.svg(SHADED).to_svg(a))
    assert len(tinted) == 3 and "#6f8fcf" not in tinted       # three shades of the category's colour
    bitmaps = [base64.b64decode(m["src"].split(",", 1)[1]).decode() for m in w.marks]
    assert any(fills(b) == tinted for b in bitmaps)           # the widget's mark images
    export = w.to_svg()
    body, legend = export.split('<g class="legend"', 1)
    assert tinted <= fills(body) and tinted <= fills(legend)  # the marks and the legend swatch
