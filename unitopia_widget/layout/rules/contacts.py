"""``contacts``: contacts finer than the layout's raster, cleared on a finer one after the solve.

The solver judges the marks on a raster of ``grid.rho`` px per canvas px, aimed at a
mean footprint ``prepare.assemble.TARGET_RADIUS`` raster px across, so two marks that touch less than a
raster pixel deep can read as apart there. That is little of all the ink, but much of a
small ring's, and hollow marks are held to a per-unit contract (``legalize.unit_crowding``).
Their layouts are drawn once more at ``fine_rho`` px per canvas px, each footprint cut at
alpha 0.5 as a checker renders a unit. Every movable unit with more than ``clear_share``
of its footprint pixels on a footprint it collides with, or outside its region, moves by
whole fine pixels, at most one layout raster pixel, to the nearby spot where the fewest
of its pixels are; it stays where it is unless that spot has fewer than where it is. A
pixel two footprints share counts for both, so every move lowers the overlap in all.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ..step.fine import draw
from .state import Rule, movable, shift


@dataclass(frozen=True)
class ContactsSettings:
    fine_rho: float = 2.0          # fine raster px per canvas px: a checker's 2x supersampling
    max_fine: int = 24_000_000     # fine raster px over all layer slabs at most (more get coarser)
    clear_share: float = 0.002     # share of a unit's footprint pixels overlapped or outside above which it moves
    rounds: int = 3                # passes over the units still above it
    chunk: int = 4_000_000         # fine pixels looked up at once when a unit tries its nearby spots


@torch.no_grad()
def clear(p, center: torch.Tensor, angle: torch.Tensor, unit_scale: np.ndarray,
          free: np.ndarray, rotating: np.ndarray, c: ContactsSettings = ContactsSettings()) -> np.ndarray:
    """``(N, 2)`` canvas px: the move of each unit that clears its contacts (0 for most).

    ``p``: the solver's ``Problem`` (its ``regions`` give each layer's allowed region);
    ``center (N, 2)`` canvas px and ``angle (N,)`` radians, the solved transforms;
    ``unit_scale (N,)``; ``free (N,)`` bool, the units that may move; ``rotating (N,)`` bool,
    units whose patch must hold any rotation (``Placement.rotating``)."""
    n = len(p.layer)
    shifted = np.zeros((n, 2), dtype=np.int64)   # (dy, dx) fine px each unit has moved
    if not free.any():
        return np.zeros((n, 2))
    fine = draw(p, center, angle, unit_scale, rotating, c.fine_rho, c.max_fine)
    grid, rho, dev = fine.grid, fine.grid.rho, center.device
    index, owner, bounds, layer = fine.index, fine.owner, fine.bounds, fine.layer
    seen, inside = fine.seen, fine.inside
    cols = grid.shape[1]
    reach = max(int(rho / p.grid.rho), 1)                     # one layout raster pixel, fine px
    dy, dx = np.mgrid[-reach:reach + 1, -reach:reach + 1]
    near = dy ** 2 + dx ** 2 <= reach ** 2
    offsets = torch.as_tensor(np.stack([dy[near], dx[near]], 1), device=dev)   # (D, 2)
    stay = int(np.flatnonzero((dy[near] == 0) & (dx[near] == 0))[0])
    cost_of_move = (offsets.float() ** 2).sum(1) * 1e-3        # ties go to the shortest move
    for _ in range(c.rounds):
        share = _crowding(seen, inside, index, owner, layer, n)
        bad = (share > c.clear_share) & free
        if not bad.any():
            break
        moved = False
        for i in np.argsort(-share * bad)[: int(bad.sum())]:
            pix = index[bounds[i]:bounds[i + 1]]
            a = int(p.layer[i])
            fine.lift(i)                                         # the unit lifted off the raster
            crowded = _crowded_at(seen[a], inside[a], pix, offsets, grid.shape, c.chunk)
            within = ((offsets + torch.as_tensor(shifted[i], device=dev)) ** 2).sum(1) <= reach ** 2
            best = int(torch.argmin(torch.where(within, crowded + cost_of_move, math.inf)))
            if crowded[best] < crowded[stay]:
                pix += int(offsets[best, 0]) * cols + int(offsets[best, 1])   # a view: index too
                shifted[i] += offsets[best].cpu().numpy()
                moved = True
            fine.put(i)
        if not moved:
            break
    return shifted[:, ::-1] / rho   # (dx, dy) canvas px


def _crowded_at(seen: torch.Tensor, inside: torch.Tensor, pix: torch.Tensor,
                offsets: torch.Tensor, shape: tuple[int, int], chunk: int) -> torch.Tensor:
    """``(D,)`` float: for each of the ``offsets (D, 2)`` (rows, columns), how many of the
    unit's ``pix (n,)`` (flat fine indices) would lie on a footprint in ``seen (S,)`` or
    outside ``inside (S,)``; inf where some would leave the raster. In chunks of offsets,
    so that a large unit does not hold ``D x n`` indices at once."""
    rows, cols = shape
    r, c = pix // cols, pix % cols
    out = []
    for part in torch.split(offsets, max(1, chunk // max(len(pix), 1))):
        r2, c2 = r[None] + part[:, :1], c[None] + part[:, 1:]          # (d, n)
        on = ((r2 >= 0) & (r2 < rows) & (c2 >= 0) & (c2 < cols)).all(1)
        spot = r2.clamp(0, rows - 1) * cols + c2.clamp(0, cols - 1)
        crowded = ((seen[spot] > 0.5) | ~inside[spot]).sum(1).float()
        out.append(torch.where(on, crowded, math.inf))
    return torch.cat(out)


def _crowding(seen, inside, index, owner, layer, n: int) -> np.ndarray:
    """``(N,)``: the share of each unit's fine pixels on another colliding footprint or outside."""
    lay = layer[owner]
    hit = ((seen[lay, index] > 1.5) | ~inside[lay, index]).float()
    area = torch.bincount(owner, minlength=n).clamp_min(1).float()
    return (torch.bincount(owner, weights=hit, minlength=n) / area).cpu().numpy()


class Contacts(Rule):
    """Once, after the last iteration of a layout that was not cancelled, with hollow marks
    (``ink_share`` under 1) and regions to keep them in: hollow marks are held to a per-unit
    contract, so the free units move off the contacts finer than the raster (``clear``).
    Units on a curve track or held stay. Needed by rings and other hollow marks."""

    name = "contacts"
    phase = "finish"
    reads = ("ctl", "place")
    writes = ("place",)
    Settings = ContactsSettings

    def applies(self, s):
        p = s.p
        return bool(p.regions) and p.ink_share is not None and bool((p.ink_share < 1.0).any())

    def __call__(self, s):
        if not self.applies(s):
            return False
        place = s.place
        center, angle = place.transforms()
        shift(place, clear(s.p, center.detach(), angle.detach(), s.ctl.unit_scale(),
                           movable(place), place.rotating(), self.settings))
        return True
