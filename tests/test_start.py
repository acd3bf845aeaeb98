"""The size-aware start (pack.py) and the controller decisions it relies on (issue 11, 13)."""
import math
import warnings

import numpy as np
import pandas as pd
import pytest
import torch
from scipy.spatial.distance import pdist, squareform
from scipy.stats import spearmanr

import unitopia_widget as uw
from envelope import below_envelope
from ink import ink_metrics
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.prepare.scale import initial_scale
from unitopia_widget.layout.prepare.lattice import Region
from unitopia_widget.layout.prepare.pack import Packing, packable, rows
from unitopia_widget.layout.rules.measure_room import coverage, room
from unitopia_widget.layout.step.scales import Scales

pytestmark = pytest.mark.usefixtures("one_thread")


def lognormal(n: int, spread: float, seed: int) -> np.ndarray:
    """n lognormal values rescaled so that max / min is exactly ``spread``."""
    logs = np.log(np.random.default_rng(seed).lognormal(0.0, 1.0, n))
    return np.exp((logs - logs.min()) / np.ptp(logs) * math.log(spread))


def disc_gaps(center: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Pairwise ``(n, n)`` distance between disc edges (negative: they overlap); inf on the diagonal."""
    gap = squareform(pdist(center)) - radius[:, None] - radius[None, :]
    np.fill_diagonal(gap, np.inf)
    return gap


def start_of(chart):
    """(problem, start centres (N, 2), footprint radii (N,)) of a chart, before solving."""
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu", scales=chart.scales)
    center = problem.placement.transforms()[0].detach().numpy().astype(float)
    return problem, units, center, np.sqrt(units.area / math.pi) * problem.group_scale[0]


def test_packing_puts_spread_discs_largest_first_into_the_gaps_without_overlap():
    inside = np.zeros((200, 300), np.float32)
    inside[20:180, 30:270] = 1.0
    region = Region(inside, 1.0)
    radius = np.sort(lognormal(60, 30, 0))[::-1] ** 0.5 * 3.5   # discs cover half the region
    pack = Packing(region, 0.3 * float(np.median(radius)), float(radius.max()))
    cost = np.hypot(pack.points[:, 0] - 150, pack.points[:, 1] - 100)
    center, fitted = pack.place(radius, cost, np.arange(len(radius)))
    assert fitted
    assert disc_gaps(center, radius).min() >= -1e-6                   # no two discs overlap
    assert (region.depth_at(center) >= radius - 1.0).all()            # each inside (raster px)
    spot = np.hypot(center[:, 0] - 150, center[:, 1] - 100)
    assert spot[0] < 1.0                                              # the largest at the centre
    assert spot[-10:].max() > 2 * spot[:5].max()                      # the small ones around


def test_a_packing_asked_only_whether_all_fit_stops_at_the_first_miss():
    inside = np.zeros((100, 100), np.float32)
    inside[10:90, 10:90] = 1.0
    radius = np.full(40, 12.0)                # 40 discs of radius 12 cannot fit in 80 x 80
    cost = lambda pack: np.zeros(len(pack.points))   # noqa: E731
    full = Packing(Region(inside, 1.0), 3.0, 12.0)
    center, fitted = full.place(radius, cost(full), np.arange(40))
    missed = Packing(Region(inside, 1.0), 3.0, 12.0)
    early, answer = missed.place(radius, cost(missed), np.arange(40), until_miss=True)
    assert not fitted and not answer
    placed = int(np.flatnonzero(~early.any(axis=1))[0])   # the first disc left unplaced
    assert 0 < placed < 40
    np.testing.assert_array_equal(early[:placed], center[:placed])   # the same spots till then
    assert not early[placed:].any() and center[placed:].any()
    assert (missed.clear == missed.depth).all()          # its clearances are left untouched


def test_only_compact_marks_with_spread_sizes_are_packed_by_size():
    half = np.ones(3)
    assert packable(np.array([1.0, 2.0, 3.0]), half, half)
    assert not packable(np.array([1.0, 1.2, 1.4]), half, half)            # nearly equal: lattice
    assert not packable(np.array([1.0, 2.0, 3.0]), half * 0.1, half)      # thin strands: lattice


def test_a_closed_layer_with_spread_sizes_starts_packed_at_a_scale_its_packing_holds():
    df = pd.DataFrame({"v": lognormal(80, 10, 1)})
    chart = uw.Chart(df, size="v", canvas=(400, 300), boundary="closed",
                     container=uw.Container.ellipse(200, 150, 150, 110))
    problem, units, center, radius = start_of(chart)
    # the lattice start overlaps spread sizes, and so does packing at the loose 75% scale
    assert disc_gaps(center, radius).min() > -0.05 * radius.min()
    loose = initial_scale(units, chart.layers, chart.canvas)[0][0]
    # scattered (start.pack_layer), it packs a little looser than largest first from the centre
    assert 0.85 * loose < problem.group_scale[0] < loose
    inside = ((center[:, 0] - 200) / 150) ** 2 + ((center[:, 1] - 150) / 110) ** 2 <= 1
    assert inside.all()


def test_blocked_layers_without_an_emitter_start_and_end_stacked_in_two_piles():
    df = pd.DataFrame({"k": np.repeat(np.arange(3), 15), "v": lognormal(45, 8, 1)})
    vessel = uw.Container.polygon([(20, 20), (40, 280), (190, 280), (200, 150), (210, 150),
                                   (220, 280), (370, 280), (390, 20)])
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open", container=vessel,
                     forces=[uw.DirectionalForce(90)])
    for k in (1, 2):
        chart.layer(str(k)).set(blocks=[str(k - 1)])
    _, units, center, radius = start_of(chart)
    start_y = [center[units.layer == k, 1].mean() for k in range(3)]
    assert start_y[0] > start_y[1] > start_y[2]                       # each starts above the last
    assert disc_gaps(center, radius).min() > -0.05 * radius.min()
    table = chart.layout()
    end_y = table.groupby("layer")["y"].mean()
    assert end_y["0"] > end_y["1"] > end_y["2"]
    lefts = table[table["x"] < 200]["layer"].nunique()
    assert lefts == 3 and table[table["x"] > 210]["layer"].nunique() == 3   # both piles stacked


def test_stacked_layers_rest_in_strata_though_the_last_are_four_times_smaller():
    # largest first: the small marks once sifted through the gaps between the big ones
    k = np.repeat(np.arange(4), 14)
    df = pd.DataFrame({"k": k, "v": lognormal(56, 4, 2) * 16.0 ** (-k / 3)})
    vessel = uw.Container.polygon([(20, 20), (40, 280), (190, 280), (200, 150), (210, 150),
                                   (220, 280), (370, 280), (390, 20)])
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open", container=vessel,
                     forces=[uw.DirectionalForce(90)], iterations=300)
    for j in (1, 2, 3):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    table = chart.layout()
    end_y = table.groupby("layer")["y"].mean()
    assert end_y["0"] > end_y["1"] > end_y["2"] > end_y["3"]
    assert max(below_envelope(table, str(j - 1), str(j)) for j in (1, 2, 3)) <= 0.05


# six thin arms: a footprint (its ink) that packs far less densely than a disc
FLAKE = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-50 -50 100 100"><g stroke="#4a90c8" '
         'stroke-width="6" stroke-linecap="round">' + "".join(
             f'<line x1="0" y1="0" x2="{46 * math.cos(a):.1f}" y2="{46 * math.sin(a):.1f}"/>'
             for a in np.arange(6) * math.pi / 3) + "</g></svg>")
TUB = [(40, 30), (360, 30), (340, 280), (60, 280)]


def test_an_open_stack_of_spiky_marks_at_the_default_fill_settles_without_shrinking_to_a_third():
    # ink covering half the tub is more than six-armed marks pack into: the start overflowed
    # it and the legalising rounds shrank the marks to 0.31 of their start, strewn about.
    # The kept share varies by seed (0.68 to 0.85 over seeds 0 to 4): judged over three
    k = np.repeat([0, 1, 2], [12, 24, 48])
    df = pd.DataFrame({"k": k, "v": np.random.default_rng(1).uniform(1, 2, len(k)) * 4.0 ** -k})
    kept = []
    for seed in range(3):
        chart = uw.Chart(df, mark=uw.Mark.svg(FLAKE), size="v", by="k", canvas=(400, 300), seed=seed,
                         container=uw.Container.polygon(TUB), boundary="open",
                         forces=[uw.DirectionalForce(90)])
        for j in (1, 2):
            chart.layer(str(j)).set(blocks=[str(j - 1)])
        table = chart.layout()
        start, end = chart.frames[0][:, 3], chart.result.unit_scale
        kept.append(end.min() / start.max())
        end_y = table.groupby("layer")["y"].mean()
        assert end_y["0"] > end_y["1"] > end_y["2"]
        assert ink_metrics(chart.to_svg(legend=False), (400, 300))["overlap"] < 0.01
    assert min(kept) >= 0.6 and np.mean(kept) >= 0.7, kept      # 0.68 0.83 0.81 (was 0.31)


@pytest.mark.parametrize("fill", [0.2, 0.6])
def test_an_open_fill_its_marks_cannot_pack_is_lowered_with_a_warning(fill):
    df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1, 3, 80)})
    chart = uw.Chart(df, mark="star", size="v", canvas=(400, 300), seed=0, fill=fill,
                     container=uw.Container.polygon(TUB), boundary="open",
                     forces=[uw.DirectionalForce(90)])
    problem, units, _, _ = start_of(chart)
    area = Region(chart.layers[0].region.coverage((400, 300), 1.0), 1.0).area
    start = float(units.area.sum()) * problem.group_scale[0] ** 2 / area   # the ink's share
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        chart.layout()
    said = [str(w.message) for w in caught if "fill=" in str(w.message)]
    if fill == 0.2:
        assert not said and start == pytest.approx(0.2, rel=1e-6)
    else:
        # stars settle into about 0.4 of the tub; their footprints pack into 0.32 at the start
        assert 0.25 < start < 0.45
        assert len(said) == 1 and "fill=0.6 is more than" in said[0], said
        assert "footprints" in said[0] and "Lower fill=" in said[0]
        lowered = float(said[0].split("laid out at fill=")[1].split(":")[0])
        reached = float(units.area.sum()) * chart.result.scale ** 2 / area
        assert 0.25 < lowered < 0.5 and lowered == pytest.approx(reached, abs=0.01)


def test_unequal_sizes_settle_in_about_as_many_iterations_as_equal_ones():
    def settle(values):
        chart = uw.Chart(pd.DataFrame({"v": values}), size="v", canvas=(720, 415), seed=0,
                         container=uw.Container.ellipse(360, 207, 200, 200), boundary="open",
                         forces=[uw.PointForce(360, 407)], fill=0.6)
        table = chart.layout()
        gap = disc_gaps(table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2)
        return chart.result.phases["settle"], max(-gap.min(), 0.0) / (table["width"].min() / 2)

    equal, _ = settle(np.ones(200))
    unequal, dent = settle(np.random.default_rng(0).uniform(1, 10, 200))
    # the settle's iterations: 49 against 32 on a Xeon; on an AMD EPYC 111 against 32 (36 at
    # seeds 2 and 3): the pile still compacts, marks creeping on at the steps' pace and clear
    # of their neighbours at the window's end, so ``rules.rest`` counts them as falling (ending
    # the settle sooner left corpus piles looser: RESULTS.md). A fixed widening of the pile's
    # room once took 314; the polish is not compared: equal discs, which the raster resolves,
    # end it faster
    assert unequal <= 4 * equal
    assert dent < 0.15, dent              # the deepest overlap, in smallest radii: under a raster px


def test_a_shared_scale_has_no_room_while_one_of_its_containers_is_full():
    df = pd.DataFrame({"bag": ["a"] * 20 + ["b"] * 4, "v": lognormal(24, 20, 2)})
    chart = uw.Chart(df, size="v", by="bag", canvas=(400, 300), boundary="closed", piles=None)
    chart.layer("a").set(container=uw.Container.rect(10, 10, 180, 280))
    chart.layer("b").set(container=uw.Container.rect(210, 10, 180, 280))
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu")
    ctl = Scales(problem)
    inside = problem.terms.inside.numpy()
    full_a = torch.as_tensor(np.nonzero(inside[0] >= 0.5)[0])      # ink over all of bag a
    ink = torch.ones(len(full_a))
    assert not room(problem, ctl, coverage(problem, ink, full_a))[0]             # a is full: no growth
    nothing = torch.zeros(0, dtype=torch.long)
    assert room(problem, ctl, coverage(problem, torch.zeros(0), nothing))[0]     # both empty: room


def test_marks_too_few_to_fill_a_closed_container_spread_over_it():
    # a shared scale held by the fuller bag: the 12 marks of bag b cover a fifth of it
    df = pd.DataFrame({"bag": ["a"] * 60 + ["b"] * 12, "v": lognormal(72, 20, 2)})
    chart = uw.Chart(df, size="v", by="bag", canvas=(400, 300), boundary="closed", piles=None)
    chart.layer("a").set(container=uw.Container.rect(10, 10, 180, 280))
    chart.layer("b").set(container=uw.Container.rect(210, 10, 180, 280))
    problem, units, center, radius = start_of(chart)
    b = units.layer == 1
    assert (np.pi * radius[b] ** 2).sum() < 0.3 * 180 * 280
    x, y = center[b].T
    assert np.ptp(x) > 0.6 * 180 and np.ptp(y) > 0.6 * 280             # from edge to edge
    assert disc_gaps(center[b], radius[b]).min() > 0                   # none touching


def test_an_open_pile_emitted_onto_a_seesaw_legalises_below_one_percent():
    df = pd.DataFrame({"kind": ["work"] * 40 + ["life"] * 40, "hours": lognormal(80, 10, 6)})
    seesaw = uw.Container.polygon([(40, 40), (760, 40), (760, 380), (40, 500)])
    chart = uw.Chart(df, mark="star", size="hours", by="kind", container=seesaw,
                     canvas=(800, 600), forces=[uw.DirectionalForce(90)], boundary="open", seed=0)
    chart.layer("work").set(emitter=uw.CurveEmitter([(80, 60), (200, 40), (300, 60), (380, 50)]))
    chart.layer("life").set(emitter=uw.CurveEmitter([(420, 50), (520, 40), (620, 60), (740, 50)]),
                            blocks=["work"])
    chart.layout()
    m = ink_metrics(chart.to_svg(legend=False), chart.canvas, k=1)
    assert m["overlap"] < 0.01           # 1.24% when fixed scales shrank by the overlap alone


def test_thin_marks_are_laid_in_rows_along_the_container_without_overlap():
    inside = np.zeros((120, 340), np.float32)
    inside[10:110, 20:320] = 1.0
    region = Region(inside, 1.0)
    assert abs(region.axis()) < 0.01                                   # a wide box: along x
    assert abs(abs(Region(inside.T.copy(), 1.0).axis()) - math.pi / 2) < 0.01
    length = np.linspace(40, 120, 20)
    center = rows(region, length, np.full(20, 4.0), region.axis(), np.arange(20))
    ends = np.concatenate([center - [[l / 2, 0] for l in length], center + [[l / 2, 0] for l in length]])
    assert ((ends[:, 0] >= 19) & (ends[:, 0] <= 321)).all()           # every rod inside
    for y in np.unique(center[:, 1]):                                  # rods in a row: end to end
        row = np.nonzero(center[:, 1] == y)[0]
        lo, hi = center[row, 0] - length[row] / 2, center[row, 0] + length[row] / 2
        order = np.argsort(lo)
        assert (lo[order][1:] >= hi[order][:-1] - 1e-6).all()
    assert len(np.unique(center[:, 1])) > 1


def test_thin_marks_fill_every_row_of_an_ellipse_evenly_longest_in_the_widest():
    yy, xx = np.mgrid[0:200, 0:400] + 0.5
    inside = ((((xx - 200) / 190) ** 2 + ((yy - 100) / 90) ** 2) <= 1).astype(np.float32)
    region = Region(inside, 1.0)
    length = lognormal(60, 8, 2) * 12
    center = rows(region, length, np.full(60, 3.0), region.axis(), np.arange(60))
    ys = np.unique(np.round(center[:, 1], 6))
    gap = float(np.diff(ys).min())
    assert ys.min() < 10 + gap and ys.max() > 190 - gap                # top and bottom rows in use
    assert np.allclose(np.diff(ys), gap, atol=1e-6)                   # evenly spaced, none skipped
    longest = int(np.argmax(length))
    assert abs(center[longest, 1] - 100) <= gap                       # the longest in a middle row
    shares = []
    for y in ys:                                                       # each row about as full
        row = np.abs(center[:, 1] - y) < 1e-6
        width = 2 * 190 * math.sqrt(max(1 - ((y - 100) / 90) ** 2, 0))
        shares.append(length[row].sum() / width)
    assert max(shares) - min(shares) < 0.5


def test_thin_marks_in_a_row_lie_in_their_start_order_not_by_length():
    """Laid longest first, every row graded from its long marks at one end to its short ones
    at the other (a pattern the data does not hold: Spearman rho of length against the place
    along the row, -0.98); in their start order, none."""
    yy, xx = np.mgrid[0:200, 0:400] + 0.5
    inside = ((((xx - 200) / 190) ** 2 + ((yy - 100) / 90) ** 2) <= 1).astype(np.float32)
    region = Region(inside, 1.0)
    length = lognormal(80, 9, 2) * 10
    ranks = np.random.default_rng(4).permutation(80)
    center = rows(region, length, np.full(80, 3.0), region.axis(), ranks)
    along = np.zeros(80)
    for y in np.unique(np.round(center[:, 1], 6)):   # the place along its row, 0 to 1
        row = np.nonzero(np.abs(center[:, 1] - y) < 1e-6)[0]
        along[row] = np.argsort(np.argsort(center[row, 0])) / max(len(row) - 1, 1)
        assert np.array_equal(row[np.argsort(center[row, 0])], row[np.argsort(ranks[row])])
    assert abs(spearmanr(length, along)[0]) < 0.25


def test_thin_marks_start_in_rows_cut_at_a_neck_not_across_it():
    """Two discs joined by a narrow neck: no mark starts across the neck (pulled into both
    discs, one laid across it poked out there), while a plain ellipse's rows are whole."""
    from unitopia_widget.layout.prepare.pack import necks
    yy, xx = np.mgrid[0:200, 0:400] + 0.5
    twins = ((np.hypot(xx - 105, yy - 100) <= 95) | (np.hypot(xx - 295, yy - 100) <= 95)
             | ((np.abs(xx - 200) <= 12) & (np.abs(yy - 100) <= 10))).astype(np.float32)
    region = Region(twins, 1.0)
    length = np.full(50, 70.0)
    center = rows(region, length, np.full(50, 3.0), 0.0, np.arange(50))
    lo, hi = center[:, 0] - 35, center[:, 0] + 35
    assert not ((lo < 200) & (hi > 200)).any()                        # none across the neck
    assert (hi < 200).sum() >= 20 and (lo > 200).sum() >= 20          # both discs in use
    ellipse = np.sqrt(np.clip(1 - np.linspace(-1, 1, 201) ** 2, 0, None)) * 90
    assert necks(ellipse) == [] and len(necks(region.depth[100] / region.rho)) == 1


def test_turnable_strands_start_along_a_wide_container():
    df = pd.DataFrame({"length": lognormal(30, 4, 3)})
    strand = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 80">'
                         '<rect width="4" height="80"/></svg>')
    chart = uw.Chart(df, mark=strand, height="length", rotate=True, canvas=(400, 300),
                     boundary="closed", container=uw.Container.ellipse(200, 150, 180, 90))
    problem, units, center, _ = start_of(chart)
    angle = problem.placement.transforms()[1].detach().numpy()
    assert np.allclose(np.abs(angle), math.pi / 2, atol=0.02)          # upright boxes lie flat


@pytest.mark.parametrize("margin", [0.0, 0.2])
def test_tied_large_marks_start_scattered_among_the_small_ones(margin):
    """20 large discs (20x the area) among 120 small ones in a closed ellipse start at random
    spots, few touching, no nearer the centre than the small ones: packed from the centre out
    they sat in the middle (44 contacts), and with a margin of 0.2 the holes of their own
    lattice read as empty. (Each mark keeps its own margin.)"""
    df = pd.DataFrame({"v": np.repeat([1.0, 20.0], [120, 20])})
    chart = uw.Chart(df, size="v", canvas=(400, 300), boundary="closed", margin=margin,
                     margin_of="own", container=uw.Container.ellipse(200, 150, 180, 130))
    problem, units, center, radius = start_of(chart)
    big = units.area > 2 * units.area.min()
    contacts = (disc_gaps(center[big], radius[big] * (1 + margin)) < 0.5 * radius[~big].mean()).sum() / 2
    far = np.hypot(center[:, 0] - 200, center[:, 1] - 150)
    print(f"margin {margin}: {contacts:g} contacts, mean distance large {far[big].mean():.1f} "
          f"small {far[~big].mean():.1f}")
    # (a large disc's centre keeps its radius from the rim: a little nearer the centre)
    assert contacts < big.sum() and far[big].mean() > 0.85 * far[~big].mean()


def test_a_pile_of_spread_sizes_starts_pressed_and_settles_soon_and_mixed():
    """400 discs of areas spread 10x poured into a disc, open, under a point force at its
    bottom: scattered at random spots, the start was loose, and marks crept into its gaps for
    hundreds of iterations (Table 1 at 1,000: 756 to 940). Pressed on their discs first, the
    start is a pile: no disc in another, sizes still mixed, and the settle ends early."""
    df = pd.DataFrame({"v": np.random.default_rng(5).uniform(1, 10, 400)})
    chart = uw.Chart(df, size="v", canvas=(400, 300), seed=0, boundary="open", fill=0.6,
                     container=uw.Container.ellipse(200, 150, 140, 140),
                     forces=[uw.PointForce(200, 290)], iterations=600)
    _, units, center, radius = start_of(chart)
    assert disc_gaps(center, radius).min() > -0.05 * radius.min()
    distance = np.hypot(center[:, 0] - 200, center[:, 1] - 290)
    rho = spearmanr(units.area, distance).statistic
    print(f"start: rho of size against distance {rho:+.3f}, mean distance {distance.mean():.1f}")
    assert abs(rho) <= 0.2
    chart.layout()
    print(f"settled in {chart.result.phases['settle']} iterations")
    assert chart.result.phases["settle"] <= 150

