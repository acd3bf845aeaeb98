"""The Table 1 benchmark's own parts (benchmarks/discs.py, peers.py, table1.py): the exact
overlap measure, the sizes, the start, the pymunk peer and the fresh-process rows. Nothing
here is timed; the benchmark's numbers live in benchmarks/RESULTS.md."""
from __future__ import annotations

import math
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmarks"))
import discs  # noqa: E402
import peers  # noqa: E402
import table1  # noqa: E402


def grid_lens(d, a, b, k=2001):
    """The lens area by counting the points of a fine grid inside both discs."""
    x0, x1 = -a, a
    xs = np.linspace(x0, x1, k)
    X, Y = np.meshgrid(xs, xs)
    both = (X ** 2 + Y ** 2 <= a * a) & ((X - d) ** 2 + Y ** 2 <= b * b)
    return both.sum() * (xs[1] - xs[0]) ** 2


def test_lens_area_of_two_unit_discs_one_radius_apart_is_the_textbook_value():
    textbook = 2 * math.acos(0.5) - math.sqrt(3) / 2
    assert discs.lens_area(1.0, 1.0, 1.0)[()] == pytest.approx(textbook)


def test_lens_area_is_zero_apart_and_the_small_disc_inside():
    got = discs.lens_area([2.0, 3.0, 0.5], [1.0, 1.0, 2.0], [1.0, 1.0, 1.0])
    assert got[:2].tolist() == [0.0, 0.0]
    assert got[2] == pytest.approx(math.pi)


def test_lens_area_of_unequal_discs_matches_counting():
    assert discs.lens_area(2.0, 2.0, 1.0)[()] == pytest.approx(grid_lens(2.0, 2.0, 1.0), rel=2e-3)


def test_circle_metrics_measure_overlap_outside_and_height():
    center = np.array([[discs.CX, discs.CY], [discs.CX + 10, discs.CY],   # a lens
                       [discs.CX, discs.CY + discs.R]])                   # on the rim
    r = np.array([10.0, 10.0, 10.0])
    m = discs.circle_metrics(center, r)
    area = 3 * math.pi * 100
    assert m["overlap_%"] == pytest.approx(100 * discs.lens_area(10.0, 10.0, 10.0)[()] / area)
    # half of the rim disc sticks out, a little more since the container curves away
    assert 100 * 0.5 / 3 < m["outside_%"] < 100 * 0.51 / 3
    assert m["mean_y"] == pytest.approx(discs.CY + discs.R / 3)


def test_sizes_equal_10x_and_heavy_tailed_within_their_spread():
    assert discs.values(50, "equal").tolist() == [1.0] * 50
    ten = discs.values(2000, "10x")
    assert 1 <= ten.min() and ten.max() <= 10 and ten.max() / ten.min() > 9
    heavy = discs.values(2000, "heavy")
    assert heavy.max() / heavy.min() == pytest.approx(discs.HEAVY_SPREAD)
    assert np.median(heavy) == pytest.approx(1.0, abs=0.1)


def test_unknown_sizes_name_the_accepted_ones():
    with pytest.raises(ValueError, match=r"sizes='5x': expected one of equal, 10x, heavy"):
        discs.values(10, "5x")


def test_radii_cover_sixty_percent_of_the_container():
    r = discs.radii(discs.values(300, "heavy"))
    assert np.sum(np.pi * r ** 2) == pytest.approx(0.6 * math.pi * discs.R ** 2)


def test_lattice_start_packs_equal_discs_inside_at_the_force():
    r = discs.radii(discs.values(300, "equal"))
    start = discs.lattice_start(r)
    m = discs.circle_metrics(start, r)
    assert m["overlap_%"] == 0 and m["outside_%"] == 0
    assert m["mean_y"] > discs.CY + 0.15 * discs.R   # gathered towards the bottom


def test_lattice_start_tightens_for_few_large_discs():
    r = discs.radii(discs.values(10, "equal"))   # radius ~98: the first lattice holds fewer
    assert discs.lattice_start(r).shape == (10, 2)


def test_pymunk_settles_thirty_discs_inside_the_container_towards_the_force():
    r = discs.radii(discs.values(30, "10x"))
    start = discs.lattice_start(r)
    out = peers.settle(r, start)
    m = discs.circle_metrics(out["center"], r)
    assert out["center"].shape == (30, 2) and 0 < out["steps"] < peers.MAX_STEPS
    assert m["outside_%"] < 0.5 and m["overlap_%"] < 1.0
    assert discs.circle_metrics(start, r)["overlap_%"] > 1.0   # unequal discs start overlapped
    assert m["mean_y"] > discs.circle_metrics(start, r)["mean_y"]


def test_random_start_pours_the_discs_over_the_whole_container():
    r = discs.radii(discs.values(500, "10x"))
    m = discs.circle_metrics(discs.random_start(r), r)
    assert m["outside_%"] == 0 and m["overlap_%"] > 10
    assert m["mean_y"] == pytest.approx(discs.CY, abs=20)


def test_pymunk_from_a_random_start_falls_to_the_force():
    r = discs.radii(discs.values(30, "equal"))
    start = discs.random_start(r)
    out = peers.settle(r, start)
    m = discs.circle_metrics(out["center"], r)
    assert m["mean_y"] > discs.circle_metrics(start, r)["mean_y"] + 0.1 * discs.R
    assert m["overlap_%"] < 1.0


def test_a_row_runs_engine_and_pymunk_in_fresh_processes_and_reports_the_ratio():
    row = table1.row(20, "equal", closed=False, peer="lattice")
    assert row["sizes"] == "equal" and row["iterations"] > 0
    assert row["overlap_%"] < 1.0 and row["pymunk_overlap_%"] < 1.0
    assert row["ratio_cold"] == pytest.approx(row["cold_s"] / row["pymunk_cold_s"])
    assert row["ratio_warm"] == pytest.approx(row["warm_s"] / row["pymunk_warm_s"])
    assert row["import_s"] > 0 and row["warm_s"] > 0
    text = table1.markdown([row], closed=False)
    assert text.splitlines()[0].startswith("| N | sizes | import s | cold s | warm s |")
    assert "| 20 | equal |" in text and text.count("\n") == 2


def test_closed_tables_show_density_and_no_pymunk_columns():
    row = {"N": 1000, "sizes": "equal", "cold_s": 1.0, "density": 0.8801, "mean_y": 415.0}
    text = table1.markdown([row], closed=True)
    assert text.splitlines()[0] == "| N | sizes | cold s | density |"
    assert text.splitlines()[2] == "| 1,000 | equal | 1.00 | 0.880 |"


def test_cli_rejects_unknown_sizes_and_sizes_with_equal_only(capsys):
    with pytest.raises(SystemExit):
        table1.main(["200", "--sizes", "equal,5x"])
    assert "--sizes 'equal,5x': '5x' is not one of equal, 10x, heavy" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        table1.main(["200", "--sizes", "10x", "--equal-only"])
    assert "not allowed with argument --sizes" in capsys.readouterr().err
