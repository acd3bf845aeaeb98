"""From a design and a DataFrame to a solved layout: bind the rows into ``Units``
(``prepare.bind``), build the solver's ``Problem`` (``prepare.assemble``), warm-start and pin it
(``prepare.warm``, ``prepare.pins``), solve it (``solver``) and return the placements table."""
from __future__ import annotations

import numpy as np
import pandas as pd
import torch

from ..design.units import Units
from .prepare.assemble import build_problem, check_abort
from .prepare.bind import bind
from .prepare.pins import pin_problem, pinned_units
from .prepare.problem import Cancelled
from .prepare.warm import warm_problem
from .solver import Result, solve
from .step.heap import held


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
    mark); ``mark`` indexes the layer's marks."""
    names = np.array([layer.name for layer in layers], dtype=object)
    width = 2 * units.half_w * result.unit_scale
    height = 2 * units.half_h * result.unit_scale
    box = units.box_size
    return pd.DataFrame({
        "row": units.rows, "layer": names[units.layer],
        "x": result.center[:, 0], "y": result.center[:, 1], "angle": result.angle,
        "sx": width / box[:, 0], "sy": height / box[:, 1], "width": width, "height": height,
        "mark": units.mark,
    })


def layout(df, layers, canvas, seed=0, device=None, on_frame=None, cancel=None,
           on_progress=None, frame_every: int = 3, scales: str = "shared", abort=None,
           pins=(), previous=None):
    """Bind, build and solve. Returns ``(units, result, placements DataFrame)``.

    ``cancel()`` returning True ends the solve, which keeps its last step (none taken: the
    start). ``abort()`` (a Stop) returning True during the setup or before the first step
    raises ``Cancelled``: there is no layout to keep; but once ``on_frame`` has shown the
    start (a fresh, unpinned run shows it before the fields are made), a Stop keeps the
    start as the layout. ``pins``: ``design.pins.Pin``s held in place (``layout.pins``);
    ``previous``: a ``warm.snapshot`` to start from (None: a fresh start)."""
    units = bind(df, layers)
    check_abort(abort)
    pinned, pin_xy, pin_angle = pinned_units(units, layers, pins)
    # a fresh, unpinned start is the solver's start: it is shown before the fields are made
    early = on_frame if previous is None and len(pinned) == 0 else None
    with held():   # the iterations' scratch tensors reuse the heap, not fresh pages
        problem = build_problem(units, layers, canvas, seed, pick_device(device), scales=scales,
                                abort=abort, on_start=early)
        if previous is not None:
            problem = warm_problem(problem, units, layers, canvas, previous, pinned, pin_xy)
        problem = pin_problem(problem, units, layers, canvas, pinned, pin_xy, pin_angle)
        result = solve(problem, on_frame=on_frame, cancel=cancel, on_progress=on_progress,
                       frame_every=frame_every, start_frame=early is None)
    if result.iterations == 0 and early is None and abort is not None and abort():
        raise Cancelled("the layout was stopped before its first step")
    table = placements(units, layers, result)
    return units, result, table
