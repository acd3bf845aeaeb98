"""Tests for unitopia_widget.layout.step.losses: CanvasLoss values on hand-built rasters and its backward."""
import math

import pytest
import torch

from unitopia_widget.layout.step.losses import CanvasLoss, CanvasTerms

D = torch.float64


def make_terms(n_layers=1, size=4, penalty=None, outside=None, inside=None, blocks=None,
               dtype=D, **weights) -> CanvasTerms:
    """Terms on ``n_layers`` slabs of ``size`` pixels; unset fields are zero."""
    def t(x):
        if x is None:
            return torch.zeros(n_layers, size, dtype=dtype)
        return torch.as_tensor(x, dtype=dtype).reshape(n_layers, size)
    return CanvasTerms(penalty=t(penalty), outside=t(outside), inside=t(inside),
                       blocks=torch.zeros(n_layers, n_layers, dtype=dtype) if blocks is None
                       else torch.as_tensor(blocks, dtype=dtype), **weights)


def loss_and_grad(values, index, layer, terms):
    v = torch.as_tensor(values, dtype=terms.penalty.dtype).clone().requires_grad_(True)
    loss = CanvasLoss.apply(v, torch.as_tensor(index), torch.as_tensor(layer), terms)
    (grad,) = torch.autograd.grad(loss, v)
    return float(loss.detach()), grad


def reference_loss(values, index, layer, terms):
    """The loss in plain torch ops; blocking layers' coverage enters with gradients stopped."""
    n_layers, size = terms.penalty.shape
    flat = layer * size + index
    cover = torch.zeros(n_layers * size, dtype=values.dtype).index_add(0, flat, values)
    cover = cover.view(n_layers, size)
    total = cover + terms.blocks @ cover.detach()
    overlap = torch.relu(total - 1).sum()
    contain = (values * terms.penalty.reshape(-1)[flat]).sum()
    fill = (terms.inside * torch.relu(1 - total)).sum()
    return (terms.w_overlap * overlap + terms.w_contain * contain + terms.w_fill * fill) / terms.norm


# --- forward values ----------------------------------------------------------

def test_overlap_counts_the_excess_coverage_exactly():
    # pixel 1: 0.7 + 0.6 = 1.3 -> 0.3 excess; pixel 2: 0.5 + 0.5 + 0.25 -> 0.25; pixel 3: 0.9 -> 0
    values = [0.7, 0.6, 0.5, 0.5, 0.25, 0.9]
    index = [1, 1, 2, 2, 2, 3]
    terms = make_terms(w_contain=0.0)
    loss, grad = loss_and_grad(values, index, [0] * 6, terms)
    assert loss == pytest.approx(0.55, abs=1e-12)
    assert grad.tolist() == [1.0, 1.0, 1.0, 1.0, 1.0, 0.0]
    assert terms.stats["overlap"] == pytest.approx(0.55 / sum(values), abs=1e-12)
    assert terms.stats["outside"] == 0.0


def test_marks_that_only_touch_cost_nothing():
    terms = make_terms()
    loss, grad = loss_and_grad([1.0, 0.4, 0.6, 1.0], [0, 1, 1, 2], [0] * 4, terms)
    assert loss == 0.0 and grad.abs().sum() == 0.0


def test_containment_is_alpha_times_the_penalty_and_outside_share_is_reported():
    penalty = [0.0, 0.0, 1.0, 3.5]          # flat 1 outside plus distance beyond pixel 2
    outside = [0.0, 0.0, 1.0, 1.0]
    terms = make_terms(penalty=penalty, outside=outside, w_overlap=0.0, w_contain=2.0)
    loss, grad = loss_and_grad([1.0, 0.8, 0.5, 0.2], [0, 1, 2, 3], [0] * 4, terms)
    assert loss == pytest.approx(2.0 * (0.5 * 1.0 + 0.2 * 3.5), abs=1e-12)
    assert grad.tolist() == pytest.approx([0.0, 0.0, 2.0, 7.0])
    assert terms.stats["outside"] == pytest.approx((0.5 + 0.2) / 2.5, abs=1e-12)


def test_fill_penalises_uncovered_container_pixels():
    inside = [1.0, 1.0, 0.5, 0.0]           # pixel 2 half inside, pixel 3 outside the container
    terms = make_terms(inside=inside, w_overlap=0.0, w_contain=0.0, w_fill=0.5)
    loss, grad = loss_and_grad([0.6, 1.2, 0.2, 0.7], [0, 1, 2, 3], [0] * 4, terms)
    gap = 1.0 * 0.4 + 0.0 + 0.5 * 0.8 + 0.0
    assert loss == pytest.approx(0.5 * gap, abs=1e-12)
    assert grad.tolist() == pytest.approx([-0.5, 0.0, -0.25, 0.0])
    assert terms.stats["fill"] == pytest.approx(1 - gap / 2.5, abs=1e-12)


def test_fill_reports_nan_without_a_closed_container():
    terms = make_terms()
    loss_and_grad([0.5], [0], [0], terms)
    assert math.isnan(terms.stats["fill"])


def test_norm_divides_every_term():
    kw = dict(penalty=[0, 0, 2.0, 0], inside=[1, 1, 1, 1], w_fill=0.3)
    values, index = [0.9, 0.8, 0.6, 0.3], [0, 0, 2, 3]
    one, g1 = loss_and_grad(values, index, [0] * 4, make_terms(**kw))
    ten, g10 = loss_and_grad(values, index, [0] * 4, make_terms(norm=10.0, **kw))
    assert one > 0 and ten == pytest.approx(one / 10, abs=1e-12)
    assert torch.allclose(g10, g1 / 10)


def test_layers_do_not_collide_without_blocks():
    # layers 0 and 1 fill the same pixel: they only overlap each other through blocks
    terms = make_terms(n_layers=2, size=2)
    loss, grad = loss_and_grad([0.8, 0.9], [0, 0], [0, 1], terms)
    assert loss == 0.0 and grad.abs().sum() == 0.0


def test_blocks_are_one_way():
    # layer 1 blocks on layer 0: at pixel 0 layer 1 sees 0.9 + its own 0.5 = 1.4 > 1, and
    # the gradient reaches layer 1's sample only; layer 0's sample (0.9 alone, < 1) feels
    # nothing, exactly as if layer 1 were not there. The value counts layer 1's share of
    # the excess: 0.5 / 1.4 * 0.4
    terms = make_terms(n_layers=2, size=2, blocks=[[0, 0], [1, 0]])
    loss, grad = loss_and_grad([0.9, 0.5], [0, 0], [0, 1], terms)
    assert loss == pytest.approx(0.5 / 1.4 * 0.4, abs=1e-12)
    assert grad.tolist() == [0.0, 1.0]
    # the other direction: layer 0 blocking on layer 1 moves the pressure to layer 0
    terms = make_terms(n_layers=2, size=2, blocks=[[0, 1], [0, 0]])
    loss, grad = loss_and_grad([0.9, 0.5], [0, 0], [0, 1], terms)
    assert grad.tolist() == [1.0, 0.0]


def test_the_blocking_layers_gradient_ignores_the_blocked_layer():
    # layer 0 overlaps itself at pixel 0 (1.2); layer 1 blocks on it and also sits there
    base = dict(n_layers=2, size=3, penalty=[[0, 0, 0.5], [0, 0, 0.5]],
                inside=[[1, 1, 1], [1, 1, 1]], w_fill=0.2)
    alone = make_terms(**base, blocks=[[0, 0], [1, 0]])
    _, g_alone = loss_and_grad([0.7, 0.5, 0.4], [0, 0, 2], [0, 0, 0], alone)
    both = make_terms(**base, blocks=[[0, 0], [1, 0]])
    _, g_both = loss_and_grad([0.7, 0.5, 0.4, 0.3, 0.9], [0, 0, 2, 0, 1], [0, 0, 0, 1, 1], both)
    assert torch.equal(g_both[:3], g_alone)
    # layer 1's samples: pixel 0 is over-full (1.2 + 0.3), pixel 1 is under-full (0.9)
    assert g_both[3:].tolist() == pytest.approx([1.0, -0.2])


def test_float32_inputs_give_a_float32_loss():
    terms = make_terms(dtype=torch.float32)
    loss = CanvasLoss.apply(torch.tensor([0.7, 0.6], requires_grad=True), torch.tensor([1, 1]),
                            torch.tensor([0, 0]), terms)
    assert loss.dtype == torch.float32 and loss.shape == ()
    assert float(loss.detach()) == pytest.approx(0.3, abs=1e-6)


# --- backward ------------------------------------------------------------------

def random_case(seed, n_layers, size, samples, blocks):
    g = torch.Generator().manual_seed(seed)
    values = torch.rand(samples, generator=g, dtype=D) * 0.9 + 0.05
    index = torch.randint(0, size, (samples,), generator=g)
    layer = torch.randint(0, n_layers, (samples,), generator=g)
    terms = make_terms(
        n_layers=n_layers, size=size, blocks=blocks,
        penalty=torch.rand(n_layers, size, generator=g, dtype=D) * (torch.rand(n_layers, size, generator=g) > 0.5),
        inside=(torch.rand(n_layers, size, generator=g, dtype=D) > 0.3).to(D),
        w_overlap=1.0, w_contain=0.7, w_fill=0.15, norm=3.7)
    return values, index, layer, terms


def kink_free(values, index, layer, terms, margin=1e-3):
    """True when no pixel total sits within ``margin`` of 1, where the loss has a kink."""
    n_layers, size = terms.penalty.shape
    cover = torch.zeros(n_layers * size, dtype=D).index_add(0, layer * size + index, values)
    total = cover.view(n_layers, size) + terms.blocks @ cover.view(n_layers, size)
    return bool(((total - 1).abs() > margin).all())


@pytest.mark.parametrize("seed", range(4))
def test_gradcheck_against_finite_differences_without_blocks(seed):
    values, index, layer, terms = random_case(seed, 2, 12, 40, None)
    assert kink_free(values, index, layer, terms)
    values.requires_grad_(True)
    assert torch.autograd.gradcheck(lambda v: CanvasLoss.apply(v, index, layer, terms),
                                    (values,), eps=1e-6, atol=1e-8)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("blocks", [None, [[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 1, 0], [0, 0, 0], [0, 1, 0]]])
def test_backward_matches_the_autograd_reference(seed, blocks):
    values, index, layer, terms = random_case(seed, 3, 10, 50, blocks)
    assert kink_free(values, index, layer, terms)
    v1 = values.clone().requires_grad_(True)
    loss = CanvasLoss.apply(v1, index, layer, terms)
    (grad,) = torch.autograd.grad(loss, v1)
    v2 = values.clone().requires_grad_(True)
    ref = reference_loss(v2, index, layer, terms)
    (ref_grad,) = torch.autograd.grad(ref, v2)
    if blocks is None:   # with obstacles the value is the layer's share (see test_blocks_are_one_way)
        assert float(loss.detach()) == pytest.approx(float(ref.detach()), rel=1e-12, abs=1e-12)
    assert torch.allclose(grad, ref_grad, rtol=1e-12, atol=1e-12)
    # the reference itself is right: without blocks it is the plain loss, which
    # gradcheck confirms; with blocks a finite difference would also move the
    # blocked layers (through the obstacles), which the loss deliberately ignores
    if blocks is not None:
        assert bool((ref_grad != 0).any())


def test_backward_scales_with_the_incoming_gradient():
    values, index, layer, terms = random_case(11, 2, 8, 30, None)
    v = values.clone().requires_grad_(True)
    (3.0 * CanvasLoss.apply(v, index, layer, terms)).backward()
    w = values.clone().requires_grad_(True)
    CanvasLoss.apply(w, index, layer, terms).backward()
    assert torch.allclose(v.grad, 3.0 * w.grad)


def test_repeated_calls_on_the_same_terms_do_not_leak_coverage():
    # the solver reuses one CanvasTerms for every iteration
    shared = make_terms(n_layers=2, size=4, inside=[[1] * 4, [1] * 4], w_fill=0.2,
                        blocks=[[0, 0], [1, 0]])
    loss_and_grad([0.9, 0.8, 0.7, 0.6], [0, 1, 2, 3], [0, 0, 1, 1], shared)
    again, g_again = loss_and_grad([0.6, 0.6], [1, 1], [1, 1], shared)
    fresh, g_fresh = loss_and_grad([0.6, 0.6], [1, 1], [1, 1], make_terms(
        n_layers=2, size=4, inside=[[1] * 4, [1] * 4], w_fill=0.2, blocks=[[0, 0], [1, 0]]))
    assert again == fresh and torch.equal(g_again, g_fresh)
    assert again == pytest.approx(0.2 + 0.2 * (8 - 1.0), abs=1e-12)   # excess + w_fill * gap


@pytest.mark.parametrize("dtype", [torch.float32, D])
def test_an_open_layout_skips_the_fill_target_and_gets_the_same_numbers(dtype):
    # no layer has a fill target: the forward leaves the inside table out; forced through
    # it (any_inside set), every number agrees to the last bit
    values, index, layer, _ = random_case(5, 2, 12, 60, None)
    values = values.to(dtype)
    g = torch.Generator().manual_seed(5)
    penalty, outside = torch.rand(2, 12, generator=g), torch.rand(2, 12, generator=g)

    def run(force):
        terms = make_terms(n_layers=2, size=12, dtype=dtype, penalty=penalty, outside=outside,
                           w_contain=0.7, w_fill=0.15, norm=3.7)
        assert not terms.any_inside
        if force:
            terms.any_inside = True
        v = values.clone().requires_grad_(True)
        loss = CanvasLoss.apply(v, index, layer, terms)
        (grad,) = torch.autograd.grad(loss, v)
        return loss.detach(), grad, terms.sums

    for skipped, full in zip(run(False), run(True)):
        assert torch.equal(skipped, full)


@pytest.mark.parametrize("blocks", [None, [[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 1, 0], [0, 0, 0], [0, 1, 0]]])
def test_the_units_shares_of_the_overlap_add_up_to_each_layers_overlap(blocks):
    values, index, layer, terms = random_case(5, 3, 10, 50, blocks)
    owner = torch.arange(50) % 7 * 3 + layer          # 21 units, each in one layer
    unit_layer = torch.arange(21) % 3
    CanvasLoss.apply(values, index, layer, terms)
    per_unit = terms.unit_overlap(values, index, owner, unit_layer, 21)
    per_layer = torch.zeros(3, dtype=D).index_add_(0, unit_layer, per_unit)
    assert torch.allclose(per_layer, terms.sums[0], rtol=1e-12, atol=1e-12)
    assert bool((per_unit > 0).any())


@pytest.mark.parametrize("blocks", [None, [[0, 0, 0], [1, 0, 0], [1, 1, 0]]])
def test_mostly_empty_samples_are_summed_inked_alone_with_the_same_numbers(blocks, monkeypatch):
    # most samples at alpha 0 (a thin mark's turning square): the forward sums the inked ones
    # alone. Loss, per-layer sums and the gradient through the alphas are those of summing
    # them all, call after call on the same terms (a kept buffer of another length)
    import unitopia_widget.layout.step.losses as losses

    def run(pack, cases):
        monkeypatch.setattr(losses, "PACK_EMPTY", 0.5 if pack else 1.0)
        terms, out = random_case(7, 3, 10, 50, blocks)[3], []
        for x, index, layer in cases:
            x = x.clone().requires_grad_(True)
            loss = CanvasLoss.apply(torch.relu(x), index, layer, terms)   # alpha 0: no gradient
            (grad,) = torch.autograd.grad(loss, x)
            out.append((loss.detach(), terms.sums.clone(), grad))
        return out, terms

    cases = []
    for seed, samples in ((1, 400), (2, 250), (3, 400)):
        g = torch.Generator().manual_seed(seed)
        values, index, layer, _ = random_case(seed, 3, 10, samples, blocks)
        empty = torch.rand(samples, generator=g) < 0.75
        cases.append((torch.where(empty, -values, values), index, layer))
    (packed, terms), (full, _) = run(True, cases), run(False, cases)
    assert terms._packed is not None                  # the inked samples were packed
    for a, b in zip(packed, full):
        for x, y in zip(a, b):
            assert torch.allclose(x, y, rtol=1e-12, atol=1e-12)
    assert all(bool((grad != 0).any()) for *_, grad in packed)


@pytest.mark.parametrize("pack", [False, True])
def test_the_tables_read_at_the_border_marks_alone_give_the_same_numbers(pack, monkeypatch):
    # marks whose patch meets no pixel with a containment penalty or an outside share read
    # zeros there: the forward gathers both tables only at the others, to the last bit; the
    # same with the inked samples packed (every empty one packed away here)
    import numpy as np
    import unitopia_widget.layout.step.losses as losses
    monkeypatch.setattr(losses, "PACK_EMPTY", 0.0 if pack else 1.0)
    from unitopia_widget.layout.step.raster import (Planner, RasterGrid, SPRITE_SIDE, render_samples,
                                                    sprite_pyramid)
    grid = RasterGrid((60.0, 40.0), 1.0, pad=2)
    h, w = grid.shape
    g = torch.Generator().manual_seed(3)
    rim = torch.zeros(2, h, w)
    rim[0, :, :8], rim[1, 30:, :] = 1.0, 1.0            # layer 0: a left band, layer 1: the bottom
    penalty = (rim * torch.rand(2, h, w, generator=g)).reshape(2, -1)
    outside = (rim * torch.rand(2, h, w, generator=g)).reshape(2, -1)
    terms = CanvasTerms(penalty=penalty, outside=outside, inside=torch.zeros(2, h * w),
                        blocks=torch.zeros(2, 2), shape=(h, w), w_contain=0.7, norm=50.0)
    center = torch.tensor([[5.0, 20.0], [30.0, 20.0], [50.0, 10.0], [30.0, 34.0], [45.0, 12.0],
                           [12.0, 36.0]])
    layer = torch.tensor([0, 0, 0, 1, 1, 1])
    sprite = [sprite_pyramid(np.ones((SPRITE_SIDE, SPRITE_SIDE)), "cpu")]
    plan = Planner(np.zeros(6, int), [SPRITE_SIDE], np.zeros(6, bool), sprite, grid,
                   "cpu").plan_for(np.full(6, 3.0), np.full(6, 3.0))
    half = torch.full((6,), 3.0)
    values, index, owner = render_samples(center, torch.zeros(6), half, half, plan, sprite, grid)
    border = terms.border(index, plan, layer)
    flat = index.long() + layer[owner] * h * w
    meets = torch.zeros(6, dtype=torch.bool).index_put_((owner,), (penalty.reshape(-1)[flat] != 0)
                                                        | (outside.reshape(-1)[flat] != 0), accumulate=True)
    assert meets.tolist() == [True, False, False, True, False, True]
    assert border.tolist() == torch.nonzero(meets[owner]).reshape(-1).tolist()

    def run(values, index, at):
        v = values.detach().clone().requires_grad_(True)
        loss = CanvasLoss.apply(v, index, layer[owner], terms, at)
        (grad,) = torch.autograd.grad(loss, v)
        return loss.detach(), grad, terms.sums.clone()

    for read, full in zip(run(values, index, border), run(values, index, None)):
        assert torch.equal(read, full)
    # the marks move: the rows the last border wrote are cleared, the new border's written
    run(values, index, border)
    moved = center + torch.tensor([[15.0, 0.0], [-25.0, 0.0], [0.0, 0.0], [0.0, -20.0], [0.0, 20.0], [0.0, 0.0]])
    values, index, _ = render_samples(moved, torch.zeros(6), half, half, plan, sprite, grid)
    again = terms.border(index, plan, layer)
    assert not torch.equal(again, border)
    for read, full in zip(run(values, index, again), run(values, index, None)):
        assert torch.equal(read, full)
    assert (terms._packed is not None) == pack and bool((values == 0).any())
    if pack:   # packed, the numbers are those of every sample summed, but for rounding
        loss, grad, sums = run(values, index, again)
        monkeypatch.setattr(losses, "PACK_EMPTY", 1.0)
        dense_loss, dense_grad, dense_sums = run(values, index, again)
        inked = values > 0
        assert torch.allclose(loss, dense_loss, rtol=1e-6) and torch.allclose(sums, dense_sums, rtol=1e-6)
        assert torch.allclose(grad[inked], dense_grad[inked]) and bool((grad[~inked] == 0).all())


def test_a_patch_overhanging_the_raster_is_read_whole():
    # a mark larger than the raster: its samples are clamped onto it, it has no origin to
    # look up, and all of them are read (the summed-area lookups stay in bounds)
    import numpy as np
    from unitopia_widget.layout.step.raster import (Planner, RasterGrid, SPRITE_SIDE, render_samples,
                                                    sprite_pyramid)
    grid = RasterGrid((10.0, 8.0), 1.0, pad=2)
    h, w = grid.shape
    zero = torch.zeros(1, h * w)
    terms = CanvasTerms(penalty=zero, outside=zero, inside=zero, blocks=torch.zeros(1, 1),
                        shape=(h, w), norm=9.0)
    sprite = [sprite_pyramid(np.ones((SPRITE_SIDE, SPRITE_SIDE)), "cpu")]
    half = np.array([7.0] + [2.0] * 8)
    plan = Planner(np.zeros(9, int), [SPRITE_SIDE], np.zeros(9, bool), sprite, grid, "cpu").plan_for(half, half)
    assert sorted(part.overhangs for part in plan.parts) == [False, True]
    center = torch.tensor([[5.0, 4.0]] + [[2.0 + k, 3.0] for k in range(8)])
    size = torch.tensor(half, dtype=torch.float32)
    values, index, owner = render_samples(center, torch.zeros(9), size, size, plan, sprite, grid)
    border = terms.border(index, plan, torch.zeros(9, dtype=torch.long))
    assert border.tolist() == torch.nonzero(owner == 0).reshape(-1).tolist()
