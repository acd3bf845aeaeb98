"""Strata: a layer that blocks on another rests on it, and never sifts into the gaps between
its marks (issue 18, part 3): outside it in rings around a point force, above it under a
downward one, emitted from a grid or packed on a layer poured from an emitter."""
import math

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from envelope import below_envelope
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.prepare.scale import overfilled
from unitopia_widget.layout.step.strata import Radial, cone_distance, shadow, shadow_distance

pytestmark = pytest.mark.usefixtures("one_thread")

POINT = (200.0, 150.0)
BINS = 360   # angle bins of the envelope: 1 degree, under a small mark's width at its radius


def lognormal(n: int, spread: float, seed: int) -> np.ndarray:
    """n lognormal values rescaled so that max / min is exactly ``spread``."""
    logs = np.log(np.random.default_rng(seed).lognormal(0.0, 1.0, n))
    return np.exp((logs - logs.min()) / np.ptp(logs) * math.log(spread))


def polar(x, y, point=POINT):
    """(angle bin, radius) of canvas points from ``point``."""
    dx, dy = np.asarray(x) - point[0], np.asarray(y) - point[1]
    angle = np.arctan2(dy, dx) % (2 * math.pi)
    return np.minimum((angle / (2 * math.pi) * BINS).astype(int), BINS - 1), np.hypot(dx, dy)


def envelope(table, layer: str, point=POINT) -> np.ndarray:
    """``(BINS,)`` per angle bin around ``point``, the largest radius of a layer's ink (its
    discs) on the ray through the bin's middle; 0 in a bin without ink."""
    ray = (np.arange(BINS) + 0.5) / BINS * 2 * math.pi
    top = np.zeros(BINS)
    for x, y, w in table[table["layer"] == layer][["x", "y", "width"]].to_numpy():
        d, a = math.hypot(x - point[0], y - point[1]), math.atan2(y - point[1], x - point[0])
        off = d * np.sin(ray - a)                   # the ray's distance from the disc's centre
        far = d * np.cos(ray - a) + np.sqrt(np.maximum((w / 2) ** 2 - off ** 2, 0.0))
        top = np.where((np.abs(off) <= w / 2) & (far > 0), np.maximum(top, far), top)
    return top


def inside_envelope(table, lower: str, upper: str, point=POINT) -> float:
    """Share of layer ``upper``'s marks whose centre lies inside the envelope of ``lower``."""
    up = table[table["layer"] == upper]
    b, r = polar(up["x"], up["y"], point)
    return float(np.mean(r < envelope(table, lower, point)[b]))


@pytest.fixture(scope="module")
def rings():
    """Three layers around a point force, largest first, each blocking on the one before;
    linear sizes 4x from the first to the last (and 4x in area within each layer)."""
    torch.set_num_threads(1)
    k = np.repeat(np.arange(3), [12, 36, 108])    # enough to ring the layer below
    df = pd.DataFrame({"k": k, "v": lognormal(len(k), 4, 3) * 16.0 ** (-k / 2)})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open",
                     container=uw.Container.rect(10, 10, 380, 280),
                     forces=[uw.PointForce(*POINT)], iterations=300)
    for j in (1, 2):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    return chart.layout()


def test_rings_lie_in_layer_order_and_none_sifts_inside_the_one_it_blocks_on(rings):
    _, r = polar(rings["x"], rings["y"])
    mean = pd.Series(r).groupby(rings["layer"].to_numpy()).mean()
    assert mean["0"] < mean["1"] < mean["2"]
    worst = max(inside_envelope(rings, str(j - 1), str(j)) for j in (1, 2))
    assert worst <= 0.05, worst      # 9% of the smallest marks on main: in the largest's gaps


def test_the_radial_shadow_fills_the_room_between_the_ink_and_the_point():
    # one blob of ink to the right of the point: the shadow is the ink's cone to the point
    h, w = 60, 80
    ink = torch.zeros(h, w)
    yy, xx = torch.meshgrid(torch.arange(h) + 0.5, torch.arange(w) + 0.5, indexing="ij")
    ink[(xx - 60) ** 2 + (yy - 30) ** 2 <= 36] = 1.0
    shadow = Radial(((20.0, 30.0, 1.0),)).on((h, w), rho=1.0, pad=0, device="cpu")(ink)
    assert shadow[30, 40] > 0.9 and shadow[30, 25] > 0.9          # between the ink and the point
    assert shadow[30, 75] < 0.1 and shadow[30, 5] < 0.1           # beyond the ink, behind the point
    assert shadow[10, 40] < 0.1 and shadow[50, 40] < 0.1          # off the cone
    cone = cone_distance(torch.stack([xx.reshape(-1), yy.reshape(-1)], 1).double().numpy(),
                         np.array([60.0, 30.0]), 6.0, np.array([20.0, 30.0]))
    agree = (cone.reshape(h, w) < -1) == (shadow.numpy() > 0.5)   # the start's cone, well inside
    assert agree[(cone.reshape(h, w) < -1) | (cone.reshape(h, w) > 1)].mean() > 0.99


def test_the_radial_sweep_back_covers_what_lies_beyond_the_ink_from_the_point():
    # the same blob, swept out from the point (``out``): the ink's shadow cast away from it
    h, w = 60, 80
    ink = torch.zeros(h, w)
    yy, xx = torch.meshgrid(torch.arange(h) + 0.5, torch.arange(w) + 0.5, indexing="ij")
    ink[(xx - 60) ** 2 + (yy - 30) ** 2 <= 36] = 1.0
    back = Radial(((20.0, 30.0, 1.0),)).on((h, w), rho=1.0, pad=0, device="cpu")(ink, out=True)
    assert back[30, 75] > 0.9 and back[30, 62] > 0.9              # the ink and beyond it
    assert back[30, 40] < 0.1 and back[30, 5] < 0.1               # between it and the point
    assert back[5, 75] < 0.1 and back[55, 75] < 0.1               # off its angle


def test_several_point_piles_each_ring_their_own_point():
    # three piles apart, three layers each blocking on the one before: each point its own rings
    points = [(70.0, 100.0), (200.0, 100.0), (330.0, 100.0)]
    k = np.repeat(np.arange(3), [9, 27, 81])
    df = pd.DataFrame({"k": k, "v": lognormal(len(k), 4, 3) * 16.0 ** (-k / 2)})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 200), boundary="open", fill=0.35,
                     container=uw.Container.rect(5, 5, 390, 190),
                     forces=[uw.PointForce(*p) for p in points], iterations=300)
    for j in (1, 2):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    table = chart.layout()
    near = np.argmin([np.hypot(table["x"] - x, table["y"] - y) for x, y in points], axis=0)
    for p, point in enumerate(points):
        mine = table[near == p]
        assert mine["layer"].nunique() == 3                       # every pile has every layer
        assert max(inside_envelope(mine, str(j - 1), str(j), point) for j in (1, 2)) <= 0.05


def test_rings_poured_in_turn_from_an_emitter_around_the_point_rest_outside_each_other():
    # emitted layers see the shadow in the loss: poured in turn from a ring, each rests on the last
    k = np.repeat(np.arange(3), [12, 36, 108])
    df = pd.DataFrame({"k": k, "v": lognormal(len(k), 4, 3) * 16.0 ** (-k / 2)})
    turn = np.linspace(0, 2 * math.pi, 37)   # cubic Bezier control points along a circle
    ring = uw.CurveEmitter([(POINT[0] + 140 * math.cos(a), POINT[1] + 140 * math.sin(a)) for a in turn])
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open", emitter=ring,
                     container=uw.Container.rect(10, 10, 380, 280),
                     forces=[uw.PointForce(*POINT)], iterations=300)
    for j in (1, 2):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    table = chart.layout()
    assert max(inside_envelope(table, str(j - 1), str(j)) for j in (1, 2)) <= 0.05


def start_table(chart) -> pd.DataFrame:
    """The start of a chart (before solving) as a placements-like table: x, y, width
    (footprint discs at the start scale), layer."""
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu", scales=chart.scales)
    center = problem.placement.transforms()[0].detach().numpy().astype(float)
    width = 2 * np.sqrt(units.area / math.pi) * problem.group_scale[0]
    return pd.DataFrame({"x": center[:, 0], "y": center[:, 1], "width": width,
                         "layer": [chart.layers[i].name for i in units.layer]})


@pytest.mark.parametrize("pull", ["down", "point"])
def test_a_grid_emitted_layer_starts_and_rests_beyond_the_layer_it_blocks_on(pull):
    # a packed pile, and a grid of small marks blocking on it: the grid once covered the pile
    k = np.repeat([0, 1], [30, 60])
    df = pd.DataFrame({"k": k, "v": np.where(k == 0, lognormal(90, 6, 1), 0.5)})
    force = uw.DirectionalForce(90) if pull == "down" else uw.PointForce(*POINT)
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open",
                     container=uw.Container.rect(10, 10, 380, 280), forces=[force], iterations=300)
    chart.layer("1").set(emitter=uw.GridEmitter(), blocks=["0"])
    share = below_envelope if pull == "down" else inside_envelope
    assert share(start_table(chart), "0", "1") == 0.0      # 45% (down), 48% (point) on main
    assert share(chart.layout(), "0", "1") <= 0.05         # 30%, 15% on main


def test_layers_of_alike_sizes_start_each_above_the_one_it_blocks_on():
    # each layer's sizes too alike to be packed by size (they start on a lattice): the third
    # and fourth layers once started on the floor, under the first
    k = np.repeat(np.arange(4), 30)
    df = pd.DataFrame({"k": k, "v": lognormal(120, 2, 3) * 4.0 ** -k})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open",
                     container=uw.Container.polygon([(50, 20), (350, 20), (310, 285), (90, 285)]),
                     forces=[uw.DirectionalForce(90)])
    for j in (1, 2, 3):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    start = start_table(chart)
    assert [below_envelope(start, str(j - 1), str(j)) for j in (1, 2, 3)] == [0.0, 0.0, 0.0]
    mean = start.groupby("layer")["y"].mean()
    assert mean["0"] > mean["1"] > mean["2"] > mean["3"]


def test_a_packed_layer_resting_on_an_emitted_one_stays_above_it():
    # the lower layer poured from a curve at the top, the upper packed: once started at the
    # floor, where the poured marks would rest, and stayed there
    k = np.repeat([0, 1], [16, 32])
    df = pd.DataFrame({"k": k, "v": lognormal(48, 6, 1) * np.where(k == 0, 1.0, 0.4)})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open", fill=0.2,
                     container=uw.Container.rect(10, 10, 380, 280),
                     forces=[uw.DirectionalForce(90)], iterations=1000)
    chart.layer("0").set(emitter=uw.CurveEmitter([(40, 30), (150, 20), (250, 40), (360, 30)]))
    chart.layer("1").set(blocks=["0"])
    table = chart.layout()
    mean = table.groupby("layer")["y"].mean()
    assert mean["0"] > mean["1"]                           # 259 < 265 on main
    assert below_envelope(table, "0", "1") <= 0.05         # 6% on main


def test_piles_grown_into_one_another_block_the_gaps_on_the_border_between_them():
    # two points 60 px apart, a disc of ink either side of the border (x = 50) with a gap
    # across it: each pile's sweep sees the other's ink within a band past its cell
    h, w = 60, 100
    yy, xx = torch.meshgrid(torch.arange(h) + 0.5, torch.arange(w) + 0.5, indexing="ij")
    ink = (((xx - 45) ** 2 + (yy - 30) ** 2 <= 16) | ((xx - 57) ** 2 + (yy - 30) ** 2 <= 16)).float()
    points = ((20.0, 30.0, 1.0), (80.0, 30.0, 1.0))
    apart = Radial(points).on((h, w), rho=1.0, pad=0, device="cpu")(ink)
    grown = Radial(points, band=6.0).on((h, w), rho=1.0, pad=0, device="cpu")(ink)
    gap = [(30, 50), (30, 51)]                    # (row, column) either side of the border
    assert all(apart[p] < 0.1 for p in gap)       # each side sees only its own cell's ink
    assert all(grown[p] > 0.9 for p in gap)
    assert grown[30, 10] < 0.1 and grown[10, 50] < 0.1 and grown[30, 90] < 0.1   # beyond, off
    # the start's cones agree: the gap is taken once the band reaches the other disc
    xy = np.array([[50.5, 30.5], [51.5, 30.5], [50.5, 10.5]])
    discs, radii = np.array([[45.5, 30.5], [57.5, 30.5]]), np.array([4.0, 4.0])
    assert (shadow_distance(xy, Radial(points), discs, radii)[:2] > 0).all()
    assert (shadow_distance(xy, Radial(points, band=6.0), discs, radii) < 0).tolist() == \
        [True, True, False]


@pytest.mark.parametrize("dim, reverse", [(0, False), (0, True), (1, False), (1, True)])
def test_a_shadow_holds_the_ink_at_or_before_each_pixel_along_its_sweep_summed_up_to_one(dim, reverse):
    """Down, up, right and left, on two slabs at once: the running sum along the raster axis,
    clamped at a full pixel; on ink of whole pixels, the running maximum (below the
    envelope). 37 rows: the scan down the columns runs in blocks (``SCAN_BLOCK``), so
    the sums carry across two block borders and a padded last block."""
    rng = torch.Generator().manual_seed(dim + 2 * reverse)
    ink = torch.rand(2, 37, 21, generator=rng) * 0.1
    ink[1] = (torch.rand(37, 21, generator=rng) > 0.8).to(ink.dtype)   # whole pixels
    ref = ink.numpy()
    if reverse:
        ref = np.flip(ref, dim + 1)
    ref = np.minimum(np.cumsum(ref, axis=dim + 1), 1.0)
    if reverse:
        ref = np.flip(ref, dim + 1)
    out = shadow(ink, dim, reverse).numpy()
    np.testing.assert_allclose(out, ref, rtol=1e-6, atol=1e-6)
    whole = np.flip(ink[1].numpy(), dim) if reverse else ink[1].numpy()
    whole = np.maximum.accumulate(whole, axis=dim)
    np.testing.assert_array_equal(out[1], np.flip(whole, dim) if reverse else whole)
    assert (out[0] < 1.0).any() and (out[0] == 1.0).any()   # the sum fills up along the sweep


@pytest.mark.parametrize("sees_ink", [False, True])
def test_a_stacks_obstacles_are_the_shadows_of_the_layers_below_call_after_call(sees_ink):
    """``CanvasTerms.obstacles`` on three layers, each resting on those below it, down the
    columns of 37-row slabs (not whole scan blocks): row a is the shadow of the ink of the
    layers below a, clamped at a full pixel; the bottom layer's row is 0. The obstacle and
    the padded ink are buffers kept between calls: a second call on other coverage gives
    its own shadows, nothing of the first. With a layer that also sees another's ink itself,
    that ink is added."""
    from unitopia_widget.layout.step.losses import CanvasTerms
    h, w = 37, 21
    zeros = torch.zeros(3, h * w)
    rests = torch.tensor([[0.0, 0, 0], [1, 0, 0], [1, 1, 0]])
    blocks = torch.zeros(3, 3)
    if sees_ink:
        blocks[0, 2] = 1.0   # the bottom layer sees the top layer's ink itself
    terms = CanvasTerms(penalty=zeros, outside=zeros, inside=zeros, blocks=blocks, rests=rests,
                        sweeps=((0, False),) * 3, shape=(h, w))
    rng = torch.Generator().manual_seed(7)
    for _ in range(2):
        own = torch.rand(3, h * w, generator=rng) * (torch.rand(3, h * w, generator=rng) > 0.7)
        got = terms.obstacles(own).clone()
        ref = blocks @ own
        for a in (1, 2):
            ink = (rests[a] @ own).clamp(max=1.0).view(h, w)
            ref[a] += torch.from_numpy(np.minimum(np.cumsum(ink.numpy(), axis=0), 1.0).reshape(-1))
        np.testing.assert_allclose(got.numpy(), ref.numpy(), rtol=1e-6, atol=1e-6)
        assert (got[1] > 0).any() and (got[2] == 1.0).any()
        assert sees_ink or not got[0].any()


@pytest.mark.parametrize("sees_ink", [False, True])
def test_radial_shadows_read_at_the_samples_are_the_whole_shadows_there(sees_ink):
    """``CanvasTerms.obstacles(own, flat)`` (the loss's read: the radial shadows resampled at
    the samples' pixels alone) equals the whole obstacle read at ``flat``, to the bit, call
    after call: a stack of three layers swept in to two points, with ink at the raster's
    corners and borders (where the rays' samples are cut to those that reach the raster)."""
    from unitopia_widget.layout.step.losses import CanvasTerms
    h, w = 45, 70
    zeros = torch.zeros(3, h * w)
    rests = torch.tensor([[0.0, 0, 0], [1, 0, 0], [1, 1, 0]])
    blocks = torch.zeros(3, 3)
    if sees_ink:
        blocks[0, 2] = 1.0
    sweep = Radial(((10.0, 30.0, 1.0), (55.0, 12.0, 2.0)), band=3.0).on((h, w), 1.0, 0, "cpu")
    terms = CanvasTerms(penalty=zeros, outside=zeros, inside=zeros, blocks=blocks, rests=rests,
                        sweeps=(None, sweep, sweep), shape=(h, w))
    rng = torch.Generator().manual_seed(3)
    for _ in range(2):
        own = torch.rand(3, h * w, generator=rng) * (torch.rand(3, h * w, generator=rng) > 0.6)
        own.view(3, h, w)[:, [0, -1]] = 1.0   # the borders inked
        flat = torch.randint(0, 3 * h * w, (4000,), generator=rng)
        whole = terms.obstacles(own).reshape(-1).index_select(0, flat)
        at = terms.obstacles(own, flat)
        assert torch.equal(at, whole)
        assert (at[flat >= h * w] > 0.5).sum() > 1000 and (at[flat < h * w] == 0).all() != sees_ink


def test_independent_scales_that_overfill_one_container_warn_and_name_the_fill():
    """Three open layers stacked in one box under ``scales="independent"``: each alone covers
    the default fill (0.5) of it, 150% in all, which warns and names ``fill=``; fills that add
    up to 75%, or one shared scale, do not warn."""
    import warnings
    df = pd.DataFrame({"k": np.repeat([0, 1, 2], 10), "v": np.linspace(1.0, 2.0, 30)})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open", iterations=20,
                     container=uw.Container.rect(20, 20, 360, 260), scales="independent",
                     forces=[uw.DirectionalForce(90)])
    for j in (1, 2):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    with pytest.warns(UserWarning, match=r"layers \['0', '1', '2'\] share one container under "
                                         r"scales='independent'.*150% of the container.*fill="):
        chart.layout()
    for j in range(3):
        chart.layer(str(j)).set(fill=0.25)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        chart.layout()
    assert not [w for w in caught if "share one container" in str(w.message)]
    assert overfilled(chart.layers, "shared") == []
    for j in range(3):
        chart.layer(str(j)).set(fill=None)
    assert overfilled(chart.layers, "shared") == [] \
        and overfilled(chart.layers, "independent") == [(["0", "1", "2"], 1.5)]


def test_rows_added_to_the_top_stratum_alone_pour_in_a_warm_run():
    # three layers poured in turn from a grid; a warm run holds back only the rows added, so
    # the middle stage is empty: the next stage with units is poured (it stopped at the empty one)
    k = np.repeat(np.arange(3), [20, 20, 20])
    df = pd.DataFrame({"k": k, "v": lognormal(len(k), 2, 4)})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open", fill=0.3,
                     emitter=uw.GridEmitter(), container=uw.Container.rect(10, 10, 380, 280),
                     forces=[uw.DirectionalForce(90)], iterations=200)
    for j in (1, 2):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    chart.layout()
    chart.set_data(pd.concat([df, pd.DataFrame({"k": [2, 2], "v": [2.0, 3.0]})], ignore_index=True))
    table = chart.layout()
    assert len(table) == 62 and chart.result.phases.get("settle.pour", 0) >= 1
    top = table[table.layer == "2"]
    assert (top.y < table[table.layer == "1"].y.mean()).mean() > 0.9   # the added rows on top too
