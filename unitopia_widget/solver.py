"""The layout solver: Adam on translations and rotations, a controller on the global scale.

Schedule: a *settle* phase (a strong pull while marks travel, a gentle one
once they rest; on closed layers the scale grows while the measured overlap
stays below ``grow_overlap / 2`` and gives way above it once marks rest;
layers held back for pouring start moving when the stage before them rests;
ends when the loss stops improving and the marks rest) and a *polish* phase
(scale frozen and shrunk by ``polish_shrink``, forces weakened, decaying
steps) that removes the last overlaps; if a closed layout still overlaps more
than ``final_overlap``, the scale gives up a little and polishing repeats.
The scale is controlled rather than learned because a gradient balance
between fill and overlap settles at a few percent of overlap with spiky marks.
Frames ``(N, 4)`` float32 (x, y, angle in degrees, global scale) go to
``on_frame`` every ``frame_every`` iterations; ``cancel()`` returning True
stops the run between iterations and keeps the current transforms.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import torch

from .forces import potential
from .losses import CanvasLoss, CanvasTerms
from .placement import Placement
from .raster import RasterGrid, plan_groups, render_samples


@dataclass
class Problem:
    """Everything the solver needs; ``N`` units, ``L`` layers. Lengths in canvas px."""

    grid: RasterGrid
    pyramids: list                 # per sprite: list of (1, 1, h, w) tensors, finest first
    sprite_sides: list[int]        # long side of each sprite's finest level
    sprite: np.ndarray             # (N,) sprite id per unit
    layer: np.ndarray              # (N,) layer index per unit
    half_w: np.ndarray             # (N,) half box width at scale 1 (drawn, no margin)
    half_h: np.ndarray             # (N,) half box height at scale 1
    margin: np.ndarray             # (N,) margin fraction: footprint = box * (1 + 2 margin)
    placement: Placement           # positions and angles, with their constraints
    terms: CanvasTerms             # containment / fill fields per layer, blocks
    forces: list                   # per layer: list of forces
    scale: float                   # initial global scale
    free_scale: bool               # control the scale (some closed layer fills its container)
    stage: np.ndarray | None = None  # (N,) pouring stage: stage k moves once stage k - 1 rests
    stage_wait: int = 150          # iterations a stage waits at most for the one before
    travelling: bool = True        # whether marks start away from where they will rest
    max_iterations: int = 600
    polish_iterations: int = 60
    polish_shrink: float = 0.008
    polish_force: float = 0.05     # force weight in the polish phase, relative
    force_weight: float = 0.005    # force pressure relative to overlap, once marks rest
    force_travel: float = 0.03     # force pressure while marks are still travelling
    lr: float = 0.04               # translation step when marks touch, in mean mark radii
    lr_travel: float = 0.3         # the step while nothing overlaps (marks travelling), mean radii
    overlap_target: float = 0.002  # raster overlap share above which steps shrink
    final_overlap: float = 0.001   # overlap share a closed layout must reach (scale shrinks until)
    legalize_rounds: int = 10
    legalize_shrink: float = 0.005
    grow_overlap: float = 0.01     # the fill controller grows the scale below half this overlap
    scale_step: float = 0.003      # log-scale step of the fill controller per iteration
    patience: int = 12
    settle_motion: float = 0.75    # mean travel over a patience window, in mean radii, below which marks rest
    device: str = "cpu"


@dataclass
class Result:
    """Final transforms and quality; ``center (N, 2)``, ``angle (N,)`` degrees."""

    center: np.ndarray
    angle: np.ndarray
    scale: float
    iterations: int
    seconds: float
    cancelled: bool
    stats: dict = field(default_factory=dict)


def solve(problem: Problem, on_frame: Callable | None = None, frame_every: int = 3,
          cancel: Callable[[], bool] | None = None, on_progress: Callable | None = None) -> Result:
    """Run the layout; see the module docstring for the schedule."""
    p = problem
    dev = torch.device(p.device)
    started = time.perf_counter()
    layer_t = torch.as_tensor(p.layer, device=dev, dtype=torch.long)
    half_w0 = torch.as_tensor(p.half_w * (1 + 2 * p.margin), device=dev, dtype=torch.float32)
    half_h0 = torch.as_tensor(p.half_h * (1 + 2 * p.margin), device=dev, dtype=torch.float32)
    radius = float(np.mean(np.hypot(p.half_w, p.half_h))) * p.scale
    log_scale = torch.tensor(math.log(p.scale), device=dev)
    place = p.placement
    params = [{"params": place.parameters(), "lr": p.lr * radius}]
    if place.angle_params():
        params.append({"params": place.angle_params(), "lr": 0.05})
    optimizer = torch.optim.Adam(params, betas=(0.8, 0.95))
    rotating = place.rotating()
    force_layers = [(torch.nonzero(layer_t == a).reshape(-1), fs)
                    for a, fs in enumerate(p.forces) if fs]

    iteration, best, since_best, phase = 0, math.inf, 0, "settle"
    polish_left = p.polish_iterations
    loss_value, cancelled = math.inf, False
    base_lrs = [g["lr"] for g in optimizer.param_groups]
    gain_max = p.lr_travel / p.lr
    gain, rounds = 1.0, 0
    # marks placed where the forces pull them start at rest; emitted ones start travelling
    window_start, travelling, last_overlap = place.transforms()[0].detach().clone(), p.travelling, math.inf
    stage = np.zeros(len(p.layer), dtype=int) if p.stage is None else np.asarray(p.stage)
    poured, poured_at = 0, 0
    if stage.max() > 0:
        place.hold(stage > poured)
    while True:
        if cancel is not None and cancel():
            cancelled = True
            break
        scale = torch.exp(log_scale)
        center, angle = place.transforms()
        hw, hh = scale * half_w0, scale * half_h0
        groups = plan_groups(hw.detach().cpu().numpy(), hh.detach().cpu().numpy(), p.sprite,
                             p.sprite_sides, rotating, p.grid.rho)
        values, index, owner = render_samples(center, angle, hw, hh, groups, p.pyramids, p.grid)
        loss = CanvasLoss.apply(values, index, layer_t[owner], p.terms)
        if phase == "polish":
            weight = p.force_weight * p.polish_force
        else:   # a strong pull carries marks through jams; a gentle one lets piles settle
            weight = p.force_travel if travelling else p.force_weight
        for members, fs in force_layers:
            loss = loss + weight * potential(fs, center[members]).mean() / radius
        loss = loss + place.penalty()
        optimizer.zero_grad(set_to_none=True)
        loss.backward()
        optimizer.step()
        place.project(p.grid.canvas, iteration)
        iteration += 1
        loss_value = float(loss.detach())
        if on_frame is not None and iteration % frame_every == 0:
            on_frame(_frame(place, float(torch.exp(log_scale.detach()))))
        if on_progress is not None:
            on_progress(iteration, loss_value, p.terms.stats)
        if phase == "settle":
            # big steps while marks travel freely, small ones once they press on each other
            if loss_value < best * (1 - 1e-3) - 1e-6:
                best, since_best = loss_value, 0
            else:
                since_best += 1
            overlap = p.terms.stats["overlap"]
            # crowding; while marks travel, only crowding that gets worse (an emitter's
            # first pile-up resolving is no reason to slow down)
            crowded = overlap > p.overlap_target and (not travelling or overlap > last_overlap * 1.001)
            last_overlap = overlap
            gain = max(1.0, gain * 0.7) if crowded else min(gain_max, gain * (1.1 if travelling else 1.05))
            optimizer.param_groups[0]["lr"] = base_lrs[0] * gain
            if p.free_scale:
                # the scale grows while marks have room and gives way when they crowd (or, when
                # too few to crowd, as they leave the container)
                crowd = max(overlap, p.terms.stats["outside"])
                if crowd < 0.5 * p.grow_overlap:
                    log_scale += p.scale_step
                    since_best = 0
                elif crowd > 1.5 * p.grow_overlap and not travelling:   # not for transient crowds
                    log_scale -= p.scale_step
            if iteration % p.patience == 0:
                # settled when the marks stopped travelling over the last window
                with torch.no_grad():
                    now = place.transforms()[0].detach().clone()
                pouring = torch.as_tensor(stage == poured, device=now.device)
                moved = float((now - window_start).norm(dim=1)[pouring].mean())
                travelling = moved > p.settle_motion * radius
                window_start = now
                if poured < stage.max() and (not travelling or iteration - poured_at >= p.stage_wait):
                    poured, poured_at, travelling = poured + 1, iteration, True   # pour the next layer
                    place.hold(stage > poured)
            if (since_best >= p.patience and not travelling) \
                    or iteration >= p.max_iterations - p.polish_iterations:
                phase = "polish"
                if p.free_scale:
                    log_scale -= p.polish_shrink
        else:
            polish_left -= 1
            for g, lr0 in zip(optimizer.param_groups, base_lrs):
                g["lr"] = lr0 * max(polish_left, 1) / p.polish_iterations
            if polish_left <= 0 or iteration >= p.max_iterations:   # max_iterations is a cap
                if (p.free_scale and p.terms.stats["overlap"] > p.final_overlap
                        and rounds < p.legalize_rounds and iteration < p.max_iterations):
                    # still crowded: give up a little scale and polish again
                    rounds += 1
                    polish_left = p.polish_iterations // 3
                    log_scale -= max(p.legalize_shrink, p.terms.stats["overlap"])
                    continue
                break
    center, angle = place.transforms()
    scale = float(torch.exp(log_scale))
    if on_frame is not None:
        on_frame(_frame(place, scale))
    stats = dict(p.terms.stats, loss=loss_value)
    return Result(center=center.detach().cpu().numpy().astype(np.float64),
                  angle=np.degrees(angle.detach().cpu().numpy().astype(np.float64)),
                  scale=scale, iterations=iteration, seconds=time.perf_counter() - started,
                  cancelled=cancelled, stats=stats)


def _frame(place: Placement, scale: float) -> np.ndarray:
    """float32 ``(N, 4)``: x, y, angle (degrees), global scale."""
    with torch.no_grad():
        center, angle = place.transforms()
        out = torch.empty((center.shape[0], 4), dtype=torch.float32)
        out[:, :2] = center.cpu()
        out[:, 2] = torch.rad2deg(angle).cpu()
        out[:, 3] = scale
    return out.numpy()
