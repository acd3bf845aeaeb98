"""One mark for k units: count= tables, per= marks, their rounding, partial marks, and what
the key, tooltips, selection and design say of them (design/tally.py, layout/prepare/tally.py)."""
from __future__ import annotations

import io
import re

import numpy as np
import pandas as pd
import pytest
from PIL import Image

import unitopia_widget as uw
from unitopia_widget.output import animation
from unitopia_widget.design.tally import ink_clip, marks_per_group
from unitopia_widget.layout.prepare.warm import unit_keys

COUNTS = pd.DataFrame({"species": ["Adelie", "Gentoo", "Chinstrap"], "n": [1234, 567, 89]})


def per_category(chart) -> dict:
    """{category: marks} of a one-layer chart coloured by species."""
    rows = chart.df.loc[chart.units.rows, "species"]
    return rows.value_counts().to_dict()


def test_a_count_table_draws_one_unit_per_count_coloured_by_its_row():
    chart = uw.Chart(COUNTS, count="n", color="species", mark="square")
    assert len(chart.units.rows) == 1890
    colours = pd.Series(chart.units.colors).value_counts()
    assert sorted(colours.tolist()) == [89, 567, 1234]
    assert chart.titles()[-1].startswith("species: Chinstrap\nn: 89")   # a unit's tooltip: its row


def test_rows_of_no_units_draw_nothing_and_fractions_need_per():
    df = pd.DataFrame({"c": ["a", "b"], "n": [0, 3]})
    assert uw.Chart(df, count="n", mark="square").units.rows == [1, 1, 1]
    with pytest.raises(ValueError, match=r"count='n': without per=, .* whole numbers; row 1 "
                                         r"has 2.5; .* per=1"):
        uw.Chart(df.assign(n=[1, 2.5]), count="n", mark="square")
    with pytest.raises(ValueError, match=r"count='n': 1 of 2 rows .* not >= 0"):
        uw.Chart(df.assign(n=[-1, 2]), count="n", mark="square")
    with pytest.warns(UserWarning, match=r"dropped 1 of 2 rows .* count='n'"):
        chart = uw.Chart(df.assign(n=[-1, 2]), count="n", mark="square", dropna=True)
    assert chart.units.rows == [1, 1]


def test_per_rounds_by_largest_remainder_within_the_layer():
    chart = uw.Chart(COUNTS, count="n", per=100, color="species", mark="square")
    marks = per_category(chart)
    assert sum(marks.values()) == 19 == round(1890 / 100)
    assert marks == {"Adelie": 12, "Gentoo": 6, "Chinstrap": 1}
    for species, n in zip(COUNTS.species, COUNTS.n):
        assert abs(marks[species] - n / 100) < 1
    assert chart.units.amount.sum() == pytest.approx(1890)   # every unit stands in some mark


@pytest.mark.parametrize("rounding, expected", [
    ("floor", {"Adelie": 12, "Gentoo": 5}), ("ceil", {"Adelie": 13, "Gentoo": 6, "Chinstrap": 1}),
    ("nearest", {"Adelie": 12, "Gentoo": 6, "Chinstrap": 1})])
def test_the_other_roundings_round_each_category_alone(rounding, expected):
    chart = uw.Chart(COUNTS, count="n", per=100, rounding=rounding, color="species", mark="square")
    assert per_category(chart) == expected


def test_largest_remainder_gives_the_extra_marks_to_the_largest_remainders():
    # 1.49 + 1.6 + 0.41 = 3.5 marks -> 4: the floors (1, 1, 0), then one more for 0.6 and 0.49
    marks, fraction = marks_per_group(np.array([149.0, 160.0, 41.0]), 100, "largest-remainder", False)
    assert marks.tolist() == [2, 2, 0] and fraction.tolist() == [1, 1, 1]
    marks, fraction = marks_per_group(np.array([149.0, 160.0, 41.0]), 100, "largest-remainder", True)
    assert marks.tolist() == [2, 2, 1] and fraction == pytest.approx([0.49, 0.6, 0.41])


def test_per_without_count_counts_rows_and_the_tooltip_says_which():
    df = pd.DataFrame({"kind": ["a"] * 250 + ["b"] * 60})
    chart = uw.Chart(df, per=100, color="kind", mark="square")
    assert per_category_of(chart, "kind") == {"a": 2, "b": 1}   # 2.5 + 0.6 = 3.1 -> 3
    first = chart.titles()[0]
    assert first == "kind: a\nunits: 100\nrows: 100 (0, 1, 2, ...)"
    b = chart.units.layer.size - 1
    assert chart.titles()[b] == "kind: b\nunits: 60\nrows: 60 (250, 251, 252, ...)"


def per_category_of(chart, column) -> dict:
    return chart.df.loc[chart.units.rows, column].value_counts().to_dict()


def test_selecting_a_mark_selects_the_rows_it_covers():
    w = uw.UnitoPia(COUNTS, count="n", per=100, color="species", mark="square")
    adelie = [k for k, r in enumerate(w._chart.units.rows) if r == 0]
    w.selected_units = [adelie[-1]]   # the last Adelie mark covers 134 units of row 0
    assert w.selected.index.tolist() == [0]
    df = pd.DataFrame({"kind": ["a", "b"] * 150})
    w = uw.UnitoPia(df, per=100, color="kind", mark="square")
    w.selected_units = [0]
    assert w.selected.index.tolist() == list(range(0, 200, 2))
    assert set(w.selected["kind"]) == {"a"}


def test_the_legend_says_what_a_mark_stands_for():
    chart = uw.Chart(COUNTS, count="n", per=100, color="species", mark="square", iterations=20)
    chart.layout(cancel=lambda: True)
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", chart.to_svg())
    assert "1 mark = 100 n" in texts and "19 marks for 1,890 n" in texts
    rows = uw.Chart(pd.DataFrame({"kind": ["a"] * 30}), per=10, color="kind", mark="square")
    rows.layout(cancel=lambda: True)
    assert "1 mark = 10 rows" in re.findall(r"<text[^>]*>([^<]*)</text>", rows.to_svg())


def test_a_numeric_size_or_colour_with_per_is_refused_naming_both():
    df = COUNTS.assign(v=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"size='v' cannot be combined with per=100: a mark of "
                                         r"100 units has no single size"):
        uw.Chart(df, count="n", per=100, size="v", mark="square")
    with pytest.raises(ValueError, match=r"color='v' is numeric, so it cannot be combined with "
                                         r"per=100"):
        uw.Chart(df, count="n", per=100, color="v", mark="square")
    with pytest.raises(ValueError, match=r"per must be a number of units > 0.*got -1"):
        uw.Chart(df, per=-1)
    with pytest.raises(ValueError, match=r"rounding must be one of 'largest-remainder', 'floor', "
                                         r"'ceil', 'nearest'; got 'up'"):
        uw.Chart(df, per=10, rounding="up")


def test_too_many_units_are_refused_naming_a_per_that_fits():
    with pytest.raises(ValueError, match=r"25000 units is more than this widget lays out "
                                         r"\(20000\); sample or aggregate the rows first, or .* "
                                         r"per=2 draws these 25,000 units"):
        uw.Chart(pd.DataFrame({"v": np.ones(25_000)}), mark="square")
    huge = pd.DataFrame({"c": ["a"], "n": [10 ** 12]})   # refused before a row is repeated
    with pytest.raises(ValueError, match=r"per=1e\+08 draws"):
        uw.Chart(huge, count="n", mark="square")
    assert len(uw.Chart(huge, count="n", per=10 ** 8, mark="square").units.rows) == 10_000


def test_a_partial_mark_keeps_its_fraction_of_the_ink():
    person = uw.Mark.from_spec("fa:person")
    for fraction in (0.2, 0.5, 0.89):
        clip = ink_clip(person, fraction)
        ink = person.as_footprint("ink").silhouette(256)
        kept = ink[:, :int(round(clip * ink.shape[1]))].sum() / ink.sum()
        assert kept == pytest.approx(fraction, abs=0.02)
    assert ink_clip(person, 1.0) == 1.0


def test_partial_marks_are_clipped_in_the_svg_the_png_the_page_and_the_film(tmp_path):
    chart = uw.Chart(COUNTS, count="n", per=100, partial=True, color="species", mark="fa:person",
                     arrange="grid", container=uw.Container.rect(10, 10, 780, 480))
    table = chart.layout()   # a grid stands still: a few iterations
    assert len(table) == 20 and (table["drawn"] < 1).sum() == 3
    assert table["units"].sum() == pytest.approx(1890)
    svg = chart.to_svg(legend=False)
    assert svg.count('clip-path="url(#c') == 3 and svg.count("<clipPath") == 3
    png = np.array(Image.open(io.BytesIO(chart.to_png(scale=1.0, legend=False))).convert("RGBA"))

    def ink(k):   # alpha inside unit k's box
        x, y, w, h = table.loc[k, ["x", "y", "width", "height"]]
        return png[int(y - h / 2):int(y + h / 2) + 1, int(x - w / 2):int(x + w / 2) + 1, 3].sum()

    whole = ink(int(np.nonzero(table["drawn"].to_numpy() == 1)[0][0]))
    for k in np.nonzero(table["drawn"].to_numpy() < 1)[0]:
        fraction = table.loc[k, "units"] / 100
        assert ink(k) / whole == pytest.approx(fraction, rel=0.1)
    chart.save(tmp_path / "chart.html")
    assert (tmp_path / "chart.html").read_text().count('clip-path=\\"url(#c') == 3
    last = animation.render(chart, svg, fps=2, seconds=0.5)[-1]   # the film's last frame
    film = np.asarray(last.convert("L"), dtype=float)
    k = int(np.nonzero(table["drawn"].to_numpy() < 1)[0][0])
    x, y, w, h = table.loc[k, ["x", "y", "width", "height"]]
    box = film[int(y - h / 2):int(y + h / 2), int(x - w / 2):int(x + w / 2)]
    right = box[:, int(w * table.loc[k, "drawn"]) + 2:]
    assert right.min() > 250 and box.min() < 200   # ink left of the cut, none right of it


def test_count_per_rounding_and_partial_are_saved_and_written_as_code():
    chart = uw.Chart(COUNTS, count="n", per=100, rounding="ceil", partial=True, color="species",
                     mark="square")
    layer = chart.design()["layers"][0]
    assert {k: layer[k] for k in ("count", "per", "rounding", "partial")} == {
        "count": "n", "per": 100, "rounding": "ceil", "partial": True}
    again = uw.Chart.from_design(COUNTS, chart.design())
    assert (again.layers[0].per, again.layers[0].partial) == (100, True)
    assert "'per': 100" in chart.to_code() and "'count': 'n'" in chart.to_code()
    plain = uw.Chart(COUNTS, mark="square").design()["layers"][0]
    assert not {"count", "per", "rounding", "partial"} & set(plain)   # old designs unchanged


def test_by_layers_round_each_layer_alone():
    df = pd.DataFrame({"year": [1, 1, 2, 2], "kind": ["a", "b", "a", "b"], "n": [150, 150, 50, 60]})
    chart = uw.Chart(df, by="year", count="n", per=100, color="kind", mark="square")
    assert np.bincount(chart.units.layer).tolist() == [3, 1]   # round(3.0), round(1.1)


def test_a_warm_start_matches_each_unit_of_a_row_to_its_own_place():
    assert unit_keys(["a", "a", "a", "b"], [0, 0, 1, 0]) == [
        ("a", 0, 0), ("a", 0, 1), ("a", 1, 0), ("b", 0, 0)]
