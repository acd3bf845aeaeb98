"""Tests for unitopia_widget.design.emitters and bezier: grid and curve emitters, stroke fitting."""
import math

import numpy as np
import pandas as pd
import pytest
import torch
from scipy.spatial import cKDTree
from scipy.spatial.distance import pdist
from scipy.stats import spearmanr

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.prepare.curves import CurveTrack
from unitopia_widget.design.bezier import Curve, fit_bezier
from unitopia_widget.design.emitters import CurveEmitter, GridEmitter, emitter_from_json
from unitopia_widget.layout.solver import solve

S_CURVE = [[100, 400], [250, 100], [550, 450], [700, 150]]
TWO_SEGMENTS = [[80, 250], [180, 60], [320, 60], [400, 250], [480, 440], [620, 440], [720, 250]]


pytestmark = pytest.mark.usefixtures("one_thread")


def bezier(points, n=20001) -> np.ndarray:
    """(n, 2) points of the piecewise cubic, evaluated from its definition."""
    pts = np.asarray(points, dtype=float)
    t = np.linspace(0, 1, n)[:, None]
    out = []
    for j in range(0, len(pts) - 1, 3):
        p0, p1, p2, p3 = pts[j:j + 4]
        out.append((1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t ** 2 * p2
                   + t ** 3 * p3)
    return np.concatenate(out)


def up_axis(table) -> np.ndarray:
    """(N, 2) unit up axis of each mark: (sin a, -cos a), a the placement angle."""
    a = np.radians(table["angle"].to_numpy())
    return np.stack([np.sin(a), -np.cos(a)], axis=1)


def angle_between(u, v) -> np.ndarray:
    """Degrees between the rows of u and v."""
    v = v / np.linalg.norm(v, axis=1, keepdims=True)
    return np.degrees(np.arccos(np.clip((u * v).sum(1), -1, 1)))


def ordered_frame(n, seed=0):
    return pd.DataFrame({"v": np.ones(n), "when": np.random.default_rng(seed).permutation(n)},
                        index=[f"u{i}" for i in range(n)])


# --- GridEmitter -----------------------------------------------------------------

def test_grid_place_hands_out_lattice_points_in_reading_order():
    lattice = np.array([[10, 10], [30, 10], [50, 10], [20, 27], [40, 27], [10, 44]], float)
    ranks = np.array([2, 0, 1, 5, 3, 4])
    placed = GridEmitter().place(lattice, ranks)
    np.testing.assert_array_equal(placed, lattice[ranks])      # rank k gets the k-th point


def test_grid_place_thins_evenly_when_more_points_fit():
    lattice = np.stack([np.arange(10) * 10.0, np.zeros(10)], axis=1)
    placed = GridEmitter().place(lattice, np.arange(4))
    np.testing.assert_array_equal(placed[:, 0], [0, 30, 60, 90])   # first and last kept


def test_grid_place_with_a_direction_orders_along_it():
    pts = np.array([[x, y] for y in (10, 30, 50) for x in (10, 30, 50)], float)
    placed = GridEmitter(direction=90).place(pts, np.arange(9))
    # downstream first: rank 0 at the bottom row, the last rank on the top row
    assert np.all(np.diff(placed[:, 1]) <= 0) and placed[0, 1] == 50 and placed[-1, 1] == 10


def test_grid_layout_with_speed_zero_keeps_the_emitted_grid():
    df = ordered_frame(30)
    chart = uw.Chart(df, size="v", order="when", emitter=uw.GridEmitter(speed=0),
                     container=uw.Container.rect(100, 50, 600, 400), iterations=40)
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, chart.seed, "cpu")
    emitted = problem.placement.t.detach().numpy().astype(float)
    result = solve(problem)
    np.testing.assert_array_equal(result.center, emitted)          # nothing moved...
    assert result.scale != pytest.approx(problem.scale, rel=1e-4)   # ...only the scale changed
    # the same through the public API
    table = chart.layout()
    np.testing.assert_allclose(table[["x", "y"]].to_numpy(), emitted, atol=1e-4)
    # reading order: rank 0 top-left, ranks run along rows, rows top to bottom
    by_rank = table.assign(rank=df.loc[table["row"], "when"].to_numpy()).sort_values("rank")
    xy = by_rank[["x", "y"]].to_numpy()
    assert xy[0, 1] == xy[:, 1].min() and xy[0, 0] == xy[xy[:, 1] == xy[0, 1], 0].min()
    dy, dx = np.diff(xy[:, 1]), np.diff(xy[:, 0])
    assert np.all(dy >= -1e-6) and np.all(dx[np.abs(dy) < 1e-6] > 0)
    # a hexagonal lattice: rows sqrt(3)/2 spacing apart, odd rows offset by half a spacing
    rows = np.unique(np.round(xy[:, 1], 3))
    pitch = np.diff(rows)
    spacing = pitch[0] / (math.sqrt(3) / 2)
    np.testing.assert_allclose(pitch, pitch[0], rtol=1e-4)
    phase = ((xy[:, 0] - xy[0, 0]) / spacing) % 1.0
    row_no = np.round((xy[:, 1] - rows[0]) / pitch[0]).astype(int)
    np.testing.assert_allclose(np.minimum(np.abs(phase - 0.5 * (row_no % 2)),
                                          1 - np.abs(phase - 0.5 * (row_no % 2))), 0, atol=1e-3)
    inside = (xy[:, 0] > 100) & (xy[:, 0] < 700) & (xy[:, 1] > 50) & (xy[:, 1] < 450)
    assert inside.all()


def test_grid_emitter_validation_and_json():
    with pytest.raises(ValueError, match=r"GridEmitter: speed must be >= 0, got -1"):
        GridEmitter(speed=-1)
    with pytest.raises(ValueError, match=r"GridEmitter: direction must be a number of degrees or "
                                         r"None; got 'down'"):
        GridEmitter(direction="down")
    g = GridEmitter(speed=0.5, direction=45)
    assert emitter_from_json(g.to_json()) == g
    assert g.to_json() == {"kind": "grid", "speed": 0.5, "direction": 45.0}


# --- CurveEmitter: spacing -------------------------------------------------------

def test_arc_positions_space_equal_marks_evenly_in_rank_order():
    emitter = CurveEmitter([[0, 0], [100, 0], [200, 0], [300, 0]])   # a straight 300 px line
    ranks = np.array([3, 0, 2, 1, 4])
    arc = emitter.arc_positions(np.full(5, 20.0), ranks)
    # free room 300 - 100 = 200 shared as 40 px gaps: centres at 30, 90, 150, 210, 270
    np.testing.assert_allclose(arc, np.array([30, 90, 150, 210, 270.0])[ranks], atol=1e-9)


def test_arc_positions_respect_unequal_lengths_and_squeeze_onto_a_short_curve():
    emitter = CurveEmitter([[0, 0], [100, 0], [200, 0], [300, 0]])
    arc = emitter.arc_positions(np.array([10.0, 50.0, 30.0]), np.arange(3))
    gap = (300 - 90) / 3
    np.testing.assert_allclose(arc, [5 + gap / 2, 10 + gap + 25 + gap / 2,
                                     60 + 2 * gap + 15 + gap / 2], atol=1e-9)
    tight = emitter.arc_positions(np.full(10, 60.0), np.arange(10))   # 600 px of marks on 300 px
    assert np.all(np.diff(tight) > 0) and tight[0] >= 0 and tight[-1] <= 300
    np.testing.assert_allclose(np.diff(tight), 30.0, atol=1e-9)


def curve_start(fill):
    """The start of 20 equal circles emitted from ``S_CURVE`` in a shuffled ``order=``:
    the bound units, their start centres ``(20, 2)`` and footprint diameter (px)."""
    chart = uw.Chart(ordered_frame(20), size="v", order="when", emitter=uw.CurveEmitter(S_CURVE),
                     boundary="open", fill=fill, iterations=20)
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu")
    start = problem.placement.t.detach().numpy().astype(float)
    return units, start, 2 * float(problem.disc[0] * problem.scale)


def test_curve_layout_starts_marks_on_the_curve_in_order():
    units, start, diameter = curve_start(fill=0.04)    # 20 marks fit on the curve end to end
    assert 20 * diameter < Curve(S_CURVE).length
    assert cKDTree(bezier(S_CURVE)).query(start)[0].max() < 0.5
    arc = Curve(S_CURVE).nearest_arc(start)
    assert spearmanr(units.order, arc).statistic == pytest.approx(1.0)
    steps = np.diff(np.sort(arc))
    np.testing.assert_allclose(steps, steps.mean(), atol=8.0)    # even, up to the arc lookup


def test_marks_a_curve_is_too_short_for_start_beside_it_in_order_not_on_top_of_each_other():
    units, start, diameter = curve_start(fill=0.1)     # 20 marks longer than the curve
    assert 20 * diameter > 1.15 * Curve(S_CURVE).length
    assert pdist(start).min() > 0.95 * diameter        # squeezed onto the curve: 0.7
    assert cKDTree(bezier(S_CURVE)).query(start)[0].max() < 1.5 * diameter
    assert spearmanr(units.order, Curve(S_CURVE).nearest_arc(start)).statistic > 0.9


# --- CurveEmitter: modes -------------------------------------------------------------

@pytest.fixture(scope="module")
def line_layout():
    df = ordered_frame(30, seed=1)
    chart = uw.Chart(df, size="v", order="when", mark="triangle", orientation="along_emitter",
                     emitter=uw.CurveEmitter(S_CURVE, mode="line"), boundary="open", fill=0.1,
                     iterations=150)
    return df, chart, chart.layout()


def test_line_mode_keeps_the_order_along_the_curve(line_layout):
    df, _, table = line_layout
    arc = Curve(S_CURVE).nearest_arc(table[["x", "y"]].to_numpy())
    rho = spearmanr(df.loc[table["row"], "when"], arc).statistic
    assert rho > 0.95, rho


def test_line_mode_keeps_centres_on_the_curve(line_layout):
    _, _, table = line_layout
    distance = cKDTree(bezier(S_CURVE)).query(table[["x", "y"]].to_numpy())[0]
    assert distance.max() < 1.0, distance.max()


def test_line_mode_marks_do_not_pile_up(line_layout):
    # the marks push each other along the curve: centres stay at least ~ a mark apart
    _, _, table = line_layout
    arc = np.sort(Curve(S_CURVE).nearest_arc(table[["x", "y"]].to_numpy()))
    assert np.diff(arc).min() > 0.3 * table["height"].mean()


def test_along_emitter_orientation_follows_the_curve(line_layout):
    _, _, table = line_layout
    curve = Curve(S_CURVE)
    tangent, _ = curve.frame(curve.nearest_arc(table[["x", "y"]].to_numpy()))
    target = np.stack([tangent[:, 1], -tangent[:, 0]], axis=1)   # the tangent turned -90 degrees
    err = angle_between(up_axis(table), target)
    print(f"along_emitter (line, 30 triangles): median {np.median(err):.2f} deg, "
          f"90th percentile {np.percentile(err, 90):.2f} deg")
    assert np.median(err) < 6 and np.percentile(err, 90) < 12


def test_band_mode_keeps_order_and_lets_marks_leave_the_line():
    df = ordered_frame(40, seed=2)
    chart = uw.Chart(df, size="v", order="when", emitter=uw.CurveEmitter(S_CURVE, mode="band"),
                     boundary="open", fill=0.25, iterations=150)
    table = chart.layout()
    xy = table[["x", "y"]].to_numpy()
    rho = spearmanr(df.loc[table["row"], "when"], Curve(S_CURVE).nearest_arc(xy)).statistic
    assert rho > 0.95, rho
    distance = cKDTree(bezier(S_CURVE)).query(xy)[0]
    assert distance.max() > 0.25 * table["width"].mean()     # stacked sideways, off the curve


def test_band_offsets_keep_the_centres_on_the_canvas():
    # a band mark's offset grows along the normal without bound; a step may carry it off the
    # canvas, where its raster (and so its loss) is cut away and nothing brings it back
    curve = Curve(S_CURVE)
    track = CurveTrack(np.arange(5), curve, "band", np.linspace(0, curve.length, 5),
                       np.arange(5), True, "cpu")
    with torch.no_grad():
        track.v.copy_(torch.tensor([-5000.0, 5000.0, -5000.0, 5000.0, 0.0]))
    low, high = torch.full((5, 2), 12.0), torch.tensor([[788.0, 588.0]]).expand(5, 2)
    track.project(low, high)
    center = track.positions()[0]
    assert bool(((center >= low - 1e-3) & (center <= high + 1e-3)).all()), center
    assert float(track.v[4]) == 0.0                      # a centre already on stays
    assert float(track.v[0]) != 0.0                      # pulled in to the edge, not the curve


def test_a_warm_run_starts_band_marks_where_they_ended():
    # a change (here a margin) runs the layout again from the last one: marks on a band start
    # where they ended, not back on the curve at their emitted arc lengths
    df = ordered_frame(30, seed=4)
    chart = uw.Chart(df, size="v", order="when", emitter=uw.CurveEmitter(S_CURVE, mode="band"),
                     forces=[uw.PointForce(400, 560)], boundary="open", fill=0.25, iterations=150)
    before = chart.layout().set_index("row")[["x", "y"]]
    assert cKDTree(bezier(S_CURVE)).query(before.to_numpy())[0].max() > 20   # off the curve
    chart.layers[0].set(margin=0.02)
    frames = []
    chart.layout(on_frame=lambda frame, *final: frames.append(frame.copy()))
    start = pd.DataFrame(frames[0][:, :2], columns=["x", "y"], index=chart.placements["row"])
    moved = np.hypot(*(start.loc[before.index] - before).to_numpy().T)
    assert moved.max() < 1.0, moved.max()


def test_free_mode_lets_marks_leave_the_curve_order():
    df = ordered_frame(30, seed=3)
    chart = uw.Chart(df, size="v", order="when", emitter=uw.CurveEmitter(S_CURVE, mode="free"),
                     forces=[uw.PointForce(600, 420)], boundary="open", fill=0.2, iterations=100)
    table = chart.layout()
    distance = cKDTree(bezier(S_CURVE)).query(table[["x", "y"]].to_numpy())[0]
    assert np.median(distance) > 0.5 * table["width"].mean()  # gathered at the force


def test_along_emitter_needs_a_curve_emitter():
    df = pd.DataFrame({"v": np.ones(5)})
    chart = uw.Chart(df, orientation="along_emitter", iterations=20)
    with pytest.raises(ValueError, match=r"orientation='along_emitter' needs a uw.CurveEmitter"):
        chart.layout()


# --- Curve and fit_bezier --------------------------------------------------------------

def test_curve_length_and_lookup_exact_on_a_straight_line():
    curve = Curve([[0, 0], [10, 0], [20, 0], [30, 0]])
    assert curve.length == pytest.approx(30.0, abs=1e-9)
    np.testing.assert_allclose(curve.at(np.array([0.0, 12.5, 30.0, 99.0])),
                               [[0, 0], [12.5, 0], [30, 0], [30, 0]], atol=1e-9)
    tangent, normal = curve.frame(np.array([15.0]))
    np.testing.assert_allclose(tangent, [[1, 0]], atol=1e-9)
    np.testing.assert_allclose(normal, [[0, 1]], atol=1e-9)


def test_curve_length_matches_the_definition():
    dense = bezier(TWO_SEGMENTS, 200001)
    truth = np.linalg.norm(np.diff(dense, axis=0), axis=1).sum()
    assert Curve(TWO_SEGMENTS).length == pytest.approx(truth, rel=1e-4)


def test_nearest_arc_finds_points_on_the_curve():
    curve = Curve(TWO_SEGMENTS)
    arcs = np.array([0.0, 100.0, 333.3, curve.length])
    found = curve.nearest_arc(curve.at(arcs))
    spacing = curve.length / (2 * 128)
    np.testing.assert_allclose(found, arcs, atol=spacing)


@pytest.mark.parametrize("points", [S_CURVE, TWO_SEGMENTS], ids=["one", "two"])
def test_fit_bezier_refits_points_sampled_from_a_known_curve(points):
    stroke = bezier(points, 301)[::3]                    # ~100 points along the curve
    fitted = fit_bezier(stroke, tolerance=2.0)
    assert fitted.ndim == 2 and fitted.shape[1] == 2 and (len(fitted) - 1) % 3 == 0
    np.testing.assert_allclose(fitted[0], stroke[0])               # the stroke's ends are kept
    np.testing.assert_allclose(fitted[-1], stroke[-1])
    # every stroke point lies within the tolerance of the fitted curve, and back
    fit_dense = bezier(fitted)
    assert cKDTree(fit_dense).query(stroke)[0].max() < 2.0
    assert cKDTree(bezier(points)).query(fit_dense)[0].max() < 2.0


def test_fit_bezier_splits_a_corner_into_more_segments():
    corner = np.concatenate([np.stack([np.linspace(0, 200, 50), np.zeros(50)], 1),
                             np.stack([np.full(50, 200.0), np.linspace(0, 200, 50)], 1)[1:]])
    fitted = fit_bezier(corner, tolerance=1.0)
    assert len(fitted) >= 7 and (len(fitted) - 1) % 3 == 0
    assert cKDTree(bezier(fitted)).query(corner)[0].max() < 1.0


def test_from_stroke_builds_a_curve_emitter():
    stroke = bezier(TWO_SEGMENTS, 401)[::4]
    emitter = CurveEmitter.from_stroke(stroke, tolerance=2.0, mode="band", speed=0.5)
    assert isinstance(emitter, CurveEmitter) and emitter.mode == "band" and emitter.speed == 0.5
    assert (len(emitter.points) - 1) % 3 == 0
    assert cKDTree(bezier(emitter.points)).query(stroke)[0].max() < 2.0


@pytest.mark.parametrize("points", [
    [[0, 0], [1, 1], [2, 2]],                       # 3 points
    [[0, 0], [1, 1], [2, 2], [3, 3], [4, 4]],       # 5 points
    [[0, 0], [1, 1], [2, 2], [3, 3], [4, 4], [5, 5]],
    [0, 1, 2, 3],                                   # not (k, 2)
])
def test_wrong_number_of_control_points(points):
    with pytest.raises(ValueError, match=r"cubic Bezier control points of shape \(3k \+ 1, 2\)"):
        uw.CurveEmitter(points)


def test_curve_emitter_other_errors():
    with pytest.raises(ValueError, match=r"zero length"):
        uw.CurveEmitter([[5, 5]] * 4)
    with pytest.raises(ValueError, match=r"finite"):
        uw.CurveEmitter([[0, 0], [1, np.nan], [2, 2], [3, 3]])
    with pytest.raises(ValueError, match=r"mode must be one of 'free', 'line', 'band'; got 'lines'"):
        uw.CurveEmitter(S_CURVE, mode="lines")
    with pytest.raises(ValueError, match=r"stroke must be an \(m, 2\) array"):
        CurveEmitter.from_stroke([[1, 2]])
    with pytest.raises(ValueError, match=r"all points coincide"):
        CurveEmitter.from_stroke([[1, 2], [1, 2], [1, 2]])


def test_curve_emitter_json_round_trip_and_drift():
    e = CurveEmitter(TWO_SEGMENTS, speed=2.0, direction="normal", mode="line")
    again = emitter_from_json(e.to_json())
    assert again == e and again.to_json()["points"] == [list(map(float, p)) for p in TWO_SEGMENTS]
    arc = np.array([10.0, 200.0])
    tangent, normal = e.curve.frame(arc)
    np.testing.assert_allclose(e.drift(arc), normal)
    np.testing.assert_allclose(CurveEmitter(TWO_SEGMENTS).drift(arc), tangent)
    np.testing.assert_allclose(CurveEmitter(TWO_SEGMENTS, direction=90).drift(arc), [[0, 1], [0, 1]],
                               atol=1e-12)
    with pytest.raises(ValueError, match=r"unknown kind 'spiral'"):
        emitter_from_json({"kind": "spiral"})


@pytest.mark.parametrize("seed", range(10))
def test_marks_emitted_high_above_the_floor_fall_all_the_way_down_to_it(seed):
    # the force weakens when the first marks come to rest, and a crowded pile below keeps the
    # steps small: a mark still falling must count as falling however small its steps (it goes
    # straight on), or the settle ends with marks in mid-air on some seeds and not others
    df = pd.DataFrame({"v": np.random.default_rng(1).uniform(1, 4, 40)})
    chart = uw.Chart(df, mark="star", size="v", canvas=(600, 500), boundary="open", fill=0.2,
                     container=uw.Container.rect(20, 20, 560, 460), seed=seed,
                     emitter=uw.CurveEmitter([(60, 40), (220, 30), (380, 50), (540, 40)]),
                     forces=[uw.DirectionalForce(90)])
    table = chart.layout()
    bottom = table.y + table.height / 2
    print(f"lowest mark bottom {bottom.max():.0f}, mean centre y {table.y.mean():.0f}")
    assert bottom.max() > 470                        # the pile reaches the floor at 480
    assert table.y.mean() > 300                      # and lies low: no marks left hanging
