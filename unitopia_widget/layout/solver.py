"""The layout solver: Adam on translations and rotations, a controller on the global scale.

Each iteration renders the marks, steps Adam and reads the loss back; then the rules
of ``rules.SCHEDULE`` run on the shared ``rules.State``: a *settle* phase (forces
pull, controlled scales grow while there is room and give way when marks crowd, marks
come to rest, jammed ones relocate, crossing thin ones turn, held layers pour), a
*polish* phase (scales frozen, steps decaying, legalising rounds) and, unless cancelled,
a *finish* (hollow marks' contacts cleared). ``Result.phases`` counts the iterations each
phase and rule acted on; ``Result.rules`` names the rules that apply to the layout.
The scale is controlled rather than learned because a gradient balance
between fill and overlap settles at a few percent of overlap with spiky marks.
Frames ``(N, 4)`` float32 (x, y, angle in degrees, global scale) go to
``on_frame`` at the start, every ``frame_every`` iterations and at the end; ``cancel()`` returning True
stops the run between iterations and keeps the current transforms.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import torch

from ..design.encodings import footprint
from ..design.forces import potential
from .prepare.problem import Problem
from .rules import SCHEDULE, STEPS, State, run, start
from .step.losses import CanvasLoss, shares
from .step.optim import Adam
from .step.placement import frame
from .step.raster import Planner, render_samples
from .step.scales import Scales
from .step import threads
from .step.transfer import Readback, upload


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
    phases: dict = field(default_factory=dict)  # "settle"/"polish"/"finish" and "phase.rule": iterations
    rules: tuple = ()                           # the names of the rules that apply to this layout
    axes: list = field(default_factory=list)    # positions.Axis of each bound x=/y= channel


def solve(problem: Problem, on_frame: Callable | None = None, frame_every: int = 3,
          cancel: Callable[[], bool] | None = None, on_progress: Callable | None = None,
          start_frame: bool = True, settled: bool = False) -> Result:
    """Run the layout: render, step, read back, then the rules of ``rules.SCHEDULE``.
    ``start_frame=False``: the caller has sent the start frame (``build_problem``'s ``on_start``).
    ``settled``: the start is a layout that settled (``finer``): the solve only polishes it.
    ``on_progress(iteration, loss, stats)`` after each step: ``stats`` the overlap and outside
    shares and ``"phase"``, the phase the step ran in ("settle", "polish")."""
    p = problem
    dev = torch.device(p.device)
    started = time.perf_counter()
    layer_t = torch.as_tensor(p.layer, device=dev, dtype=torch.long)
    # half footprints at scale 1 (margins included): on the host to plan patches, on the device to draw
    foot_w, foot_h = p.half_w * footprint(p.margin), p.half_h * footprint(p.margin)
    half_w0 = torch.as_tensor(foot_w, device=dev, dtype=torch.float32)
    half_h0 = torch.as_tensor(foot_h, device=dev, dtype=torch.float32)
    ctl = Scales(p)
    radius = float(np.mean(np.hypot(p.half_w, p.half_h) * ctl.unit_scale()))
    place = p.placement
    steps = STEPS
    params = [{"params": place.parameters(), "lr": steps.lr * radius}]
    if place.angle_params():
        params.append({"params": place.angle_params(), "lr": 0.05})
    optimizer = Adam(params, betas=(0.8, 0.95))
    rotating = place.rotating()
    planner = Planner(p.sprite, p.sprite_sides, rotating, p.pyramids, p.grid, dev,
                      p.sprite_aspects)
    n_layers = p.terms.penalty.shape[0]
    readback, plan, sample_layer = Readback(dev), None, None
    force_layers = [(torch.nonzero(layer_t == a).reshape(-1), fs)
                    for a, fs in enumerate(p.forces) if fs]
    # marks stay on the canvas with all their ink (rotating ones with their box's circle)
    ink = np.where(rotating[:, None], np.hypot(p.half_w, p.half_h)[:, None],
                   np.stack([p.half_w, p.half_h], 1))
    ink_t = torch.as_tensor(ink, device=dev, dtype=torch.float32)
    # marks placed where the forces pull them start at rest; emitted ones start travelling
    s = State(p=p, steps=steps, ctl=ctl, place=place, optimizer=optimizer, radius=radius,
              force_layers=force_layers,
              stage=np.zeros(len(p.layer), dtype=int) if p.stage is None else np.asarray(p.stage),
              window_start=place.transforms()[0].detach().clone(), travelling=p.travelling,
              base_lrs=[g["lr"] for g in optimizer.param_groups],
              polish_left=steps.polish_iterations, room=np.zeros(ctl.count, dtype=bool),
              phase="polish" if settled else "settle")
    start(s)
    applying = tuple(rule.name for rule in SCHEDULE if rule.applies(s))
    if s.stage.max() > 0:
        place.hold(s.stage > s.poured)
    if on_frame is not None and start_frame:   # the start: shown before the first steps
        on_frame(frame(place, ctl.unit_scale()))
    cancelled = False
    # the first plan's samples decide the threads the passes use (the loop finds it kept)
    first = planner.plan_for(foot_w * ctl.unit_scale(), foot_h * ctl.unit_scale())
    with threads.fitted(len(first.owner), dev):
        while not s.done:
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
            # the containment tables are read only at the marks whose patch meets the border
            loss = CanvasLoss.apply(values, index, sample_layer, p.terms, p.terms.border(index, plan, layer_t))
            if s.phase == "polish":   # legalising rounds: no force presses the marks together
                weight = steps.force_weight * steps.polish_force * (s.rounds == 0)
            else:   # a strong pull carries marks through jams; a gentle one lets piles settle
                weight = steps.force_travel if s.travelling else steps.force_weight
            for members, fs in force_layers:
                loss = loss + weight * potential(fs, center[members]).mean() / radius
            if p.anchor is not None:
                loss = loss + p.anchor.loss(center)
            loss = loss + place.penalty()
            optimizer.zero_grad(set_to_none=True)
            loss.backward()
            optimizer.step()
            place.project(p.grid.canvas, s.iteration, ink_t * scale[:, None])
            s.iteration += 1
            # the loss and the per-layer sums, on a GPU those of the iteration before (no stall)
            readings = readback.push(torch.cat([loss.detach().reshape(1), p.terms.sums.reshape(-1)]))
            s.loss_value, sums = float(readings[0]), readings[1:].reshape(4, n_layers).astype(float)
            s.stats = shares(sums.sum(1), p.terms.inside_total)
            if on_frame is not None and s.iteration % frame_every == 0:
                on_frame(frame(place, ctl.unit_scale()))
            if on_progress is not None:
                on_progress(s.iteration, s.loss_value, {**s.stats, "phase": s.phase})
            s.overlap_g, s.outside_g = ctl.crowding(sums[:3])
            s.values, s.index, s.owner = values, index, owner
            run(s)
    if not cancelled:
        s.phase = "finish"
        run(s)
    unit_scale = ctl.unit_scale()
    center, angle = place.transforms()
    if on_frame is not None:
        on_frame(frame(place, unit_scale))
    stats = dict(p.terms.stats, loss=s.loss_value)
    return Result(center=center.detach().cpu().numpy().astype(np.float64),
                  angle=np.degrees(angle.detach().cpu().numpy().astype(np.float64)),
                  scale=float(np.exp(ctl.log[0])), iterations=s.iteration,
                  seconds=time.perf_counter() - started, cancelled=cancelled, stats=stats,
                  unit_scale=unit_scale.astype(np.float64), phases=dict(s.record), rules=applying,
                  axes=[] if p.anchor is None else list(p.anchor.axes))
