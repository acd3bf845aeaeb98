"""Moves the solver makes by hand, outside the gradient: jammed marks into holes
(``relocate.py``), crossing thin marks side by side (``uncross.py``), buried marks of a
stratum back onto its surface (``surface.py``), and what Adam must forget or rescale when
it happens. ``p`` is the solver's ``Problem``."""
from __future__ import annotations

import numpy as np
import torch

from ...design.encodings import footprint
from ..prepare.pack import thin
from ..step.placement import Placement
from .relocate import hole_need, holes, unit_overlap
from ..step.scales import Scales
from .surface import buried
from .uncross import ink_pairs, turns


def movable(place: Placement) -> np.ndarray:
    """Bool ``(N,)``: units the solver may move by hand: released, and not on a curve track."""
    free = place.keep[:, 0].cpu().numpy() > 0
    for track in place.tracks:
        free[track.index.cpu().numpy()] = False
    return free


def forget(optimizer, params, units: list) -> None:
    """Clear Adam's moments of ``units`` in each of ``params``: they were moved by hand."""
    for param in params:
        state = optimizer.state.get(param, {})
        for key in ("exp_avg", "exp_avg_sq"):
            if key in state:
                state[key][units] = 0.0


def relocate(p, ctl: Scales, place: Placement, optimizer, room: np.ndarray,
              cover: np.ndarray, values, index, owner) -> bool:
    """Move the most overlapped free marks of roomy closed layers into their holes
    (``relocate.py``; ``cover (H, W)`` the ink raster) and forget their Adam momentum.
    Returns whether any moved."""
    overlap = unit_overlap(values, index, owner, len(p.layer), p.terms.penalty.shape[1])
    inside = p.terms.inside_host
    scale = ctl.unit_scale()
    reach = p.reach * scale * p.grid.rho
    radius = hole_need(p.half_w, p.half_h, p.margin, p.disc) * scale * p.grid.rho
    free, moved = movable(place), False
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
                forget(optimizer, (place.t,), [unit for unit, _ in moves])
                moved = True
    return moved


def rescale_moments(optimizer, param: torch.Tensor, ratio: float) -> None:
    """Scale Adam's moments of ``param`` as if its gradients had been ``ratio`` times as large
    all along: the steps stay as they were, and a gradient that shrinks by ``ratio`` now
    still moves the units at full pace instead of waiting for the second moment to forget."""
    state = optimizer.state.get(param)
    if state:
        state["exp_avg"].mul_(ratio)
        state["exp_avg_sq"].mul_(ratio * ratio)


def uncross(p, ctl: Scales, place: Placement, optimizer, values, index, owner) -> bool:
    """Turn thin marks whose ink crosses parallel, side by side (``uncross.py``), and forget
    their Adam momentum. Returns whether any moved."""
    free = place.turnable & thin(p.half_w, p.half_h)
    if not free.any():   # no thin mark turns: no readback
        return False
    free &= movable(place)
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
        forget(optimizer, (place.t, place.theta), [unit for unit, _, _ in moves])
    return bool(moves)


def resurface(p, place: Placement, optimizer, values, index, owner) -> bool:
    """Lift the free marks buried in their stratum's obstacle back onto its surface
    (``surface.py``) and forget their Adam momentum. Returns whether any moved."""
    if p.terms.rests is None:   # no layer rests on another (the engine leaves it None)
        return False
    with torch.no_grad():
        center = place.transforms()[0].cpu().numpy().astype(float)
        lifts = buried(p.terms, values.detach(), index, owner, p.layer, center, movable(place),
                       p.grid.rho)
        for unit, (dx, dy) in lifts:
            place.t[unit, 0] += dx
            place.t[unit, 1] += dy
    if lifts:
        forget(optimizer, (place.t,), [unit for unit, _ in lifts])
    return bool(lifts)
