"""``drop``: open piles under a directional pull dropped onto what holds them, by their ink.

A pile settles until its marks press on each other's footprints as the layout's raster
sees them: a big mark is sampled a block of pixels at a time there, and the force that
presses the pile weakens once it rests, so marks whose boxes interlock (thin arrows in
staggered rows, the arms of stars) stop short of where their ink would meet. After the
last iteration every movable unit of such a pile falls along the pull, by whole pixels of a
fine raster (``step.fine``: footprints cut at alpha 0.5, margins included), until its
footprint would meet another footprint it may not share a pixel with, or leave its region.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ...design.encodings import footprint
from ..step.fine import FineRaster, draw
from .legalize import extents, pull_of, shadows
from .state import Rule, movable


@dataclass(frozen=True)
class DropSettings:
    fine_rho: float = 2.0          # fine raster px per canvas px
    max_fine: int = 24_000_000     # fine raster px over all layer slabs at most (more get coarser)
    rounds: int = 6                # passes; in each, every unit falls at once (those above follow)
    gap: float = 1.0               # canvas px each unit stops short of what it meets: a contact
                                   # closer reads as overlap on a raster made for thin marks (finer)


def piles(s) -> list:
    """``[(pull (2,), units (n,) int), ...]``: the movable units of the layers pulled by
    directional forces alone at a fixed (open) scale, one entry per direction of pull
    (units bound to ``x=``/``y=`` positions keep their places)."""
    free = movable(s.place)
    if s.p.anchor is not None:
        free &= ~(s.p.anchor.mask.cpu().numpy() > 0).any(1)
    out = {}
    for members, forces in s.force_layers or ():
        m = members.cpu().numpy()
        pull = pull_of(forces)
        if pull is None or s.ctl.free[s.ctl.unit_group[int(m[0])]]:
            continue
        m = m[free[m]]
        if len(m):
            out.setdefault(tuple(np.round(pull, 9)), []).append(m)
    return [(np.asarray(key), np.concatenate(groups)) for key, groups in out.items()]


def reach(fine: FineRaster, units: np.ndarray, pull: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """``(n,)`` fine px each of ``units`` can fall along ``pull (2,)`` (at most ``limit (n,)``)
    before a pixel of its footprint meets one it collides with, or one outside its region or
    the raster, the others staying where they are. All fall at once: two units that each
    keep off the other's place keep off each other (a pull is one direction). The fall is
    the digital line of whole pixels nearest the pull; a step of it moves a unit onto new
    pixels only at its front for that step (pixels the step does not carry onto its own),
    so only those are looked up, each step."""
    rows, cols = fine.grid.shape
    size = rows * cols
    dev = fine.index.device
    k_max = int(limit.max(initial=0))
    fell = np.zeros(len(units), dtype=np.int64)
    if k_max <= 0:
        return fell
    ks = np.arange(k_max + 1)
    offsets = np.stack([np.round(ks * pull[1]), np.round(ks * pull[0])], 1).astype(np.int64)
    kinds, kind_of_step = np.unique(offsets[1:] - offsets[:-1], axis=0, return_inverse=True)
    counts = torch.as_tensor(fine.bounds[units + 1] - fine.bounds[units], device=dev)
    which = torch.repeat_interleave(torch.arange(len(units), device=dev), counts)
    pix = torch.cat([fine.index[fine.bounds[i]:fine.bounds[i + 1]] for i in units])
    own = torch.sort(which * size + pix).values   # each unit's own pixels, to step over them
    r, c = pix // cols, pix % cols

    def owned(w, rr, cc):
        key = w * size + rr.clamp(0, rows - 1) * cols + cc.clamp(0, cols - 1)
        hit = own[torch.searchsorted(own, key).clamp(max=len(own) - 1)] == key
        return hit & (rr >= 0) & (rr < rows) & (cc >= 0) & (cc < cols)

    fronts = []   # per kind of step: (unit, row, column) of the pixels that step moves onto new ones
    for dr, dc in kinds:
        front = ~owned(which, r + int(dr), c + int(dc))
        fronts.append([which[front], r[front], c[front]])
    lay_of = fine.layer[torch.as_tensor(units, device=dev)]
    falling = torch.as_tensor(limit > 0, device=dev)
    limit_t = torch.as_tensor(limit, device=dev)
    for k in range(1, k_max + 1):
        front = fronts[kind_of_step[k - 1]]
        keep = falling[front[0]]
        if not bool(keep.all()):
            front[:] = [v[keep] for v in front]
        w, rr, cc = front[0], front[1] + int(offsets[k, 0]), front[2] + int(offsets[k, 1])
        on = (rr >= 0) & (rr < rows) & (cc >= 0) & (cc < cols)
        q = rr.clamp(0, rows - 1) * cols + cc.clamp(0, cols - 1)
        lay = lay_of[w]
        hit = ~on | ~fine.inside[lay, q] | (fine.seen[lay, q] - owned(w, rr, cc).float() > 0.5)
        stop = falling & ((torch.bincount(w[hit], minlength=len(units)) > 0) | (limit_t < k))
        if bool(stop.any()):
            done = stop.cpu().numpy()
            fell[done] = np.minimum(k - 1, limit[done])
            falling &= ~stop
            if not bool(falling.any()):
                break
    fell[falling.cpu().numpy()] = k_max
    return fell


@torch.no_grad()
def fall(s, c: DropSettings = DropSettings()) -> np.ndarray:
    """``(N, 2)`` canvas px each unit of the ``piles`` of the solver's state ``s`` falls."""
    p, place = s.p, s.place
    center, angle = place.transforms()
    unit_scale = s.ctl.unit_scale()
    fine = draw(p, center.detach(), angle.detach(), unit_scale, place.rotating(), c.fine_rho,
                c.max_fine)
    rho, cols = fine.grid.rho, fine.grid.shape[1]
    xy = center.detach().cpu().numpy().astype(float)
    turn = angle.detach().cpu().numpy().astype(float)
    foot = footprint(p.margin) * unit_scale
    moved = np.zeros((len(p.layer), 2))
    for pull, units in piles(s):
        # a layer resting on another may not fall past the top of its boxes (``shadows``)
        barrier = np.full(len(p.layer), np.inf)
        if p.terms.rests is not None:
            side = np.array([-pull[1], pull[0]])
            along = extents(p.half_w * foot, p.half_h * foot, turn, pull)
            across = extents(p.half_w * foot, p.half_h * foot, turn, side)
            barrier = shadows(xy + moved, along, across, pull, p.layer,
                              p.terms.rests.cpu().numpy() > 0, units)
        for _ in range(c.rounds):
            room = (barrier[units] - (xy[units] + moved[units]) @ pull) * rho
            limit = np.where(np.isfinite(room), np.floor(np.maximum(room, 0.0)),
                             float(sum(fine.grid.shape))).astype(np.int64)
            steps = np.maximum(reach(fine, units, pull, limit) - math.ceil(c.gap * rho), 0)
            if not steps.any():
                break
            for i, k in zip(units[steps > 0], steps[steps > 0]):
                dr, dc = int(round(k * pull[1])), int(round(k * pull[0]))
                fine.lift(i)
                fine.index[fine.bounds[i]:fine.bounds[i + 1]] += dr * cols + dc
                fine.put(i)
                moved[i] += (dc / rho, dr / rho)
    return moved


class Drop(Rule):
    """Once, after the last iteration of a layout that was not cancelled: the units of open
    piles under directional forces fall along their pull until their footprints meet (``fall``;
    those of a layer resting on another no further than its boxes' top, as ``legalize.press``).
    Needed by open piles of marks whose boxes interlock or whose ink the layout's raster
    samples coarsely: thin marks above all. Corpus, seeds 0-4, all 15 directional piles
    that moved pull further: thin arrows pushed right (m095) 0.55 -> 0.68, thin bars (m109)
    0.50 -> 0.62, the thin-push kind 0.65 -> 0.69, spiky flakes (m029) 0.37 -> 0.41; strata
    in order, thin arrows (m081) 0.95 -> 0.99, stars on a slope 0.94 -> 0.97."""

    name = "drop"
    phase = "finish"
    reads = ("ctl", "place", "force_layers")
    writes = ("place",)
    Settings = DropSettings

    def applies(self, s):
        return bool(s.force_layers) and bool(piles(s))

    def __call__(self, s):
        if not self.applies(s):
            return False
        move = fall(s, self.settings)
        if not move.any():
            return False
        with torch.no_grad():
            s.place.t += torch.as_tensor(move, dtype=s.place.t.dtype, device=s.place.t.device)
        return True
