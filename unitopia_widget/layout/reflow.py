"""Live reflow: a run after a small change answered where the change reaches.

A warm run whose layers are those of the last run (the design equal but for its pins; the
rows may differ) reuses that run's ``Problem`` (``Layout.problem``: the raster, the region
fields, the sprite pyramids and the blocks, made from the layers, the canvas and the raster
resolution only) and gives each unit its arrays anew (``rebase``). It starts from the last
layout as any warm run does (``prepare.warm``, ``prepare.pins``), with the scale kept
(``warm`` shrinks it only where added rows need the room), and then moves only the marks
the change reaches (``settle``, on a ``window.Window``). Where rows were added to or
removed from a container whose scale the fill controls (and no kept mark changed size),
every mark there must move: its scale follows the footprint area ratio and
``prepare.room.make_room`` moves the marks along the room the change makes or leaves and
relaxes their discs, which leaves the layout near legal; the window then starts from there
with every mark movable, with small steps, and judges the overlap the change added net of
the overlap it removed. A unit is *crowded* when its overlapped or outside share
of its ink grew by more than ``ReflowSettings.crowded`` over the last layout; crowded units
are *active* (they move), every unit with ink in the raster box around the active ones is
drawn, the others frozen as obstacles, and a frozen unit that becomes crowded joins the
active ones (in a jam, one pressed at all), so the window grows while overlaps propagate.
The run stops as soon as the layout is legal again: the overlap the change added is at most
``final_overlap`` of all the marks' area, and no unit's share grew by more than ``worst``. A
change that reaches too far (``spread``), or one the window cannot absorb in
``max_iterations``, is answered by the full warm run instead (``reflow`` returns None); so
are marks made smaller in a container whose scale grows into their room, design changes
beyond pins and margins (a force), emitters, curve tracks and x=/y= positions, which no
window answers.
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np
import torch

from ..design.encodings import footprint
from .prepare.assemble import padded_margin, room_reach
from .prepare.pins import pin_problem
from .prepare.problem import Problem
from .prepare.start import footprint_radius
from .prepare.room import make_room, regrown
from .prepare.warm import replace_start, warm_problem
from .rules import STEPS
from .solver import Result
from .step.placement import Placement
from .window import Window, bounds, final_stats, inside


@dataclass(frozen=True)
class ReflowSettings:
    """The window's tuning numbers."""

    crowded: float = 0.01        # growth of a unit's overlapped + outside share of its ink that activates it
    worst: float = 0.05          # the most growth of one unit's share a legal layout keeps
    touch: float = 0.002         # growth of a frozen unit's share that activates it in a jam
    patience: int = 2            # rounds without the worst growth falling by ``progress``: a jam
    progress: float = 0.002
    final_overlap: float = 0.001  # the most grown overlap and outside of all units, a share of all their ink
    round_iterations: int = 4    # steps between two looks at the window
    max_iterations: int = 100    # steps before the full warm run takes over
    spread: float = 0.2          # share of the units active beyond which the full warm run takes over
    gain: float = 4.0            # first step, in ``Steps.lr`` (mean radii per step), decaying to 1
    gain_decay: float = 0.97     # per step
    floor: float = 0.1           # the least step, in ``Steps.lr``
    room: float = 0.02           # share of a controlled scale group's footprint area its marks may
    #                              give up (as a warm start's scale does) before the scale must grow
    slack: float = 2.0           # largest footprint radii the raster box reaches past the drawn units
    net: bool = False            # the grown overlap of all units summed with its falls (a change
    #                              that moves every mark, where the falls are as real as the growths)
    moved_gain: float = 1.0      # ``gain`` where every mark moved to a start near legal (``make_room``)


SETTINGS = ReflowSettings()


def rebase(base: Problem, units, layers) -> Problem | None:
    """``base`` (the last run's problem, before its warm start and pins) for ``units``: its
    raster, fields, pyramids, blocks and scales, with the per-unit arrays of ``units``;
    None where those parts do not carry over (other marks, poured stages, curve tracks,
    x=/y= anchors, units that cannot move, or emitters)."""
    place = base.placement
    if (base.anchor is not None or place.tracks or not bool(place.movable.all())
            or (base.stage is not None and base.stage.max() > 0) or place.orientation is not None
            or any(layer.emitter is not None for layer in layers)
            or len(base.sprite_sides) != len(units.sprites)):
        return None
    unit_scale = base.group_scales()[base.layer_groups()[units.layer]]
    margin = padded_margin(units, unit_scale, base.unseen)   # the base raster's unseen depth
    band = footprint(margin)
    terms = dataclasses.replace(
        base.terms, norm=float((units.area * band ** 2 * unit_scale ** 2).sum()) * base.grid.rho ** 2,
        sums=None, _cover=None, _tables=None, _rows=None, _onehot=None, _obstacle=None)
    n = len(units.rows)
    placement = Placement(np.zeros((n, 2)), np.zeros(n), np.ones(n, bool),
                          np.array([layers[li].rotate for li in units.layer], bool), base.device)
    return dataclasses.replace(
        base, sprite=units.sprite, layer=units.layer, half_w=units.half_w, half_h=units.half_h,
        margin=margin, placement=placement, terms=terms, reach=room_reach(units),
        disc=footprint_radius(units), ink_share=units.ink_share, stage=None, travelling=False)


def resumed(base: Problem, units, layers) -> Problem | None:
    """``base`` (the last run's problem) ``rebase``d for ``units`` with the forces of
    ``layers``, for a full warm run that needs no new problem: one whose point forces moved
    (the raster, fields, sprites and blocks depend on no force), or one after a full run cut
    short (a Stop, a newer drag message), which no window settles; None where a layer rests
    on another (the shadow it rests on sweeps from the forces, ``step.strata``) or
    ``rebase`` refuses."""
    if base.terms.rests is not None and bool(base.terms.rests.any()):
        return None
    p = rebase(base, units, layers)
    return None if p is None else dataclasses.replace(p, forces=[layer.forces for layer in layers])


def reflow(base: Problem, units, layers, canvas, previous, pinned, pin_xy, pin_angle,
           on_frame=None, cancel=None, settings: ReflowSettings = SETTINGS) -> Result | None:
    """The layout of ``units`` after a small change, answered from ``base`` (see the module
    docstring) and the snapshot ``previous`` (``warm.snapshot``); ``pinned``, ``pin_xy``,
    ``pin_angle`` as ``prepare.pins.pinned_units`` gives them. Returns the solver's
    ``Result``, or None where the full warm run must answer."""
    started = time.perf_counter()
    p = rebase(base, units, layers)
    if p is None:
        return None
    names = [layer.name for layer in layers]
    where = {(layer, row): k for k, (layer, row) in enumerate(zip(previous["layer"], previous["row"]))}
    found = np.array([where.get((names[li], row), -1) for li, row in zip(units.layer, units.rows)])
    kept = found >= 0
    if not kept.any():
        return None
    groups = regrown(p, units, layers, previous, found)
    placed = np.isin(p.layer_groups()[units.layer], list(groups))
    p = warm_problem(p, units, layers, canvas, previous, pinned, pin_xy, placed=placed)
    if groups:   # rows added to or removed from a filled container: all its marks move
        center, scales = make_room(p, units, layers, canvas, previous, found, pinned, groups)
        p = dataclasses.replace(p, placement=replace_start(p.placement, center),
                                group_scale=scales, scale=float(scales[0]))
        settings = dataclasses.replace(settings, spread=1.0, net=True, gain=settings.moved_gain)
    scale = unit_scales(p)
    area = units.area * footprint(units.margin) ** 2 * scale ** 2
    if not groups and shrunk(p, units, layers, previous, area, settings.room):
        return None   # a controlled scale grows into the room the change left: all marks move
    p = pin_problem(p, units, layers, canvas, pinned, pin_xy, pin_angle, vacate=False)
    center = p.placement.t.detach().cpu().numpy().astype(np.float64)
    step_aside(center, p.disc * scale, p.placement.movable.cpu().numpy(), pinned)
    old = np.full((len(found), 2), np.nan)
    old[kept] = previous[["x", "y"]].to_numpy(dtype=float)[found[kept]]
    grew = np.ones(len(found), bool)   # added units, and kept ones moved or grown
    grew[kept] = (np.hypot(*(center[kept] - old[kept]).T) > 1e-6) \
        | (area[kept] > previous["area"].to_numpy(dtype=float)[found[kept]] * (1 + 1e-6))
    was = None
    if groups:   # each unit's scale in the last layout, where the scale changed
        was = scale.copy()
        was[kept] = np.sqrt(previous["area"].to_numpy(dtype=float)[found[kept]]
                            / (units.area * footprint(units.margin) ** 2)[kept])
    moved = settle(p, center, old, grew, settings, on_frame, cancel, was)
    if moved is None:
        return None
    center, iterations, cancelled, stats = moved
    angle = np.degrees(p.placement.theta.detach().cpu().numpy().astype(np.float64))
    if on_frame is not None:   # the layout, the last frame as of every run
        on_frame(np.column_stack([center, angle, scale]).astype(np.float32))
    return Result(center=center, angle=angle, scale=float(p.group_scales()[0]),
                  iterations=iterations, seconds=time.perf_counter() - started,
                  cancelled=cancelled, stats=stats, unit_scale=scale,
                  phases={"reflow": iterations}, rules=("reflow",))


def shrunk(p: Problem, units, layers, previous, area: np.ndarray, room: float) -> bool:
    """Whether the marks of some controlled scale group of ``p`` take ``room`` less of their
    area than in the snapshot ``previous`` or more (rows removed, margins or sizes made
    smaller): its scale would grow into the room left. ``area (N,)``: each unit's footprint
    area now, px^2."""
    names = [layer.name for layer in layers]
    group, free = p.layer_groups(), p.group_controlled()
    known = previous["layer"].isin(names).to_numpy()
    old_group = np.full(len(previous), -1)
    old_group[known] = group[[names.index(n) for n in previous["layer"][known]]]
    before = previous["area"].to_numpy(dtype=float)
    unit_group = group[units.layer]
    return any(area[unit_group == g].sum() < before[old_group == g].sum() * (1 - room)
               for g in np.nonzero(free)[0])


def step_aside(center: np.ndarray, radius: np.ndarray, movable: np.ndarray,
               pinned: np.ndarray) -> None:
    """Move (in ``center (N, 2)``) each free unit whose centre is on a pinned one (closer
    than the larger of their discs ``radius (N,)``), where the overlap pushes it nowhere
    sure, straight away from the pin until their discs touch."""
    for k in pinned:
        gap = center - center[k]
        d = np.hypot(*gap.T)
        on = movable & (d < np.maximum(radius, radius[k]))
        if on.any():
            away = np.where(d[on, None] > 1e-9, gap[on] / np.maximum(d[on, None], 1e-9), [1.0, 0.0])
            center[on] = center[k] + away * (radius[on, None] + radius[k])


def unit_scales(p: Problem) -> np.ndarray:
    """``(N,)`` each unit's global scale in ``p``."""
    return p.group_scales()[p.layer_groups()[p.layer]]


def settle(p: Problem, center: np.ndarray, old: np.ndarray, grew: np.ndarray,
           settings: ReflowSettings, on_frame, cancel, was_scale: np.ndarray | None = None):
    """Move the units of ``p`` from ``center (N, 2)`` (the warm start) that the change
    reaches until none is crowded (module docstring); ``old (N, 2)``: each unit's centre in
    the last layout (NaN for added units); ``grew (N,)``: the units added, moved or grown
    since (only around them can a share have grown); ``was_scale (N,)``: each unit's scale in
    the last layout (None: as now). Returns ``(center (N, 2), iterations,
    cancelled, stats)``, or None when the window spreads past ``settings.spread`` or does
    not settle in ``max_iterations``."""
    n = len(p.layer)
    scale = unit_scales(p)
    band = footprint(p.margin)
    foot_w, foot_h = p.half_w * band * scale, p.half_h * band * scale
    radius = np.hypot(foot_w, foot_h)
    movable = p.placement.movable.cpu().numpy().astype(bool)
    center = center.copy()
    cropped = p.terms.rests is None or not bool(p.terms.rests.any())
    slack = settings.slack * float(radius.max())
    share, before, ink_area = np.zeros(n), np.zeros(n), np.zeros(n)
    if grew.any():   # each unit's share before and after the change, around the change
        was = np.where(np.isnan(old), center, old)
        spots = np.concatenate([center[grew], was[grew]])
        box = bounds(spots, np.concatenate([radius[grew]] * 2), slack)
        sub = np.nonzero(inside(center, radius, box))[0]
        look = Window(p, sub, center, np.zeros(n, bool), foot_w, foot_h, 0.0, 0.0,
                      box if cropped else None)
        whole = sub[look.whole]
        then = look if was_scale is None else Window(
            p, sub, center, np.zeros(n, bool), foot_w * was_scale / scale,
            foot_h * was_scale / scale, 0.0, 0.0, box if cropped else None)
        before[whole] = then.shares(was[sub])[0][look.whole] * ~np.isnan(old[whole, 0])
        now, ink = look.shares()
        share[whole], ink_area[whole] = now[look.whole], ink[look.whole]
    allowed = settings.final_overlap * p.terms.norm
    grown = (share - before) * movable
    active = grown > settings.crowded
    base_lr = STEPS.lr * float(np.mean(radius))
    ink = torch.as_tensor(np.stack([foot_w, foot_h], 1) / band[:, None], dtype=torch.float32)
    iterations, window, box, cancelled = 0, None, None, False
    least, stall = np.inf, 0   # the least worst growth so far, and the rounds since it fell
    angle = np.degrees(p.placement.theta.detach().cpu().numpy())   # the window turns no mark
    while grown.max(initial=0.0) > settings.worst or \
            float(((grown if settings.net else np.maximum(grown, 0)) * ink_area).sum()) > allowed:
        if active.sum() > settings.spread * n or iterations >= settings.max_iterations:
            return None
        if cancel is not None and cancel():
            cancelled = True
            break
        reach = bounds(center[active], radius[active], 0.0)
        if box is None or (reach[:2] < box[:2] + slack / 2).any() or (reach[2:] > box[2:] - slack / 2).any():
            box = bounds(center[active], radius[active], slack)
        # every unit with ink in the box is drawn, the frozen ones as they are: the box's
        # coverage is the layout's, and the fill term reads its holes truly
        sub = np.nonzero(inside(center, radius, box))[0]
        if window is None or not np.array_equal(window.sub, sub) \
                or not np.array_equal(window.place.movable.cpu().numpy(), active[sub]):
            window = Window(p, sub, center, active, foot_w, foot_h, base_lr, p.terms.w_fill,
                            box if cropped else None)
        for _ in range(settings.round_iterations):
            gain = max(settings.floor, settings.gain * settings.gain_decay ** iterations)
            window.step(base_lr * gain, ink[sub])
            iterations += 1
            center[sub] = window.centers()
            if on_frame is not None:   # every step: the runner sends at most its fps
                on_frame(np.column_stack([center, angle, scale]).astype(np.float32))
        whole = sub[window.whole]
        now, drawn = window.shares()
        share[whole], ink_area[whole] = now[window.whole], drawn[window.whole]
        grown = (share - before) * movable
        active |= grown > settings.crowded
        worst = float(grown.max(initial=0.0))
        stall = stall + 1 if worst > least - settings.progress else 0
        least = min(least, worst)
        if stall >= settings.patience:   # jammed: the frozen units pressed at all join
            active[sub] |= grown[sub] > settings.touch
            stall = 0
    everyone = Window(p, np.arange(n), center, np.zeros(n, bool), foot_w, foot_h, 0.0)
    return center, iterations, cancelled, final_stats(everyone, center, p.terms.w_fill)
