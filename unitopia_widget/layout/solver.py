"""The layout solver: Adam on translations and rotations, a controller on the global scale.

Schedule: a *settle* phase (a strong pull while marks travel, a gentle one
once they rest; on closed layers the scale grows while the measured overlap
stays below ``grow_overlap / 2`` and gives way above it once marks rest;
layers held back for pouring start moving when the stage before them rests;
ends when the loss stops improving and the marks rest, a tenth of them still travelling
keeping it going; a loss that rises while marks still travel, as they pile up, becomes the
new best, and so does the first loss once they rest, when the force weakens and Adam's
moments are scaled down with it) and a *polish* phase
(scale frozen and shrunk by ``polish_shrink``, forces weakened, decaying
steps) that removes the last overlaps; if a layout still overlaps more than
``final_overlap`` or pokes out more than ``final_outside``, the scale gives up
a little and polishing repeats (open layouts too: data-true sizes never push
a mark out). Closed layers also grow while their container has *room*: a
share over ``room_target`` farther than a median mark radius from any mark
(``room.py``), even while jammed marks keep some overlap, and while their footprints
poke out a little (more with margins: the band pokes out before the ink). Layers may have
their own scales (``scale_group``): each group is controlled on its own layers.
At settle windows and legalising rounds thin marks whose ink crosses turn side by side
(``uncross.py``): no gradient undoes a crossing.
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

from ..design.encodings import footprint
from ..design.forces import potential
from .losses import CanvasLoss, CanvasTerms, shares
from .optim import Adam
from .placement import Placement
from .raster import Planner, RasterGrid, render_samples
from .relocate import holes, unit_overlap
from .room import empty_share
from .pack import thin
from .transfer import Readback, upload
from .uncross import ink_pairs, turns


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
    margin: np.ndarray             # (N,) margin fraction: footprint = box * footprint(margin)
    placement: Placement           # positions and angles, with their constraints
    terms: CanvasTerms             # containment / fill fields per layer, blocks
    forces: list                   # per layer: list of forces
    scale: float                   # initial global scale (of scale group 0)
    free_scale: bool               # control the scale (some closed layer fills its container)
    scale_group: np.ndarray | None = None  # (L,) scale group per layer; None: one shared scale
    group_scale: np.ndarray | None = None  # (G,) initial scale per group; None: [scale]
    group_free: np.ndarray | None = None   # (G,) bool, controlled groups; None: [free_scale]
    reach: np.ndarray | None = None        # (N,) ink radius less margin band at scale 1 (room)
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
    final_overlap: float = 0.001   # overlap share a layout must reach (scale shrinks until)
    final_outside: float = 0.001   # outside share a layout must reach (scale shrinks until)
    room_target: float = 0.02      # empty share of a closed container below which it is full
    relocate_share: float = 0.05   # share of a roomy layer's marks moved into holes per window
    legalize_rounds: int = 10
    legalize_rounds_open: int = 20  # when no scale fills a container (forces press open piles)
    legalize_shrink: float = 0.005
    legalize_gain_open: float = 2.0   # log-scale shrink per legalising round / overlap, fixed scales
    grow_overlap: float = 0.01     # the fill controller grows the scale below half this overlap
    scale_step: float = 0.003      # log-scale step of the fill controller per iteration
    patience: int = 12
    settle_motion: float = 0.75    # mean travel over a patience window, in mean radii, below which marks rest
    device: str = "cpu"


class Cancelled(Exception):
    """A layout stopped before it had a step to keep."""


@dataclass
class Result:
    """Final transforms and quality; ``center (N, 2)``, ``angle (N,)`` degrees."""

    center: np.ndarray
    angle: np.ndarray
    scale: float                   # the scale of group 0 (the shared scale)
    iterations: int
    seconds: float
    cancelled: bool
    stats: dict = field(default_factory=dict)
    unit_scale: np.ndarray | None = None   # (N,) global scale of each unit's group


def solve(problem: Problem, on_frame: Callable | None = None, frame_every: int = 3,
          cancel: Callable[[], bool] | None = None, on_progress: Callable | None = None) -> Result:
    """Run the layout; see the module docstring for the schedule."""
    p = problem
    dev = torch.device(p.device)
    started = time.perf_counter()
    layer_t = torch.as_tensor(p.layer, device=dev, dtype=torch.long)
    # half footprints at scale 1 (margins included): on the host to plan patches, on the device to draw
    foot_w, foot_h = p.half_w * footprint(p.margin), p.half_h * footprint(p.margin)
    half_w0 = torch.as_tensor(foot_w, device=dev, dtype=torch.float32)
    half_h0 = torch.as_tensor(foot_h, device=dev, dtype=torch.float32)
    ctl = _Scales(p)
    radius = float(np.mean(np.hypot(p.half_w, p.half_h) * ctl.unit_scale()))
    place = p.placement
    params = [{"params": place.parameters(), "lr": p.lr * radius}]
    if place.angle_params():
        params.append({"params": place.angle_params(), "lr": 0.05})
    optimizer = Adam(params, betas=(0.8, 0.95))
    rotating = place.rotating()
    planner = Planner(p.sprite, p.sprite_sides, rotating, p.pyramids, p.grid, dev)
    n_layers = p.terms.penalty.shape[0]
    readback, plan, sample_layer = Readback(dev), None, None
    force_layers = [(torch.nonzero(layer_t == a).reshape(-1), fs)
                    for a, fs in enumerate(p.forces) if fs]
    # marks stay on the canvas with all their ink (rotating ones with their box's circle)
    ink = np.where(rotating[:, None], np.hypot(p.half_w, p.half_h)[:, None],
                   np.stack([p.half_w, p.half_h], 1))
    ink_t = torch.as_tensor(ink, device=dev, dtype=torch.float32)

    iteration, best, since_best, phase = 0, math.inf, 0, "settle"
    polish_left = p.polish_iterations
    loss_value, cancelled = math.inf, False
    base_lrs = [g["lr"] for g in optimizer.param_groups]
    gain_max = p.lr_travel / p.lr
    gain, rounds = 1.0, 0
    # marks placed where the forces pull them start at rest; emitted ones start travelling
    window_start, travelling, last_overlap = place.transforms()[0].detach().clone(), p.travelling, math.inf
    straggling = False   # some marks (a tenth) still travel, though most rest
    stage = np.zeros(len(p.layer), dtype=int) if p.stage is None else np.asarray(p.stage)
    poured, poured_at = 0, 0
    room = np.zeros(ctl.count, dtype=bool)
    if stage.max() > 0:
        place.hold(stage > poured)
    while True:
        if cancel is not None and cancel():
            cancelled = True
            break
        unit_scale = ctl.unit_scale()
        scale = upload(unit_scale, dev)
        center, angle = place.transforms()
        hw, hh = scale * half_w0, scale * half_h0
        if planner.plan_for(foot_w * unit_scale, foot_h * unit_scale) is not plan:
            plan = planner.current
            sample_layer = layer_t[plan.owner] if n_layers > 1 else None
        values, index, owner = render_samples(center, angle, hw, hh, plan, p.pyramids, p.grid)
        loss = CanvasLoss.apply(values, index, sample_layer, p.terms)
        if phase == "polish":   # legalising rounds: no force presses the marks together
            weight = p.force_weight * p.polish_force * (rounds == 0)
        else:   # a strong pull carries marks through jams; a gentle one lets piles settle
            weight = p.force_travel if travelling else p.force_weight
        for members, fs in force_layers:
            loss = loss + weight * potential(fs, center[members]).mean() / radius
        loss = loss + place.penalty()
        optimizer.zero_grad(set_to_none=True)
        loss.backward()
        optimizer.step()
        place.project(p.grid.canvas, iteration, ink_t * scale[:, None])
        iteration += 1
        # the loss and the per-layer sums, on a GPU those of the iteration before (no stall)
        readings = readback.push(torch.cat([loss.detach().reshape(1), p.terms.sums.reshape(-1)]))
        loss_value, sums = float(readings[0]), readings[1:].reshape(4, n_layers).astype(float)
        stats = shares(sums.sum(1), p.terms.inside_total)
        if on_frame is not None and iteration % frame_every == 0:
            on_frame(_frame(place, ctl.unit_scale()))
        if on_progress is not None:
            on_progress(iteration, loss_value, stats)
        overlap_g, outside_g = ctl.crowding(sums[:3])
        if phase == "settle":
            # big steps while marks travel freely, small ones once they press on each other
            # (marks still travelling that pile up raise the loss: the best so far, from
            # before they met, is no reference for whether the pile has settled)
            if loss_value < best * (1 - 1e-3) - 1e-6 or (travelling and loss_value > 1.5 * best):
                best, since_best = loss_value, 0
            else:
                since_best += 1
            overlap = stats["overlap"]
            # crowding; while marks travel, only crowding that gets worse (an emitter's
            # first pile-up resolving is no reason to slow down)
            crowded = overlap > p.overlap_target and (not travelling or overlap > last_overlap * 1.001)
            last_overlap = overlap
            gain = max(1.0, gain * 0.7) if crowded else min(gain_max, gain * (1.1 if travelling else 1.05))
            optimizer.param_groups[0]["lr"] = base_lrs[0] * gain
            # each controlled scale grows while its marks have room and gives way when they
            # crowd (or, when too few to crowd, as they leave the container)
            # (poking out is worse than touching: room never grows a scale past a mark outside)
            crowd = np.maximum(overlap_g, outside_g)
            grow = ctl.free & ((crowd < 0.5 * p.grow_overlap) | (
                room & (overlap_g < 1.5 * p.grow_overlap) & (outside_g < ctl.grow_outside)))
            shrink = ctl.free & ((crowd > 1.5 * p.grow_overlap) | (outside_g > p.grow_overlap)) \
                & (not travelling)
            ctl.log += p.scale_step * (grow.astype(float) - shrink.astype(float))
            if grow.any():
                since_best = 0
            if iteration % p.patience == 0:
                # the ink raster, on the host, once a window (only where some scale fills)
                cover = _coverage(p, values.detach(), index) if ctl.measures_room else None
                room = ctl.room(cover)
                # jammed: room left, yet the overlap keeps the scale from growing
                jammed = room & (overlap_g > 0.5 * p.grow_overlap)
                if jammed.any() and iteration < p.max_iterations // 4 and \
                        _relocate(p, ctl, place, optimizer, jammed, cover, values.detach(), index, owner):
                    since_best = min(since_best, p.patience // 2)   # marks moved: settle a little more
                if _uncross(p, ctl, place, optimizer, values, index, owner):
                    since_best = min(since_best, p.patience // 2)
                # settled when the marks stopped travelling over the last window
                with torch.no_grad():
                    now = place.transforms()[0].detach().clone()
                pouring = torch.as_tensor(stage == poured, device=now.device)
                travel = (now - window_start).norm(dim=1)[pouring]
                moved = float(travel.mean())
                straggling = bool(force_layers) and \
                    float(torch.quantile(travel, 0.9)) > p.settle_motion * radius
                if travelling and moved <= p.settle_motion * radius and force_layers:
                    # come to rest: the force weakens, so the loss so far is no reference, and
                    # Adam's moments, scaled with it, keep marks still in the air falling at pace
                    best, since_best = math.inf, 0
                    _rescale_moments(optimizer, place.t, p.force_weight / p.force_travel)
                travelling = moved > p.settle_motion * radius
                window_start = now
                if poured < stage.max() and (not travelling or iteration - poured_at >= p.stage_wait):
                    poured, poured_at, travelling = poured + 1, iteration, True   # pour the next layer
                    place.hold(stage > poured)
            if (since_best >= p.patience and not travelling and not straggling) \
                    or iteration >= p.max_iterations - p.polish_iterations \
                    - min(p.polish_iterations, p.max_iterations // 10):   # time to legalize
                phase = "polish"
                ctl.log -= p.polish_shrink * ctl.free
        else:
            polish_left -= 1
            for g, lr0 in zip(optimizer.param_groups, base_lrs):
                g["lr"] = lr0 * max(polish_left, 1) / p.polish_iterations
            if polish_left <= 0 or iteration >= p.max_iterations:   # max_iterations is a cap
                bad = (overlap_g > p.final_overlap) | (outside_g > p.final_outside)
                limit = p.legalize_rounds if ctl.free.any() else p.legalize_rounds_open
                if bad.any() and rounds < limit and iteration < p.max_iterations:
                    # still crowded or poking out: give up a little scale and polish again
                    rounds += 1
                    polish_left = p.polish_iterations // 3
                    _uncross(p, ctl, place, optimizer, values, index, owner)
                    # open scales give way faster: no room is lost, and forces keep piles pressed
                    give = np.where(ctl.free, 1.0, p.legalize_gain_open)
                    ctl.log -= bad * np.maximum(p.legalize_shrink,
                                                give * np.maximum(overlap_g, outside_g))
                    continue
                break
    center, angle = place.transforms()
    unit_scale = ctl.unit_scale()
    if on_frame is not None:
        on_frame(_frame(place, unit_scale))
    stats = dict(p.terms.stats, loss=loss_value)
    return Result(center=center.detach().cpu().numpy().astype(np.float64),
                  angle=np.degrees(angle.detach().cpu().numpy().astype(np.float64)),
                  scale=float(np.exp(ctl.log[0])), iterations=iteration,
                  seconds=time.perf_counter() - started, cancelled=cancelled, stats=stats,
                  unit_scale=unit_scale.astype(np.float64))


class _Scales:
    """The controlled global scales: one per scale group, as logs ``(G,)``."""

    def __init__(self, p: Problem):
        self.p = p
        n_layers = p.terms.penalty.shape[0]
        self.group = np.zeros(n_layers, int) if p.scale_group is None else np.asarray(p.scale_group)
        self.count = int(self.group.max()) + 1
        start = [p.scale] if p.group_scale is None else p.group_scale
        self.log = np.log(np.asarray(start, dtype=float))
        self.free = np.asarray([p.free_scale] if p.group_free is None else p.group_free, bool)
        self.unit_group = self.group[p.layer]
        # room grows a scale while its footprints poke out by less than this share: 0.4 of
        # grow_overlap for bare marks, all of it with margins of 0.1 and more (a mark pressed
        # against the edge pokes its margin band out long before its ink)
        margin = np.array([np.median(p.margin[self.unit_group == g]) if (self.unit_group == g).any()
                           else 0.0 for g in range(self.count)])
        self.grow_outside = p.grow_overlap * np.minimum(0.4 + 6.0 * margin, 1.0)

    @property
    def measures_room(self) -> bool:
        """Whether the room of closed containers is measured (some scale fills them)."""
        return self.p.reach is not None and bool(self.free.any())

    def unit_scale(self) -> np.ndarray:
        """``(N,)`` each unit's current scale."""
        return np.exp(self.log)[self.unit_group]

    def crowding(self, sums: np.ndarray):
        """Overlap and outside shares ``(G,)`` from the loss's per-layer sums ``(3, L)``."""
        per = np.zeros((3, self.count))
        np.add.at(per.T, self.group, sums.T)
        drawn = np.maximum(per[2], 1e-6)
        return per[0] / drawn, per[1] / drawn

    def room(self, cover: np.ndarray | None) -> np.ndarray:
        """Bool ``(G,)``: controlled groups whose closed containers all still have room
        (a shared scale that grows for an empty container overfills a full one), from the
        ink raster ``cover (H, W)`` (``_coverage``; None where ``measures_room`` is False)."""
        p, out = self.p, np.zeros(self.count, dtype=bool)
        if not self.measures_room:
            return out
        inside = p.terms.inside_host
        scale = self.unit_scale()
        for g in np.nonzero(self.free)[0]:
            roomy = []
            for layer in np.nonzero(self.group == g)[0]:
                mine = p.layer == layer
                if not inside[layer].any():
                    continue
                reach = float(np.median(p.reach[mine] * scale[mine])) * p.grid.rho
                roomy.append(empty_share(cover, inside[layer].reshape(p.grid.shape), reach)
                             > p.room_target)
            out[g] = bool(roomy) and all(roomy)
        return out


def _coverage(p: Problem, values, index) -> np.ndarray:
    """``(H, W)`` host copy of the summed sample alphas ``values (M,)`` at raster ``index (M,)``."""
    size = p.terms.penalty.shape[1]
    cover = torch.zeros(size, dtype=values.dtype, device=values.device).index_add_(0, index, values)
    return cover.cpu().numpy().reshape(p.grid.shape)


def _movable(place: Placement) -> np.ndarray:
    """Bool ``(N,)``: units the solver may move by hand: released, and not on a curve track."""
    free = place.keep[:, 0].cpu().numpy() > 0
    for track in place.tracks:
        free[track.index.cpu().numpy()] = False
    return free


def _forget(optimizer, params, units: list) -> None:
    """Clear Adam's moments of ``units`` in each of ``params``: they were moved by hand."""
    for param in params:
        state = optimizer.state.get(param, {})
        for key in ("exp_avg", "exp_avg_sq"):
            if key in state:
                state[key][units] = 0.0


def _relocate(p: Problem, ctl: _Scales, place: Placement, optimizer, room: np.ndarray,
              cover: np.ndarray, values, index, owner) -> bool:
    """Move the most overlapped free marks of roomy closed layers into their holes
    (``relocate.py``; ``cover (H, W)`` the ink raster) and forget their Adam momentum.
    Returns whether any moved."""
    overlap = unit_overlap(values, index, owner, len(p.layer), p.terms.penalty.shape[1])
    inside = p.terms.inside_host
    scale = ctl.unit_scale()
    reach = p.reach * scale * p.grid.rho
    # the disc a mark's footprint needs at any angle: its long half side, with margin
    radius = np.maximum(p.half_w, p.half_h) * footprint(p.margin) * scale * p.grid.rho
    free, moved = _movable(place), False
    for g in np.nonzero(room)[0]:
        for layer in np.nonzero(ctl.group == g)[0]:
            mine = p.layer == layer
            if not inside[layer].any():
                continue
            limit = max(1, int(p.relocate_share * mine.sum()))
            moves = holes(cover, inside[layer].reshape(p.grid.shape), overlap, radius,
                          np.nonzero(mine & free)[0], p.grid, 1.5 * float(np.median(reach[mine])), limit)
            with torch.no_grad():
                for unit, (x, y) in moves:
                    place.t[unit, 0], place.t[unit, 1] = x, y
            if moves:
                _forget(optimizer, (place.t,), [unit for unit, _ in moves])
                moved = True
    return moved


def _rescale_moments(optimizer, param: torch.Tensor, ratio: float) -> None:
    """Scale Adam's moments of ``param`` as if its gradients had been ``ratio`` times as large
    all along: the steps stay as they were, and a gradient that shrinks by ``ratio`` now
    still moves the units at full pace instead of waiting for the second moment to forget."""
    state = optimizer.state.get(param)
    if state:
        state["exp_avg"].mul_(ratio)
        state["exp_avg_sq"].mul_(ratio * ratio)


def _uncross(p: Problem, ctl: _Scales, place: Placement, optimizer, values, index, owner) -> bool:
    """Turn thin marks whose ink crosses parallel, side by side (``uncross.py``), and forget
    their Adam momentum. Returns whether any moved."""
    free = place.turnable & thin(p.half_w, p.half_h)
    if not free.any():   # no thin mark turns: no readback
        return False
    free &= _movable(place)
    with torch.no_grad():
        center, tangent = place.centers_and_tangents()
        if place.orientation is not None:   # marks turned towards a target keep to it
            free &= place.orientation(center, tangent)[1].cpu().numpy() <= 0
        if not free.any():
            return False
        pairs, shared = ink_pairs(values, index, owner, len(p.layer))
        if not len(pairs):
            return False
        scale = ctl.unit_scale() * footprint(p.margin)
        moves = turns(pairs, shared, center.cpu().numpy().astype(float),
                      place.theta.cpu().numpy().astype(float), p.half_w * scale, p.half_h * scale, free)
        for unit, (x, y), angle in moves:
            place.t[unit, 0], place.t[unit, 1], place.theta[unit] = x, y, angle
    if moves:
        _forget(optimizer, (place.t, place.theta), [unit for unit, _, _ in moves])
    return bool(moves)


def _frame(place: Placement, scale: np.ndarray) -> np.ndarray:
    """float32 ``(N, 4)``: x, y, angle (degrees), the unit's global scale."""
    with torch.no_grad():
        center, angle = place.transforms()
        out = torch.empty((center.shape[0], 4), dtype=torch.float32)
        out[:, :2] = center.cpu()
        out[:, 2] = torch.rad2deg(angle).cpu()
        out[:, 3] = torch.as_tensor(scale, dtype=torch.float32)
    return out.numpy()
