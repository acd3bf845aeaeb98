"""``strays``: a mark that ends outside its container is brought back into it.

The loss pulls ink outside a container back in with a gradient only near the container's
edge, and a mark that a gradient step carries past the wall late in a layout (a small one
squeezed between the wall and a large neighbour as the settle runs out) ends wholly outside
it, where nothing moves it again. After the last iteration, every movable unit whose
centre lies outside its region moves to the nearest spot (on the fine raster of
``step.fine``) where its footprint is wholly inside and on no footprint it collides with;
where no such spot is within reach, it stays.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ..step.fine import draw
from .state import Rule, shift, unbound


@dataclass(frozen=True)
class StraysSettings:
    fine_rho: float = 2.0          # fine raster px per canvas px
    max_fine: int = 24_000_000     # fine raster px over all layer slabs at most (more get coarser)
    reach: float = 0.25            # the farthest spot looked at, as a share of the canvas diagonal
    spacing: float = 0.25          # spots looked at this share of the unit's footprint radius apart
    chunk: int = 4_000_000         # fine pixels looked up at once


def outside(p, center: np.ndarray, units: np.ndarray) -> np.ndarray:
    """Bool ``(n,)``: which of ``units (n,)`` have their centre (``center (N, 2)`` canvas px)
    outside their layer's region (its coverage under half at that pixel, or off the canvas)."""
    rho = p.grid.rho
    out = np.zeros(len(units), bool)
    for a in np.unique(p.layer[units]):
        mine = p.layer[units] == a
        cover = p.regions[a].coverage(p.grid.canvas, rho)
        h, w = cover.shape
        xy = center[units[mine]]
        j, i = np.floor(xy[:, 0] * rho).astype(int), np.floor(xy[:, 1] * rho).astype(int)
        on = (i >= 0) & (i < h) & (j >= 0) & (j < w)
        inside = np.zeros(len(xy), bool)
        inside[on] = cover[i[on], j[on]] >= 0.5
        out[mine] = ~inside
    return out


@torch.no_grad()
def bring_back(p, place, unit_scale: np.ndarray, c: StraysSettings = StraysSettings()) -> np.ndarray:
    """``(N, 2)`` canvas px each unit of the solver's ``Problem`` ``p`` moves (0 for most):
    the movable units of ``place`` (not bound to positions) whose centres lie outside their
    regions (``outside``), to the nearest free spot wholly inside, looked for on a grid
    ``spacing`` footprint radii apart out to ``reach`` of the canvas diagonal."""
    center, angle = place.transforms()
    xy = center.detach().cpu().numpy().astype(float)
    moved = np.zeros_like(xy)
    if not p.regions:
        return moved
    free = np.flatnonzero(unbound(p, place))   # a unit bound to an x=/y= position keeps it
    strays = free[outside(p, xy, free)]
    if not len(strays):
        return moved
    fine = draw(p, center.detach(), angle.detach(), unit_scale, place.rotating(), c.fine_rho,
                c.max_fine)
    rows, cols = fine.grid.shape
    rho = fine.grid.rho
    far = c.reach * math.hypot(rows, cols)
    for i in strays:
        pix = fine.index[fine.bounds[i]:fine.bounds[i + 1]]
        if not len(pix):
            continue
        lay = int(fine.layer[i])
        fine.lift(i)
        r, col = pix // cols, pix % cols
        step = max(1, int(c.spacing * math.sqrt(len(pix) / math.pi)))
        span = np.arange(-int(far), int(far) + 1, step)
        dy, dx = np.meshgrid(span, span, indexing="ij")
        near = np.argsort(np.hypot(dy, dx).ravel(), kind="stable")
        offsets = torch.as_tensor(np.stack([dy.ravel()[near], dx.ravel()[near]], 1), device=pix.device)
        best = None
        for part in torch.split(offsets, max(1, c.chunk // len(pix))):
            rr, cc = r[None] + part[:, :1], col[None] + part[:, 1:]      # (d, P)
            on = ((rr >= 0) & (rr < rows) & (cc >= 0) & (cc < cols)).all(1)
            q = rr.clamp(0, rows - 1) * cols + cc.clamp(0, cols - 1)
            clear = on & (fine.inside[lay, q] & (fine.seen[lay, q] < 0.5)).all(1)
            if bool(clear.any()):
                best = part[int(torch.nonzero(clear)[0])]
                break
        if best is not None:
            fine.index[fine.bounds[i]:fine.bounds[i + 1]] += int(best[0]) * cols + int(best[1])
            moved[i] = (int(best[1]) / rho, int(best[0]) / rho)
        fine.put(i)
    return moved


class Strays(Rule):
    """Once, after the last iteration of a layout that was not cancelled: a movable unit whose
    centre ended outside its container moves to the nearest free spot wholly inside it
    (``bring_back``). Needed by any layout where a late step carries a small mark past the
    wall. Corpus, seeds 0-4, ink outside: small triangles piled on a slope (m070) 0.05 ->
    0.00% (at seed 4 one ended wholly outside, 0.25%), thin bars in twin discs (m109) 0.08 ->
    0.04%, thin bars around a point (m056) 0.11 -> 0.09%."""

    name = "strays"
    phase = "finish"
    reads = ("ctl", "place")
    writes = ("place",)
    Settings = StraysSettings

    def applies(self, s):
        return bool(s.p.regions)

    def __call__(self, s):
        if not self.applies(s):
            return False
        return shift(s.place, bring_back(s.p, s.place, s.ctl.unit_scale(), self.settings))
