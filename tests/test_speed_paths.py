"""Tests for the engine's fast paths (issue 13): what each does, not how long it takes.

Adam without torch.optim, the one-iteration-late readback a GPU uses, render
plans reused while no mark changes group, the snapped raster resolution, the
loosest closed-start lattice and the cold start that never imports torch._dynamo.
"""
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from unitopia_widget.layout import solver
from unitopia_widget.layout.prepare.lattice import Region, fitting_lattice
from unitopia_widget.layout.step.optim import Adam
from unitopia_widget.layout.step.raster import PATCH_SIDES, SPRITE_SIDE, Planner, RasterGrid, snap_rho
from unitopia_widget.layout.step.transfer import Readback

from test_solver import CIRCLE, CX, CY, R, chart, circle_quality

pytestmark = pytest.mark.usefixtures("one_thread")


def test_adam_takes_torch_optims_steps():
    torch.manual_seed(0)
    target = torch.randn(6, 2)
    ours, theirs = torch.zeros(6, 2, requires_grad=True), torch.zeros(6, 2, requires_grad=True)
    a = Adam([{"params": [ours], "lr": 0.1}], betas=(0.8, 0.95))
    b = torch.optim.Adam([{"params": [theirs], "lr": 0.1}], betas=(0.8, 0.95))
    for step in range(25):
        for p, opt in ((ours, a), (theirs, b)):
            opt.zero_grad()
            ((p - target) ** 2 * (1 + step % 3)).sum().backward()
            opt.step()
        a.param_groups[0]["lr"] = b.param_groups[0]["lr"] = 0.1 / (1 + step)
    torch.testing.assert_close(ours, theirs, rtol=1e-5, atol=1e-6)
    assert set(a.state[ours]) == {"step", "exp_avg", "exp_avg_sq"}


def test_readback_hands_over_the_previous_values_when_it_lags():
    late, now = Readback("cpu", lag=True), Readback("cpu")
    assert late.push(torch.tensor([1.0])).tolist() == [1.0]     # the first push waits for itself
    assert late.push(torch.tensor([2.0])).tolist() == [1.0]
    assert late.push(torch.tensor([3.0])).tolist() == [2.0]
    assert now.push(torch.tensor([3.0])).tolist() == [3.0]


def test_a_layout_read_back_one_iteration_late_is_as_good(monkeypatch):
    # what a GPU run does: the controller sees the sums of the iteration before
    monkeypatch.setattr(solver, "Readback", lambda device: Readback(device, lag=True))
    c = chart(60, boundary="open", fill=0.4, forces=[uw.PointForce(CX, CY + R)])
    overlap, outside, density = circle_quality(c.layout())
    assert overlap < 0.002 and outside < 0.002
    assert density == pytest.approx(0.4, rel=1e-3)


def test_planner_reuses_its_plan_until_a_mark_changes_group():
    grid = RasterGrid((200.0, 200.0), 1.0, pad=2)
    planner = Planner(np.zeros(3, int), [SPRITE_SIDE], np.zeros(3, bool), [None], grid, "cpu")
    half = np.array([3.3, 5.5, 5.5])       # patches 10 and 14, away from a step
    first = planner.plan_for(half, half)
    assert planner.plan_for(half * 1.01, half * 1.01) is first       # same patches, same plan
    grown = planner.plan_for(half * 1.5, half * 1.5)                 # patches step up: a new one
    assert grown is not first
    assert sorted(part.ph for part in grown.parts) != sorted(part.ph for part in first.parts)
    # each sample's owner, part after part: the loss attributes samples through it
    expected = [int(u) for part in grown.parts for u in part.idx for _ in range(part.ph * part.pw)]
    assert grown.owner.tolist() == expected


def test_planner_reads_no_group_for_footprints_it_was_last_asked(monkeypatch):
    # scales that did not move: the plan is handed back without a group key computed
    from unitopia_widget.layout.step import raster
    grid = RasterGrid((200.0, 200.0), 1.0, pad=2)
    planner = Planner(np.zeros(3, int), [SPRITE_SIDE], np.zeros(3, bool), [None], grid, "cpu")
    half = np.array([3.3, 5.5, 5.5])
    first = planner.plan_for(half, half)
    calls, keys = [], raster.group_keys
    monkeypatch.setattr(raster, "group_keys", lambda *a, **k: calls.append(1) or keys(*a, **k))
    assert planner.plan_for(np.array([3.3, 5.5, 5.5]), half.copy()) is first
    assert calls == []
    half[0] = 3.4   # the caller's array changed in place: the planner kept its own copy
    assert planner.plan_for(half, half) is first and calls == [1]


def test_a_second_layout_of_the_same_container_reuses_its_fields():
    # the coverage and distance transform are made once per container, raster and falloff
    from unitopia_widget.layout.prepare import assemble
    grid = RasterGrid((120.0, 90.0), 1.5, pad=2)
    box = uw.Container.ellipse(60, 45, 40, 30)
    first = assemble._fields(box, grid, 4.0)
    again = assemble._fields(uw.Container.ellipse(60, 45, 40, 30), grid, 4.0)
    assert all(a is b for a, b in zip(first, again))
    other = assemble._fields(uw.Container.ellipse(60, 45, 40, 31), grid, 4.0)
    assert not torch.equal(other[0], first[0])
    assert assemble._fields(box, grid, 5.0)[2] is not first[2]          # another falloff


def test_snap_rho_fits_marks_just_over_a_patch_step_into_it():
    # a 16.1 px patch at rho = 1 pays 20 x 20 samples; 0.99 x rho fits 16 x 16
    half = np.full(50, 7.05)
    rho = snap_rho(1.0, half, half, rotating=False)
    assert 0.9 <= rho < 1.0
    assert 2 * 7.05 * rho + 2 <= 16 < 2 * 7.05 + 2
    # marks that already fit keep the finest resolution
    assert snap_rho(1.0, np.full(50, 6.0), np.full(50, 6.0), rotating=False) == 1.0
    assert 16 in PATCH_SIDES and 20 in PATCH_SIDES


def test_dust_marks_do_not_set_the_raster_resolution():
    # a heavy tail: 20 visible marks and 200 drawn under 2 px across; aimed at the mean of
    # all, the raster was the finest allowed (rho 4 here), 30x the pixels of one aimed at
    # the visible marks
    from unitopia_widget.layout import engine
    from unitopia_widget.layout.prepare.bind import bind
    c = chart(220, boundary="open", fill=0.3, values=np.r_[np.ones(20), np.full(200, 1e-5)])
    problem = engine.build_problem(bind(c.df, c.layers), c.layers, c.canvas, 0, "cpu",
                                   max_iterations=1)
    assert problem.grid.rho < 4.0 / 4, problem.grid.rho


def test_packing_keeps_clearances_exact_only_as_far_as_they_matter():
    # one huge disc among small ones: each disc updates the clearances up to the largest disc
    # still to place (here and ``later``), not the huge one's radius; the same spots result
    from unitopia_widget.layout.prepare.pack import Packing
    yy, xx = np.mgrid[:200, :300]
    region = Region((((xx - 150) / 140) ** 2 + ((yy - 100) / 90) ** 2 <= 1).astype(float), 1.0)
    radii = np.r_[60.0, np.random.default_rng(0).uniform(1, 4, 60)]
    ranks, out = np.arange(len(radii)), []
    for later in (None, 3.0):
        pack = Packing(region, 1.0, float(radii.max()))
        centers = pack.place(radii, pack.depth.copy() * -1, ranks, later=later)[0]
        gap = np.hypot(*(pack.points[:, None] - centers[None]).T).T - radii
        exact = np.minimum(pack.depth, gap.min(1))
        out.append((centers, pack.clear, exact))
    np.testing.assert_array_equal(out[0][0], out[1][0])
    np.testing.assert_allclose(out[0][1], out[0][2], atol=1e-9)
    near = out[1][2] < 3.0            # exact up to ``later``; the rest at least that
    np.testing.assert_allclose(out[1][1][near], out[1][2][near], atol=1e-9)
    assert (out[1][1][~near] >= 3.0 - 1e-9).all()


def test_closed_start_lattice_is_the_loosest_that_holds_the_marks():
    # an off-centre ellipse (no symmetric jumps in the count); 3% steps overshot by 1-5%
    # (152, 314, 793), leaving a rim of empty container the scale then grew into slowly
    yy, xx = np.mgrid[:300, :400]
    region = Region((((xx - 203.3) / 170) ** 2 + ((yy - 148.7) / 120) ** 2 <= 1).astype(float), 1.0)
    for count in (150, 300, 777):
        pts = fitting_lattice(region, count, 60.0, 4.0)
        assert count <= len(pts) <= 1.02 * count, (count, len(pts))
        assert (region.depth_at(pts) > 0).all()


def test_closed_equal_circles_fill_their_container():
    c = chart(300, iterations=400)
    overlap, outside, density = circle_quality(c.layout())
    assert overlap < 0.002 and outside < 0.002
    assert density > 0.8, density


def test_a_cold_layout_never_imports_torch_dynamo():
    code = ("import sys, pandas as pd, unitopia_widget as uw\n"
            "uw.Chart(pd.DataFrame({'v': [1.0] * 12}), mark='circle', size='v',"
            " container=uw.Container.ellipse(100, 100, 80, 80), canvas=(200, 200)).layout()\n"
            "print('torch._dynamo' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False", out.stderr
