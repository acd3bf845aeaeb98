"""``uncross``: thin marks whose ink crosses are turned parallel and set side by side.

Two thin strokes that cross at an angle overlap by about ``w1 w2 / sin(angle)``:
sliding one leaves that unchanged while they still cross, and turning them
towards parallel first makes it larger, so gradients keep the X (they even open
it towards a right angle). Between settle windows and legalising rounds the
solver finds the crossing pairs in the render samples, turns both marks of each
to the bisector of their axes (the nearer way, mod 180 degrees: a long mark that
crosses its rows at a slant lies along them again) and moves the shorter one
across the longer one's line, so that the pair touches along its length: an
overlap that translations resolve.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ...design.encodings import footprint
from ..prepare.pack import thin
from .state import Rule, forget, movable


@dataclass(frozen=True)
class UncrossSettings:
    cross_angle: float = math.radians(5.0)  # long axes further apart than this cross (closer: alongside)
    least_ink: float = 0.5         # raster px^2 of shared ink (both alphas > 0.5) that make a crossing
    interior: float = 0.85         # the axes meet within this share of both half lengths (nearer an
                                   # end, sliding that mark along resolves the overlap)


def ink_pairs(values: torch.Tensor, index: torch.Tensor, owner: torch.Tensor, n_units: int):
    """``(pairs (P, 2) int, shared (P,) float)``: unit pairs whose ink shares raster px.

    Ink: samples with alpha > 0.5; ``values``/``index``/``owner`` ``(M,)`` as from
    ``render_samples``. A pixel inked by several marks counts for the neighbours in
    the (index, owner) order. One transfer to the host.
    """
    ink = values.detach() > 0.5
    idx, own = index[ink].long(), owner[ink]
    key = idx * n_units + own
    key = torch.sort(key).values
    idx, own = key // n_units, key % n_units
    same = (idx[1:] == idx[:-1]) & (own[1:] != own[:-1])
    pair = own[:-1][same] * n_units + own[1:][same]
    found, counts = torch.unique(pair, return_counts=True)
    found, counts = found.cpu().numpy(), counts.cpu().numpy().astype(float)
    return np.stack([found // n_units, found % n_units], 1), counts


def long_axis(angle: np.ndarray, half_w: np.ndarray, half_h: np.ndarray) -> np.ndarray:
    """``(N,)`` direction (radians, mod pi) of each box's long side at ``angle (N,)`` radians."""
    return np.where(half_w >= half_h, angle, angle + math.pi / 2)


def turns(pairs: np.ndarray, shared: np.ndarray, center: np.ndarray, angle: np.ndarray,
          half_w: np.ndarray, half_h: np.ndarray, turnable: np.ndarray,
          c: UncrossSettings = UncrossSettings()):
    """Moves ``[(unit, (x, y), angle), ...]`` that undo the crossings among ``pairs``.

    ``center (N, 2)`` px, ``angle (N,)`` radians, ``half_w``/``half_h`` ``(N,)``
    px (footprints, current scale), ``turnable (N,)`` bool (free to turn and to
    move). Both marks of a pair of thin marks whose long axes differ by more
    than ``c.cross_angle`` and meet away from their ends turn to the axes'
    bisector (the nearer way, mod 180 degrees), and the shorter one moves across
    the longer one's line, to the side its centre is on, until their boxes
    touch. A mark moves once per call, the most overlapped pairs first.
    """
    long, short = np.maximum(half_w, half_h), np.minimum(half_w, half_h)
    thin_free = thin(half_w, half_h) & turnable
    axis = long_axis(angle, half_w, half_h)
    moved, out = set(), []
    for k in np.argsort(-shared, kind="stable"):
        a, b = (int(u) for u in pairs[k])
        if shared[k] < c.least_ink or not (thin_free[a] and thin_free[b]) or a in moved or b in moved:
            continue
        gap = (axis[a] - axis[b] + math.pi / 2) % math.pi - math.pi / 2   # (-pi/2, pi/2]
        if abs(gap) <= c.cross_angle or not _interior(center[a], axis[a], long[a], center[b], axis[b],
                                                         long[b], c.interior):
            continue
        short_one, long_one = (a, b) if long[a] <= long[b] else (b, a)
        gap = gap if short_one == a else -gap          # the shorter's axis less the longer's
        common = axis[long_one] + gap / 2
        normal = np.array([-math.sin(common), math.cos(common)])
        offset = float((center[short_one] - center[long_one]) @ normal)
        side = 1.0 if offset >= 0 else -1.0
        x, y = center[short_one] + normal * (side * (short[short_one] + short[long_one]) - offset)
        out.append((short_one, (float(x), float(y)), float(angle[short_one] - gap / 2)))
        out.append((long_one, (float(center[long_one][0]), float(center[long_one][1])),
                    float(angle[long_one] + gap / 2)))
        moved.update((a, b))
    return out


def _interior(ca, axis_a, long_a, cb, axis_b, long_b, interior: float) -> bool:
    """Whether the long axes of two boxes meet inside both, within ``interior`` of their
    half lengths (away from their ends)."""
    da, db = np.array([math.cos(axis_a), math.sin(axis_a)]), np.array([math.cos(axis_b), math.sin(axis_b)])
    det = da[0] * -db[1] + db[0] * da[1]          # solve ca + s da = cb + t db
    if abs(det) < 1e-9:
        return False
    d = cb - ca
    s = (d[0] * -db[1] + db[0] * d[1]) / det
    t = (da[0] * d[1] - da[1] * d[0]) / det
    return abs(s) < interior * long_a and abs(t) < interior * long_b


def uncross(p, ctl, place, optimizer, values, index, owner,
            c: UncrossSettings = UncrossSettings()) -> bool:
    """Turn thin marks whose ink crosses parallel, side by side, and forget their Adam
    momentum. Returns whether any moved."""
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
                      place.theta.cpu().numpy().astype(float), p.half_w * scale, p.half_h * scale,
                      free, c)
        for unit, (x, y), angle in moves:
            place.t[unit, 0], place.t[unit, 1], place.theta[unit] = x, y, angle
    if moves:
        forget(optimizer, (place.t, place.theta), [unit for unit, _, _ in moves])
    return bool(moves)


class Uncross(Rule):
    """Each settle window (and each legalising round, run by ``legalize``): thin marks whose
    ink crosses turn side by side; no gradient undoes a crossing. Needed by hair, strands
    and rotating rectangles."""

    name = "uncross"
    window = True
    reads = ("values", "index", "owner", "ctl")
    writes = ("place", "optimizer", "since_best")
    Settings = UncrossSettings

    def applies(self, s):
        return bool((s.place.turnable & thin(s.p.half_w, s.p.half_h)).any())

    def __call__(self, s):
        if uncross(s.p, s.ctl, s.place, s.optimizer, s.values, s.index, s.owner, self.settings):
            s.settle_more()
            return True
        return False
