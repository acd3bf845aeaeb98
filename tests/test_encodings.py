"""Tests for unitopia_widget.design.encodings: size/width/height factors, colours, order, errors."""
import warnings

import numpy as np
import pandas as pd
import pytest
from PIL import ImageColor

import unitopia_widget as uw
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.design.encodings import (CATEGORICAL, DEFAULT_COLOR, SEQUENTIAL, capped_margin,
                                       encode, palette_for, sequential)


pytestmark = pytest.mark.usefixtures("one_thread")


def luminance(hex_color: str) -> float:
    r, g, b = ImageColor.getrgb(hex_color)[:3]
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def colors_of(chart) -> dict:
    """{row label: colour} of every unit, as bound for layout and export."""
    units = bind(chart.df, chart.layers)
    return dict(zip(units.rows, units.colors))


@pytest.fixture(scope="module")
def tasks():
    return pd.DataFrame({
        "Duration": [1.0, 2.0, 3.5, 0.5, 8.0, 4.0, 2.5, 6.0, 1.5, 3.0, 5.0, 7.0],
        "Task": list("abcabcabcabc"),
        "Year": [2020, 2020, 2020, 2020, 2021, 2021, 2021, 2021, 2022, 2022, 2022, 2022],
        "Kind": ["x", "y", "x", "y", "x", "z", "z", "x", "y", "y", "y", "x"],
        "Width": np.linspace(1, 4, 12),
        "Height": np.linspace(3, 1, 12),
    }, index=[f"r{i}" for i in range(12)])


# --- sizes ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def star_layout(tasks):
    chart = uw.Chart(tasks, mark="star", size="Duration", iterations=40,
                     container=uw.Container.ellipse(400, 250, 220, 180))
    return chart, chart.layout()


def test_size_binds_area_exactly_after_a_real_layout(star_layout, tasks):
    chart, table = star_layout
    assert chart.result.iterations >= 1
    fill = chart.layers[0].mark.fill_fraction
    area = (table["width"] * table["height"] * fill).to_numpy()
    value = tasks.loc[table["row"], "Duration"].to_numpy()
    np.testing.assert_allclose(area / area[0], value / value[0], rtol=1e-6)
    # the star keeps its aspect: one sx = sy scale per mark
    np.testing.assert_allclose(table["sx"], table["sy"], rtol=1e-9)


def test_size_ratios_hold_across_layers_and_marks(tasks):
    # by= with a mark per layer: one global scale, so silhouette areas stay proportional
    # to the values across layers whose marks differ in shape and fill fraction
    chart = uw.Chart(tasks, by="Task", mark={"a": "star", "b": "circle", "c": "heart"},
                     size="Duration", iterations=30)
    table = chart.layout()
    fill = table["layer"].map({layer.name: layer.mark.fill_fraction for layer in chart.layers})
    per_value = (table["width"] * table["height"] * fill).to_numpy() \
        / tasks.loc[table["row"], "Duration"].to_numpy()
    np.testing.assert_allclose(per_value, per_value[0], rtol=1e-6)


def test_width_binds_width_and_keeps_heights(tasks):
    table = uw.Chart(tasks, mark="square", width="Width", iterations=30).layout()
    value = tasks.loc[table["row"], "Width"].to_numpy()
    np.testing.assert_allclose(table["width"] / value, table["width"].iloc[0] / value[0], rtol=1e-6)
    np.testing.assert_allclose(table["height"], table["height"].iloc[0], rtol=1e-9)


def test_height_binds_height_and_keeps_widths(tasks):
    table = uw.Chart(tasks, mark="square", height="Height", iterations=30).layout()
    value = tasks.loc[table["row"], "Height"].to_numpy()
    np.testing.assert_allclose(table["height"] / value, table["height"].iloc[0] / value[0], rtol=1e-6)
    np.testing.assert_allclose(table["width"], table["width"].iloc[0], rtol=1e-9)


def test_width_and_height_together_stretch_both_extents():
    df = pd.DataFrame({"w": [1.0, 2.0, 4.0], "h": [3.0, 1.0, 2.0]})
    enc = encode(df, width="w", height="h")
    np.testing.assert_allclose(enc.width, [3 / 7, 6 / 7, 12 / 7])
    np.testing.assert_allclose(enc.height, [1.5, 0.5, 1.0])
    np.testing.assert_allclose(enc.area, 1.0)


def test_size_factors_have_mean_one():
    enc = encode(pd.DataFrame({"v": [1.0, 3.0, 8.0]}), size="v")
    np.testing.assert_allclose(enc.area, [0.25, 0.75, 2.0])
    np.testing.assert_allclose(enc.width, 1.0)


# --- colours -------------------------------------------------------------------

def test_categorical_palette_in_sorted_order():
    assert palette_for(["b", "a", "c", "a"]) == {"a": CATEGORICAL[0], "b": CATEGORICAL[1],
                                                 "c": CATEGORICAL[2]}
    many = palette_for(range(22))
    assert many[20] == CATEGORICAL[0] and many[21] == CATEGORICAL[1]   # the palette cycles


def test_categorical_colours_agree_across_layers_made_by_by(tasks):
    # layer 2020 has kinds x and y only, 2021 has x and z: z must not take y's colour
    chart = uw.Chart(tasks, by="Year", color="Kind")
    assert [layer.name for layer in chart.layers] == ["2020", "2021", "2022"]
    colors = colors_of(chart)
    expected = {"x": CATEGORICAL[0], "y": CATEGORICAL[1], "z": CATEGORICAL[2]}
    assert colors == {row: expected[k] for row, k in tasks["Kind"].items()}


def test_colour_by_the_layer_column_gives_each_layer_its_palette_colour(tasks):
    chart = uw.Chart(tasks, by="Task", color="Task")
    colors = colors_of(chart)
    assert {colors[r] for r in tasks.index[tasks.Task == "b"]} == {CATEGORICAL[1]}
    assert len(set(colors.values())) == 3


def test_numeric_colour_uses_the_sequential_scale(tasks):
    colors = colors_of(uw.Chart(tasks, color="Duration"))
    order = tasks["Duration"].sort_values().index
    assert colors[order[0]] == SEQUENTIAL[0] and colors[order[-1]] == SEQUENTIAL[-1]
    lum = [luminance(colors[r]) for r in order]
    assert all(a >= b for a, b in zip(lum, lum[1:]))          # light to dark
    assert len(set(colors.values())) == len(set(tasks["Duration"]))


def test_sequential_scale_exact_values():
    out = sequential(np.array([0.0, 1.0, 0.5, np.nan]))
    assert out[0] == SEQUENTIAL[0] and out[1] == SEQUENTIAL[-1]
    a, b = ImageColor.getrgb(SEQUENTIAL[2]), ImageColor.getrgb(SEQUENTIAL[3])
    assert out[2] == "#%02x%02x%02x" % tuple(round((x + y) / 2) for x, y in zip(a, b))
    assert out[3] == "#bab0ac"
    assert sequential(np.array([2.0, 2.0])) == [SEQUENTIAL[0]] * 2    # a constant column


def test_numeric_colour_scale_is_shared_by_the_layers_made_by_by(tasks):
    # the same value must get the same colour in every layer (one scale per column, as
    # the size scale is one per chart); here 2.0, 3.0 and 4.0 appear in different layers
    chart = uw.Chart(tasks, by="Year", color="Duration")
    colors = colors_of(chart)
    whole = dict(zip(tasks.index, sequential(tasks["Duration"].to_numpy())))
    assert colors == whole


@pytest.mark.parametrize("css, hex_color", [("tomato", "#ff6347"), ("#123456", "#123456"),
                                            ("rgb(10, 20, 30)", "#0a141e")])
def test_css_literal_colour_paints_every_unit(tasks, css, hex_color):
    assert set(colors_of(uw.Chart(tasks, color=css)).values()) == {hex_color}


def test_a_column_wins_over_a_css_colour_of_the_same_name():
    df = pd.DataFrame({"red": ["p", "q", "p"]})
    colors = colors_of(uw.Chart(df, color="red"))
    assert list(colors.values()) == [CATEGORICAL[0], CATEGORICAL[1], CATEGORICAL[0]]


def test_no_colour_binding_keeps_the_marks_own_colours(tasks):
    assert set(colors_of(uw.Chart(tasks)).values()) == {None}


def test_an_unbound_colour_leaves_svg_marks_in_their_own_colours():
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
           '<circle cx="5" cy="5" r="5" fill="#e0457b"/></svg>')
    chart = uw.Chart(pd.DataFrame({"v": [1.0, 2.0, 3.0]}), mark=svg, size="v", iterations=20)
    chart.layout()
    exported = chart.to_svg()
    assert "#e0457b" in exported and DEFAULT_COLOR not in exported


def test_an_unbound_colour_draws_shapes_in_the_default_colour(tasks):
    chart = uw.Chart(tasks, mark="circle", iterations=20)
    chart.layout()
    assert DEFAULT_COLOR in chart.to_svg()


# --- order -----------------------------------------------------------------------

def test_order_ranks_follow_the_column_with_stable_ties():
    df = pd.DataFrame({"when": [30, 10, 20, 10, 5]})
    assert encode(df, order="when").order.tolist() == [4, 1, 3, 2, 0]
    assert encode(df).order.tolist() == [0, 1, 2, 3, 4]


def test_order_ranks_are_per_layer(tasks):
    units = bind(tasks, uw.Chart(tasks, by="Task", order="Duration").layers)
    for name in "abc":
        sel = [i for i, r in enumerate(units.rows) if tasks.loc[r, "Task"] == name]
        durations = tasks.loc[[units.rows[i] for i in sel], "Duration"].to_numpy()
        assert units.order[sel].tolist() == np.argsort(np.argsort(durations)).tolist()


# --- errors ------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs, message", [
    (dict(size="Duraton"), r"size='Duraton': no such column \(did you mean 'Duration'\?\); "
                           r"the columns are 'Duration', 'Task'"),
    (dict(width="Tsk"), r"width='Tsk': no such column \(did you mean 'Task'\?\)"),
    (dict(order="Durations"), r"order='Durations': no such column \(did you mean 'Duration'\?\)"),
    (dict(color="Tsak"), r"color='Tsak' is neither a column \(did you mean 'Task'\?\) "
                         r"nor a CSS colour"),
    (dict(by="task"), r"by='task': no such column \(did you mean 'Task'\?\)"),
    (dict(margin="Durtion"), r"margin='Durtion': no such column \(did you mean 'Duration'\?\)"),
])
def test_missing_column_names_the_closest(kwargs, message):
    df = pd.DataFrame({"Duration": [1.0, 2.0], "Task": ["a", "b"]})
    with pytest.raises(ValueError, match=message):
        uw.Chart(df, **kwargs)


@pytest.mark.parametrize("channel", ["size", "width", "height", "margin"])
def test_non_numeric_column_is_refused(channel):
    df = pd.DataFrame({"Duration": [1.0, 2.0], "Task": ["a", "b"]})
    with pytest.raises(ValueError, match=rf"{channel}='Task': the column must be numeric, got dtype"):
        uw.Chart(df, **{channel: "Task"})


@pytest.mark.parametrize("values, bad, missing", [
    ([1.0, 0.0, 2.0, 3.0], 1, 0),
    ([1.0, -2.0, -0.5, 3.0], 2, 0),
    ([1.0, np.nan, 2.0, np.nan], 2, 2),
    ([1.0, np.inf, 2.0, -np.inf], 2, 0),
    ([0.0, np.nan, np.inf, -1.0], 4, 1),
])
def test_non_positive_missing_or_infinite_values_are_counted(values, bad, missing):
    df = pd.DataFrame({"Duration": values})
    with pytest.raises(ValueError, match=rf"size='Duration': {bad} of 4 rows are missing, infinite "
                                         rf"or not > 0 \({missing} missing\).*dropna=True"):
        uw.Chart(df, size="Duration")


def test_margins_of_marks_above_the_median_are_capped_at_the_median_marks_gap():
    margin = np.array([0.4, 0.4, 0.4, 0.2, 0.4])
    half_w = np.array([1.0, 1.0, 2.0, 8.0, 0.5])
    half_h = np.array([1.0, 4.0, 2.0, 2.0, 0.5])          # sizes 1, 2, 2 (median), 4, 0.5
    got = capped_margin(margin, half_w, half_h)
    np.testing.assert_allclose(got, [0.4, 0.4, 0.4, 0.1, 0.4])
    # above the median a mark's gap is its fraction of the median size (2), whatever its own
    np.testing.assert_allclose(got[3] * 4.0, 0.2 * 2.0)
    assert capped_margin(margin, half_w, half_h, "own") is margin


def test_negative_margin_values_are_refused_but_zero_is_fine():
    df = pd.DataFrame({"m": [0.0, 0.1, -0.2]})
    with pytest.raises(ValueError, match=r"margin='m': 1 of 3 rows are missing, infinite or not >= 0"):
        uw.Chart(df, margin="m")
    uw.Chart(df.iloc[:2], margin="m")


def test_nullable_integer_column_with_missing_values_is_counted():
    df = pd.DataFrame({"n": pd.array([1, None, 3], dtype="Int64")})
    with pytest.raises(ValueError, match=r"1 of 3 rows .* \(1 missing\)"):
        uw.Chart(df, size="n")


@pytest.mark.parametrize("other", [dict(width="b"), dict(height="b"), dict(width="b", height="b")])
def test_size_cannot_be_combined_with_width_or_height(other):
    df = pd.DataFrame({"a": [1.0, 2.0], "b": [2.0, 1.0]})
    with pytest.raises(ValueError, match=r"size='a' cannot be combined with width=.* or height="):
        uw.Chart(df, size="a", **other)


def test_dropna_drops_the_bad_rows_with_a_warning():
    df = pd.DataFrame({"v": [1.0, np.nan, 0.0, 2.0, 3.0]})
    with pytest.warns(UserWarning, match=r"dropped 2 of 5 rows"):
        chart = uw.Chart(df, size="v", dropna=True)
    assert chart.df.index.tolist() == [0, 3, 4]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        uw.Chart(df.iloc[[0, 3]], size="v", dropna=True)      # nothing to drop: no warning


def test_non_string_bindings_are_type_errors():
    df = pd.DataFrame({"v": [1.0, 2.0]})
    with pytest.raises(TypeError, match=r"size must be a column name"):
        uw.Chart(df, size=3)
    with pytest.raises(TypeError, match=r"color must be a column name"):
        uw.Chart(df, color=(1, 2, 3))


# --- columns checked at the door ------------------------------------------------------------
@pytest.mark.parametrize("channel", ["size", "width", "height", "margin", "color", "order", "x"])
def test_a_channel_bound_to_a_repeated_column_name_is_refused_naming_it(channel):
    df = pd.DataFrame([[1.0, 2.0], [2.0, 3.0]], columns=["v", "v"])
    with pytest.raises(ValueError, match=rf"{channel}='v': the DataFrame has 2 columns named 'v'"):
        uw.Chart(df, **{channel: "v"})


@pytest.mark.parametrize("channel", ["size", "width", "height", "margin", "x", "y"])
def test_complex_numbers_are_refused_naming_the_channel_and_dtype(channel):
    df = pd.DataFrame({"v": [1 + 5j, 2, 3]})
    with pytest.raises(ValueError, match=rf"{channel}='v': the column must hold real numbers, "
                                         r"got dtype complex128"):
        uw.Chart(df, **{channel: "v"})


@pytest.mark.parametrize("channel", ["size", "margin", "x", "y"])
@pytest.mark.parametrize("values", [[1, "a", 2.0], [1.0, 2 + 1j, 3.0]], ids=["text", "complex"])
def test_object_columns_mixing_numbers_with_other_values_are_refused(channel, values):
    df = pd.DataFrame({"v": pd.Series(values, dtype=object)})
    with pytest.raises(ValueError, match=rf"{channel}='v': the column \(dtype object\) mixes"):
        uw.Chart(df, **{channel: "v"})


def test_text_categories_still_place_on_x():
    df = pd.DataFrame({"v": pd.Series(["a", "b", 3], dtype=object).astype(str)})
    assert uw.Chart(df, x="v").layers
