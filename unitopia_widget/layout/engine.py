"""From bound units and a design to a solved ``Layout``: build the solver's ``Problem``
(``prepare.assemble``), warm-start and pin it (``prepare.warm``, ``prepare.pins``), solve it
(``solver``), keep its frames (``frames``) and return the placements table with the units,
scale, canvas and frames: the one value every output draws from. The rows are bound once,
by the caller (``prepare.bind.bind``).

A layout whose thin marks shrank past its raster is checked, and where need be polished once
more, on a raster made for its final scale (``finer``)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
import torch

from ..design.units import Units
from . import finer
from .frames import Frames
from .prepare.assemble import build_problem, check_abort
from .prepare.pins import pin_problem, pinned_units
from .prepare.problem import Cancelled
from .prepare.scale import initial_scale
from .prepare.warm import snapshot, warm_problem
from .reflow import reflow, resumed
from .solver import Result, solve
from .step.heap import held


@dataclass
class Layout:
    """One run's layout, what the chart keeps and every output draws from."""

    placements: pd.DataFrame       # one row per unit (``placements``)
    units: Units                   # the units placed: rows, layers, colours, boxes at scale 1
    scale: float                   # the global scale (of scale group 0, the shared scale)
    canvas: tuple                  # (w, h) canvas px
    frames: np.ndarray | None      # (F, N, 4) the run's frames, ending on its layout (``frames``)
    result: Result                 # the solver's account: iterations, quality, phases, rules
    axes: list = field(default_factory=list)   # positions.Axis of each bound x=/y= channel
    #: the run's ``Problem`` as built, before its warm start and pins: what a reflow reuses
    problem: object = field(default=None, repr=False)


def boxes(laid: Layout | None, units: Units, layers, canvas) -> np.ndarray:
    """``(N, 2)`` drawn box width and height of ``units``, canvas px: the layout's when ``laid``
    placed these units, else at its global scale (or, with no layout, the starting one)."""
    if laid is not None and laid.units.rows == units.rows \
            and np.array_equal(laid.units.layer, units.layer):
        return laid.placements[["width", "height"]].to_numpy(dtype=float)
    scale = np.asarray(laid.scale, dtype=float) if laid is not None else None
    if scale is None or scale.ndim:   # per-layer scales of another layout: start afresh
        scale = initial_scale(units, layers, canvas)[0]
    return np.stack([2 * units.half_w * scale, 2 * units.half_h * scale], axis=1)


def pick_device(device) -> str:
    """"cuda" when asked for or (device None/"auto") available, else "cpu"."""
    if device in (None, "auto"):
        return "cuda" if torch.cuda.is_available() else "cpu"
    if device not in ("cpu", "cuda") and not str(device).startswith("cuda:"):
        raise ValueError(f"device must be None, 'auto', 'cpu' or 'cuda', got {device!r}")
    if str(device).startswith("cuda") and not torch.cuda.is_available():
        raise ValueError(f"device={device!r} but CUDA is not available here; use 'cpu' or None")
    return str(device)


def placements(units: Units, layers, result: Result) -> pd.DataFrame:
    """The layout table: one row per unit (row, layer, x, y, angle, sx, sy, width, height,
    mark); ``mark`` indexes the layer's marks. When a layer binds ``count=`` or ``per=``,
    also ``units`` (the units each mark stands for) and ``drawn`` (the share of its box
    width drawn: below 1 for a partial mark; ``row`` is a mark's first row)."""
    names = np.array([layer.name for layer in layers], dtype=object)
    width = 2 * units.half_w * result.unit_scale
    height = 2 * units.half_h * result.unit_scale
    box = units.box_size
    table = pd.DataFrame({
        "row": units.rows, "layer": names[units.layer],
        "x": result.center[:, 0], "y": result.center[:, 1], "angle": result.angle,
        "sx": width / box[:, 0], "sy": height / box[:, 1], "width": width, "height": height,
        "mark": units.mark,
    })
    if any(layer.count is not None or layer.per is not None for layer in layers):
        table["units"] = units.amount   # the units each mark stands for
        table["drawn"] = units.clip     # the share of its box width drawn (a partial mark's < 1)
    return table


def layout(units: Units, layers, canvas, seed=0, device=None, on_frame=None, cancel=None,
           on_progress=None, frame_every: int = 3, scales: str = "shared", abort=None,
           pins=(), previous=None, reuse=None, settled: bool = True) -> Layout:
    """Build and solve the layout of ``units`` (``prepare.bind.bind(df, layers)``). Returns
    its ``Layout``.

    ``cancel()`` returning True ends the solve, which keeps its last step (none taken: the
    start). ``abort()`` (a Stop) returning True during the setup or before the first step
    raises ``Cancelled``: there is no layout to keep; but once ``on_frame`` has shown the
    start (a fresh, unpinned run shows it before the fields are made), a Stop keeps the
    start as the layout. ``pins``: ``design.pins.Pin``s held in place (``layout.pins``);
    ``previous``: a ``warm.snapshot`` to start from (None: a fresh start); ``reuse``: the
    last run's ``Layout.problem`` where only pins, rows, margins and point forces' places
    changed since (its layers, canvas, seed, scales and device are these): a warm run then
    moves only the marks the change reaches, where it can (``reflow``); after a moved force
    the full warm run reuses it (``reflow.resumed``), with no problem built. ``settled``
    False: ``previous`` is a full run cut short (a Stop, a newer drag message), which only
    the full warm run settles (on ``reuse``, where given)."""
    check_abort(abort)
    kept = Frames()

    def record(frame, *final):   # a caller's callback may also take final=True
        kept.add(frame)
        if on_frame is not None:
            on_frame(frame, *final)

    pinned, pin_xy, pin_angle = pinned_units(units, layers, pins)
    reforced = None   # the last problem, which the full warm run reuses
    if previous is not None and reuse is not None and \
            (not settled or [layer.forces for layer in layers] != list(reuse.forces)):
        reforced, reuse = resumed(reuse, units, layers), None
    if previous is not None and reuse is not None:
        with held():
            result = reflow(reuse, units, layers, canvas, previous, pinned, pin_xy, pin_angle,
                            on_frame=record, cancel=cancel)
        if result is not None:
            frames = kept.finish(np.column_stack([result.center, result.angle, result.unit_scale]))
            return Layout(placements=placements(units, layers, result), units=units,
                          scale=result.scale, canvas=tuple(canvas), frames=frames, result=result,
                          problem=reuse)
        kept = Frames()   # the full warm run's frames only
    # a fresh, unpinned start is the solver's start: it is shown before the fields are made
    early = record if previous is None and len(pinned) == 0 else None
    with held():   # the iterations' scratch tensors reuse the heap, not fresh pages
        problem = base = reforced if reforced is not None else build_problem(
            units, layers, canvas, seed, pick_device(device), scales=scales, abort=abort,
            on_start=early)
        if previous is not None:
            problem = warm_problem(problem, units, layers, canvas, previous, pinned, pin_xy)
        problem = pin_problem(problem, units, layers, canvas, pinned, pin_xy, pin_angle)
        result = solve(problem, on_frame=record, cancel=cancel, on_progress=on_progress,
                       frame_every=frame_every, start_frame=early is None)
        again = None if result.cancelled else finer.scales_past(base, units, result)
        if again is not None and not (cancel is not None and cancel()):
            fine = build_problem(units, layers, canvas, seed, pick_device(device), scales=scales,
                                 scale_at=again)
            problem = warm_problem(fine, units, layers, canvas, snapshot(units, layers, result),
                                   pinned, pin_xy)
            problem = pin_problem(problem, units, layers, canvas, pinned, pin_xy, pin_angle)
            if finer.hidden(problem, result.stats):
                counted = None if on_progress is None else finer.counting_on(on_progress, result)
                base, result = fine, finer.joined(result, solve(
                    problem, on_frame=record, cancel=cancel, on_progress=counted,
                    frame_every=frame_every, start_frame=False, settled=True))
    if result.iterations == 0 and early is None and abort is not None and abort():
        raise Cancelled("the layout was stopped before its first step")
    frames = kept.finish(np.column_stack([result.center, result.angle, result.unit_scale]))
    return Layout(placements=placements(units, layers, result), units=units, scale=result.scale,
                  canvas=tuple(canvas), frames=frames, result=result, axes=result.axes,
                  problem=base)
