"""Surface: a mark buried in its stratum's obstacle (a large mark of a lower layer rolled over
it) is lifted back onto the surface against its pull, or a little aside where a wall is in
the way, lowest stratum first (issue 18, part 3); a mark on the surface, or one no spot
clears, stays."""
import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from envelope import below_envelope
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind
from unitopia_widget.layout.step.losses import CanvasTerms
from unitopia_widget.layout.solver import solve
from unitopia_widget.layout.step.strata import Radial
from unitopia_widget.layout.rules.resurface import against, buried, strata_order

pytestmark = pytest.mark.usefixtures("one_thread")

H = W = 40


def square(unit: int, rows: range, cols: range):
    """Samples of a solid square of alpha 1: ``(values, index, owner)``."""
    index = [r * W + c for r in rows for c in cols]
    return np.ones(len(index)), np.array(index), np.full(len(index), unit)


def stack_terms(outside=None) -> CanvasTerms:
    """Three layers on a ``(H, W)`` raster under a downward pull: 1 rests on 0, 2 on both."""
    rests = torch.tensor([[0, 0, 0], [1, 0, 0], [1, 1, 0]], dtype=torch.float64)
    zero = torch.zeros(3, H * W, dtype=torch.float64)
    return CanvasTerms(penalty=zero, outside=zero if outside is None else outside, inside=zero,
                       blocks=torch.zeros(3, 3, dtype=torch.float64), rests=rests,
                       sweeps=(None, (0, False), (0, False)), shape=(H, W))


def lifts_of(terms, squares, layer, rho=0.5):
    values, index, owner = (torch.as_tensor(np.concatenate(part)) for part in zip(*squares))
    center = np.zeros((len(layer), 2))
    return dict(buried(terms, values.double(), index.int(), owner.long(), np.asarray(layer),
                       center, np.ones(len(layer), bool), rho))


def test_a_buried_mark_is_lifted_onto_the_surface_and_the_layer_above_rests_on_it_lifted():
    squares = [square(0, range(10, 20), range(0, 40)),     # a wide mark of layer 0
               square(1, range(16, 19), range(14, 17)),    # layer 1, under it
               square(2, range(5, 8), range(30, 33)),      # layer 1, on the surface
               square(3, range(12, 15), range(14, 17))]    # layer 2: clear until 1 is lifted
    lifts = lifts_of(stack_terms(), squares, [0, 1, 1, 2])
    # 9 raster px straight up puts unit 1 on rows 7-9, clear of the wide mark's top row (10);
    # unit 3 then lies in unit 1's shadow, and 6 px at 30 degrees off straight up clear it
    # beside unit 1, on the wide mark ((-3, -5) px: rows 7-9, columns 11-13), fewer than
    # the 8 px straight up
    assert lifts == {1: (0.0, -18.0), 3: (-6.0, -10.0)}


def test_a_mark_no_spot_clears_stays_where_it_is():
    outside = torch.zeros(3, H * W, dtype=torch.float64)
    outside[1].view(H, W)[:10] = 1.0    # its region ends where the obstacle begins
    outside[1].view(H, W)[:, 20:] = 1.0
    outside[1].view(H, W)[:, :10] = 1.0
    squares = [square(0, range(10, 40), range(10, 20)), square(1, range(16, 19), range(14, 17))]
    assert lifts_of(stack_terms(outside), squares, [0, 1]) == {}


def test_a_mark_under_a_ceiling_is_lifted_aside_where_straight_back_leaves_its_region():
    outside = torch.zeros(3, H * W, dtype=torch.float64)
    outside[1].view(H, W)[:10, :20] = 1.0    # a ceiling right above the obstacle
    squares = [square(0, range(10, 20), range(10, 20)), square(1, range(16, 19), range(14, 17))]
    # 7 raster px at 60 degrees off straight up, to the right: (6, -4) px, columns 20-22
    assert lifts_of(stack_terms(outside), squares, [0, 1]) == {1: (12.0, -8.0)}


def test_strata_are_lifted_lowest_first_whatever_their_order():
    rests = np.zeros((4, 4), bool)
    rests[0, 2] = rests[2, 3] = rests[1, 0] = True   # 3 <- 2 <- 0 <- 1
    assert strata_order(rests) == [2, 0, 1]


@pytest.mark.parametrize("xy, direction", [((60.0, 50.0), (1.0, 0.0)), ((50.0, 20.0), (0.0, -1.0))])
def test_a_radial_stratum_lifts_out_from_the_point_that_pulls_it(xy, direction):
    sweep = Radial(((50.0, 50.0, 1.0),)).on((100, 100), 1.0, 0, "cpu")
    np.testing.assert_allclose(against(sweep, np.array([xy]))[0], direction, atol=1e-12)


def test_small_marks_a_large_one_rolled_over_come_back_up_onto_it():
    # one large disc on the floor with three small discs of the layer resting on it under it:
    # the flat shadow gives them no gradient out, and the pull pressed them to the floor
    k = np.repeat([0, 1], [1, 24])
    df = pd.DataFrame({"k": k, "v": np.where(k == 0, 80.0, 1.0)})
    chart = uw.Chart(df, size="v", by="k", canvas=(400, 300), boundary="open",
                     container=uw.Container.rect(10, 10, 380, 280),
                     forces=[uw.DirectionalForce(90)], iterations=300)
    chart.layer("1").set(blocks=["0"])
    units = bind(chart.df, chart.layers)
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu")
    radius = float(np.hypot(problem.half_w, problem.half_h)[0] * problem.group_scale[0]) / 2 ** 0.5
    with torch.no_grad():
        problem.placement.t[0] = torch.tensor([200.0, 290.0 - radius])
        problem.placement.t[1:4] = torch.tensor([[180.0, 280.0], [200.0, 285.0], [220.0, 280.0]])
    result = solve(problem)
    table = engine.placements(units, chart.layers, result)
    assert result.phases.get("settle.resurface", 0) > 0
    assert below_envelope(table, "0", "1") == 0.0


def test_a_lift_finds_the_distance_a_plain_scan_of_every_step_finds():
    # _lift reads only the spots whose box holds a free pixel and stops at the region's box;
    # its answer must be that of trying every distance of every step in turn, as the rule
    # says: the fewest raster px that clear the mark, the first step of equal distances
    from scipy import ndimage
    from unitopia_widget.layout.rules.resurface import ResurfaceSettings, _fan, _lift, _room
    rng, c = np.random.default_rng(4), ResurfaceSettings()
    h, w, answers = 48, 64, []
    for _ in range(30):
        field = ndimage.gaussian_filter(rng.random((h, w)), float(rng.uniform(1.5, 4.0)))
        block = torch.from_numpy((field > np.quantile(field, rng.uniform(0.3, 0.8))).astype(np.float32))
        region = np.zeros((h, w), np.float32)
        region[rng.integers(0, 12):rng.integers(30, h), rng.integers(0, 16):rng.integers(40, w)] = 1.0
        outside = torch.from_numpy(1.0 - region).reshape(-1)
        block = torch.maximum(block.reshape(-1), outside)
        y, x = int(rng.integers(8, h - 8)), int(rng.integers(8, w - 8))
        rows, cols = np.mgrid[y - 3:y + 4, x - 2:x + 3]
        pixel = torch.as_tensor((rows * w + cols).reshape(-1))
        alpha = torch.from_numpy(rng.uniform(0.2, 1.0, len(pixel)).astype(np.float32))
        turn = rng.uniform(0, 2 * np.pi)
        steps = np.array(_fan(np.array([np.cos(turn), np.sin(turn)]), c.fan))
        want = None
        for k, step in enumerate(steps):   # every distance up to past the longer side
            for d in range(1, 1 + (max(h, w) - 1) // c.chunk * c.chunk + c.chunk):
                r = pixel // w + int(np.rint(d * step[1]))
                q = pixel % w + int(np.rint(d * step[0]))
                on = (r >= 0) & (r < h) & (q >= 0) & (q < w)
                cover = torch.where(on, block[(r * w + q).clamp(0, h * w - 1)], torch.tensor(1.0))
                if float((cover * alpha).sum()) <= c.clear * float(alpha.sum()):
                    if want is None or d < want[0]:
                        want = (d, k)
                    break
        got = _lift(block, alpha, pixel, steps, h, w, _room(block, outside, h, w, c.clear), c)
        assert got == want
        answers.append(want)
    assert sum(a is None for a in answers) > 2 and sum(a is not None for a in answers) > 10
