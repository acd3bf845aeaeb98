"""``exchange``: a thin mark that pokes out of its closed container trades places with a
shorter one where it fits.

Thin marks start wherever the seeded order puts them, so a long one can sit at the rim
where only a short one fits. Its ink outside keeps the fill controller from growing the
scale, and unless it may turn along the rim, a gradient cannot move it inwards through the
marks packed around it, so the container stays part empty (strands of spread heights in a
blob: 1 to 9% over seeds, where a lucky order left 0.4%). Between settle windows each
poked-out thin mark that does not turn, longest first, trades places with a shorter mark
of its layer such that each one's capsule (the box's short half side, along its long axis
to within that of its ends) lies inside at the other's place; of those, the first in an
arbitrary order (a hash of the two units), not the nearest, which moved long marks just
inwards and graded their lengths toward the centre. Trades are made only where they take
a group's ink outside below where its scale grows. Sizes show in where marks lie only
where the container cannot hold a mark.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from ...design.encodings import footprint
from ..prepare.pack import thin
from ..step.distance import edt
from .measure_room import measures_room
from .state import Rule, forget, movable
from .uncross import long_axis


@dataclass(frozen=True)
class ExchangeSettings:
    poking: float = 0.02           # share of a mark's ink outside its container that pokes out
    early: int = 2                 # exchange in the first 1 / early of the iterations only


def unit_outside(values: np.ndarray, index: np.ndarray, owner: np.ndarray, layer: np.ndarray,
                 inside: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(ink (N,), outside (N,))``: each unit's sampled alpha, and the part of it outside
    its layer's fill target.

    ``values``/``index``/``owner`` ``(M,)`` the render samples; ``layer (N,)``; ``inside``
    ``(L, S)`` each layer's container coverage on the flat raster."""
    n = len(layer)
    ink = np.bincount(owner, weights=values, minlength=n)
    return ink, np.bincount(owner, weights=values * (1.0 - inside[layer[owner], index]), minlength=n)


def capsules(half_w: np.ndarray, half_h: np.ndarray, angle: np.ndarray):
    """``(girth (N,), arm (N, 2))``: each box's short half side and half its spine along
    its long axis (to within ``girth`` of its ends), in the units of ``half_w``/``half_h``;
    ``angle (N,)`` radians."""
    girth = np.minimum(half_w, half_h)
    axis = long_axis(angle, half_w, half_h)
    spine = np.maximum(half_w, half_h) - girth
    return girth, spine[:, None] * np.stack([np.cos(axis), np.sin(axis)], 1)


def shuffled(units: np.ndarray, salt: int) -> np.ndarray:
    """``(k,)`` uint64 keys that order ``units (k,)`` arbitrarily but reproducibly, another
    order for each ``salt``: splitmix64's mix of unit and salt (no mark's size or place
    enters it; arrays of uint64 wrap around silently)."""
    key = units.astype(np.uint64) + np.full(len(units), salt, dtype=np.uint64) \
        * np.uint64(0x9E3779B97F4A7C15)
    for shift, factor in ((30, 0xBF58476D1CE4E5B9), (27, 0x94D049BB133111EB)):
        key = (key ^ (key >> np.uint64(shift))) * np.uint64(factor)
    return key ^ (key >> np.uint64(31))


def trades(center: np.ndarray, girth: np.ndarray, arm: np.ndarray, poking: np.ndarray,
           members: np.ndarray, depth: np.ndarray) -> list[tuple[int, int]]:
    """Pairs ``[(long unit, short unit), ...]`` to swap places.

    ``center (N, 2)``, ``girth (N,)``, ``arm (N, 2)`` raster px; ``poking (N,)`` bool;
    ``members``: unit ids of one layer that may move; ``depth (H, W)`` raster px to the
    container's edge. The longest poked-out mark first, each with a shorter mark not poking
    out such that both capsules lie inside at each other's centre (a trade that leaves either
    poking out only stirs the layout), the first of them in ``shuffled`` order."""
    h, w = depth.shape

    def room(at, arms, girths):
        """``(k,)`` the least depth along each capsule's spine, sampled a girth apart (a
        long one can cross a concave rim between its ends), centred at ``at (k, 2)``."""
        count = 2 * int(np.ceil(np.max(np.hypot(*arms.T) / np.maximum(girths, 1.0)))) + 1
        least = np.full(len(at), np.inf)
        for k in np.linspace(-1.0, 1.0, count):
            xy = at + k * arms
            j = np.clip(np.round(xy[:, 0]).astype(int), 0, w - 1)
            i = np.clip(np.round(xy[:, 1]).astype(int), 0, h - 1)
            least = np.minimum(least, depth[i, j])
        return least

    size = girth + np.hypot(*arm.T)
    pairs, used = [], np.zeros(len(size), dtype=bool)
    for u in members[np.argsort(-size[members], kind="stable")]:
        if not poking[u] or used[u]:
            continue
        others = members[~used[members] & ~poking[members] & (size[members] < size[u])]
        if not len(others):
            continue
        here = np.repeat(center[u][None], len(others), 0)
        fits = others[(room(center[others], np.repeat(arm[u][None], len(others), 0),
                            np.full(len(others), girth[u])) >= girth[u])
                      & (room(here, arm[others], girth[others]) >= girth[others])]
        if not len(fits):
            continue
        v = int(fits[np.argmin(shuffled(fits, int(u)))])
        pairs.append((int(u), v))
        used[[u, v]] = True
    return pairs


def exchange(p, ctl, place, optimizer, groups: np.ndarray, grow: np.ndarray, values, index,
             owner, c: ExchangeSettings = ExchangeSettings()) -> bool:
    """Swap the places of poked-out thin marks of the closed layers in ``groups (G,)`` bool
    with shorter ones where they fit, where that takes a group's ink outside below ``grow
    (G,)`` (the share below which its scale grows into room: else the trades only stir it,
    as when one mark that caps the scale pokes out), and forget the moved marks' Adam
    momentum. Returns whether any moved."""
    inside = p.terms.inside_host
    ink, out = unit_outside(values.detach().cpu().numpy().astype(float), index.cpu().numpy(),
                            owner.cpu().numpy(), p.layer, inside)
    scale = ctl.unit_scale() * footprint(p.margin) * p.grid.rho
    with torch.no_grad():
        center, angle = place.transforms()
        center = center.cpu().numpy().astype(float) * p.grid.rho + p.grid.pad
        girth, arm = capsules(p.half_w * scale, p.half_h * scale, angle.cpu().numpy().astype(float))
    slim = thin(p.half_w, p.half_h) & ~place.turnable   # a turnable one turns along the rim
    free, swapped = movable(place), []
    for g in np.nonzero(groups)[0]:
        pairs, mine_g = [], ctl.group[p.layer] == g
        for layer in np.nonzero(ctl.group == g)[0]:
            mine = (p.layer == layer) & free
            poking = mine & slim & (out > c.poking * ink)
            if poking.any() and inside[layer].any():
                depth = edt(inside[layer].reshape(p.grid.shape) >= 0.5)
                pairs += trades(center, girth, arm, poking, np.nonzero(mine)[0], depth)
        left = out[mine_g].sum() - out[[u for u, _ in pairs]].sum()
        if pairs and left < grow[g] * ink[mine_g].sum():
            swapped += pairs
    with torch.no_grad():
        for u, v in swapped:
            place.t[[u, v]] = place.t[[v, u]].clone()
    if swapped:
        forget(optimizer, (place.t,), [unit for pair in swapped for unit in pair])
    return bool(swapped)


class Exchange(Rule):
    """Each settle window in the first half of the iterations: in groups with room whose
    ink outside keeps the scale from growing (``State.grow_outside``), poked-out thin marks
    trade places with shorter ones where they fit. Needed by thin marks of spread lengths
    that do not turn (strands, arrows) in closed containers, started in the seeded order."""

    name = "exchange"
    window = True
    reads = ("room", "outside_g", "grow_outside", "iteration", "values", "index", "owner", "ctl")
    writes = ("place", "optimizer", "since_best")
    Settings = ExchangeSettings

    def applies(self, s):
        return measures_room(s.p, s.ctl) and bool((thin(s.p.half_w, s.p.half_h)
                                                    & ~s.place.turnable).any())

    def __call__(self, s):
        p, c = s.p, self.settings
        if s.room is None or s.grow_outside is None or s.iteration >= p.max_iterations // c.early:
            return False
        groups = s.room & (s.outside_g >= s.grow_outside)
        if groups.any() and exchange(p, s.ctl, s.place, s.optimizer, groups, s.grow_outside,
                                     s.values, s.index, s.owner, c):
            s.settle_more()
            return True
        return False
