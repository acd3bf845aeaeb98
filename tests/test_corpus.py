"""The generated design corpus (benchmarks/corpus) and its scoreboard: the generator covers
every axis, the measures catch what they claim to catch, and the quick slice of today's
engine stays within bounds (the whole corpus's numbers live in benchmarks/RESULTS.md)."""
from __future__ import annotations

import dataclasses
import pathlib
import sys
import warnings

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmarks"))
import scoreboard  # noqa: E402
from corpus import generate, joins, measure, order, run  # noqa: E402

pytestmark = pytest.mark.usefixtures("one_thread")
SLICE = scoreboard.quick_slice(generate.corpus(0, 120))


def test_the_corpus_has_the_issue_kinds_and_every_value_of_every_axis():
    specs = generate.corpus(0, 120)
    assert len(specs) == 120 and len({s.id for s in specs}) == 120
    assert [s.kind for s in specs[:len(generate.ISSUE_KINDS)]] == list(generate.ISSUE_KINDS)
    for axis, options in generate.AXES.items():
        drawn = {dict(s.axes)[axis] for s in specs if s.kind == "mixed"}
        assert drawn == set(options), axis


def test_the_same_seed_draws_the_same_designs_and_another_seed_others(tmp_path):
    a, b = generate.corpus(0, 20), generate.corpus(0, 20)
    assert a == b and a != generate.corpus(1, 20)
    first = generate.build(a[10], str(tmp_path)).chart.df
    again = generate.build(b[10], str(tmp_path)).chart.df
    pd.testing.assert_frame_equal(first, again)


@pytest.fixture(scope="module")
def laid_out():
    """Thirty circles packed closed in an ellipse: a layout the measures find clean."""
    container = uw.Container.ellipse(240, 180, 150, 110)
    chart = uw.Chart(pd.DataFrame({"v": np.linspace(1, 3, 30)}), mark="circle", size="v",
                     container=container, canvas=(480, 360), seed=0, legend=False)
    chart.layout()
    return chart, container


def measured(chart, container):
    return measure.ink_measures(chart.to_svg(legend=False), chart.canvas,
                                {"layer-1": container}, {"layer-1"}, {})


def measured_at(chart, container, placements):
    """The measures of ``chart`` drawn with other ``placements``; its layout is kept."""
    kept = chart.laid
    try:
        chart.laid = dataclasses.replace(kept, placements=placements)
        return measured(chart, container)
    finally:
        chart.laid = kept


def test_a_clean_layout_measures_clean(laid_out):
    m = measured(*laid_out)
    assert m["units"] == 30 and m["overlap"] < 0.01 and m["outside"] < 0.005 and m["empty"] < 0.1


def test_marks_piled_on_one_point_are_caught_as_overlap_and_leave_the_container_empty(laid_out):
    chart, container = laid_out
    moved = chart.placements.copy()
    moved[["x", "y"]] = (240.0, 180.0)
    m = measured_at(chart, container, moved)
    assert m["overlap"] > 0.5 and m["empty"] > 0.5


def test_marks_pushed_out_of_their_container_are_caught_as_ink_outside(laid_out):
    chart, container = laid_out
    moved = chart.placements.copy()
    moved["x"] = moved["x"] + 200.0                     # half of them leave the ellipse
    m = measured_at(chart, container, moved)
    assert m["outside"] > 0.3


def test_a_mark_across_the_join_of_two_heads_splits_them_and_one_inside_a_head_does_not():
    y, x = np.mgrid[0:100, 0:200] + 0.5
    heads = (np.hypot(x - 55, y - 50) <= 45) | (np.hypot(x - 145, y - 50) <= 45)   # touch at x=100
    pieces = joins.large_pieces(heads, float(heads.sum()))
    across = np.hypot(x[35:65, 85:115] - 100, y[35:65, 85:115] - 50) <= 15
    inside = np.hypot(x[35:65, 40:70] - 55, y[35:65, 40:70] - 50) <= 15
    assert pieces == 1
    assert joins.splits(heads, across, slice(35, 65), slice(85, 115), pieces)
    assert not joins.splits(heads, inside, slice(35, 65), slice(40, 70), pieces)


def strata_table(lower_y: float, upper_y: float) -> pd.DataFrame:
    xs = np.arange(20.0, 400.0, 20.0)
    rows = [(layer, x, y, 20.0, 20.0) for layer, y in (("0", lower_y), ("1", upper_y)) for x in xs]
    return pd.DataFrame(rows, columns=["layer", "x", "y", "width", "height"])


def test_strata_are_in_order_when_the_upper_layer_rests_on_the_lower_and_not_when_swapped():
    chart = uw.Chart(pd.DataFrame({"k": [0, 1]}), by="k", forces=[uw.DirectionalForce(90)],
                     boundary="open", canvas=(480, 360))
    chart.layer("1").set(blocks=["0"])
    assert order.strata_in_order(strata_table(300, 280), chart.layers) == 1.0
    assert order.strata_in_order(strata_table(280, 300), chart.layers) == 0.0
    assert order.pull(strata_table(340, 340), chart.layers, chart.canvas) > 0.9


@pytest.mark.corpus
@pytest.mark.parametrize("spec", SLICE, ids=[s.id for s in SLICE])
def test_the_quick_slice_stays_within_the_bounds_of_todays_engine(spec, tmp_path):
    """Bounds a sound engine meets on every design of the slice: no error, little overlap
    and ink outside, closed containers mostly covered, strata mostly in order, an open fill
    far below its ask only with a warning. Today's worst over layout seeds 0-4
    (benchmarks/corpus-quick-seeds.json): overlap 0.49%, outside 0.59%, empty 16.7%, strata
    0.80, fill 0.44 of the ask with no warning, 4.6 s; the bounds leave that much again.
    Strata under two point forces (m048) read 0.67 on an AMD EPYC, whose float paths differ
    from the Xeon's the board was made on: the strata bound is 0.6."""
    r = run.run(spec, str(tmp_path))
    assert "error" not in r, r.get("traceback")
    assert r["overlap"] <= 0.01 and r["outside"] <= 0.01, r
    if r["empty"] is not None:
        assert r["empty"] <= 0.25, r
    if r["fill"] is not None and not r["warnings"]:
        assert r["fill"] >= 0.3 * r["fill_asked"], r
    if r["strata"] is not None:
        assert r["strata"] >= 0.6, r
    assert r["seconds"] <= 60, r
    assert 0 < r["iterations"] and r["budget"] == max(layer.iterations for layer in
                                                       generate.build(spec, str(tmp_path)).chart.layers)


@pytest.mark.corpus
def test_a_pile_is_laid_out_the_same_on_one_thread_and_on_two(tmp_path):
    # corpus m039: lognormal stars pushed right. The finish's drop gave a pixel two
    # footprints share to whichever thread wrote it last: on two threads the pile came out
    # otherwise than on one, and otherwise again with the machine busy
    spec = next(s for s in generate.corpus(0, 120) if s.id == "m039")
    before, placed = torch.get_num_threads(), []
    try:
        for count in (1, 2):
            torch.set_num_threads(count)
            chart = generate.build(spec, str(tmp_path / str(count))).chart
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                chart.layout()
            placed.append(chart.placements[["x", "y", "angle"]].to_numpy())
    finally:
        torch.set_num_threads(before)
    np.testing.assert_array_equal(placed[0], placed[1])


def test_the_board_counts_the_layouts_that_spent_their_whole_budget():
    clean = dict(id="m", seed=0, tags={}, warnings=[], units=10, overlap=0.0, outside=0.0,
                 empty=None, fill=None, fill_asked=None, join=0.0, strata=None, rho=None,
                 pull=None, seconds=1.0, budget=600)
    records = [dict(clean, iterations=n) for n in (600, 212, 960)]
    spent = [line for line in scoreboard.totals(records) if line.startswith("iterations")]
    assert spent == ["iterations: median 600; the whole budget spent (never at rest): 2 of 3"]
    assert "| 212 |" in scoreboard.line(records[1])


def test_the_quick_slice_is_fifteen_designs_of_the_corpus():
    assert len(SLICE) == len(scoreboard.QUICK) == 15


def test_a_design_with_png_assets_builds_into_a_folder_not_made_yet(tmp_path):
    spec = next(s for s in generate.corpus(0, 120) if dict(s.axes).get("mark") == "png")
    built = generate.build(spec, str(tmp_path / "assets"), 0)
    assert any(p.suffix == ".png" for p in (tmp_path / "assets").iterdir())
    assert len(built.chart.df) > 0
