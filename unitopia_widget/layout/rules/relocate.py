"""``relocate``: jammed marks of a closed container jump into the holes of its room.

Gradients only act where a mark's footprint lies, so a mark pressed into a
crowd never sees a hole a few radii away. Between settle windows the solver
moves the most overlapped marks that fit into the largest holes: a hole is a
container pixel free of ink, its size the distance to the nearest ink or to
the container's edge (the same room ``measure_room.py`` measures). A mark fits a hole
as large as the disc the start packs it as (``hole_need``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch
from scipy import ndimage

from ...design.encodings import footprint
from ..prepare.pack import thin
from ..step.raster import RasterGrid
from .measure_room import measures_room
from .state import Rule, forget, movable


@dataclass(frozen=True)
class RelocateSettings:
    share: float = 0.05            # share of a roomy layer's marks moved into holes per window
    jammed: float = 0.005          # overlap share that keeps a scale with room from growing
                                   # (half fill-scale's grow_overlap)
    early: int = 4                 # relocate in the first 1 / early of the iterations only
    least: float = 1.5             # the smallest hole worth filling, in median reaches


def hole_need(half_w: np.ndarray, half_h: np.ndarray, margin: np.ndarray,
              disc: np.ndarray) -> np.ndarray:
    """``(N,)`` the size of hole each mark fits, at scale 1, canvas px: the disc the start
    packs it as (``disc``, ``start.footprint_radius``: area-equivalent, widened for shapes
    less compact than a disc, margins included); a thin mark (``pack.thin``), which no disc
    stands for, needs its long half side with margin. ``half_w``, ``half_h``: box half sides
    ``(N,)``, ``margin (N,)``. (A mark's long half side alone kept a teardrop out of the
    holes its own shape fits: the tips' gaps between large drops stayed empty.)"""
    return np.where(thin(half_w, half_h), np.maximum(half_w, half_h) * footprint(margin), disc)


def unit_overlap(values: torch.Tensor, index: torch.Tensor, owner: torch.Tensor,
                 n_units: int, size: int) -> np.ndarray:
    """``(N,)`` each unit's overlapped alpha (raster px^2) over all layers' coverage.

    ``values (M,)`` sample alphas at flat raster ``index (M,)``, ``owner (M,)`` unit ids.
    """
    cover = torch.zeros(size, dtype=values.dtype, device=values.device).index_add_(0, index, values)
    total = cover[index]
    over = values * torch.relu(total - 1.0) / total.clamp_min(1e-6)
    out = torch.zeros(n_units, dtype=values.dtype, device=values.device).index_add_(0, owner, over)
    return out.cpu().numpy()


def holes(cover: np.ndarray, inside: np.ndarray, overlap: np.ndarray, radius: np.ndarray,
          members: np.ndarray, grid: RasterGrid, least: float, limit: int):
    """Moves ``[(unit, (x, y) canvas px), ...]``: overlapped marks into the largest holes.

    ``cover``/``inside``: ``(H, W)`` ink and container coverage; ``overlap``:
    ``(N,)`` overlapped alpha per unit; ``radius``: ``(N,)`` raster px, the disc a
    mark's footprint needs; ``members``: unit ids that may move; ``least``: raster px, the
    smallest hole worth filling (a median reach); at most ``limit`` moves. The
    most overlapped mark that fits goes first; each filled hole is stamped.
    """
    free = (cover < 0.5) & (inside >= 0.5)
    moved, left = [], [int(u) for u in members if overlap[u] > 0]
    # one distance transform; each stamp then lowers the distances near it only
    # (to the stamped disc: |q - p| - r), where they can change: within r + the largest
    dist = ndimage.distance_transform_edt(np.pad(free, 1))[1:-1, 1:-1]   # the raster's edge bounds too
    for _ in range(limit):
        i, j = np.unravel_index(int(np.argmax(dist)), dist.shape)
        size = float(dist[i, j])
        fits = [u for u in left if radius[u] <= size]
        if size <= max(least, 1.0) or not fits:
            break
        unit = max(fits, key=lambda u: overlap[u])
        left.remove(unit)
        moved.append((unit, ((j - grid.pad + 0.5) / grid.rho, (i - grid.pad + 0.5) / grid.rho)))
        r = max(radius[unit], 1.0)
        reach = int(np.ceil(r + size)) + 1
        rows = slice(max(i - reach, 0), min(i + reach + 1, dist.shape[0]))
        cols = slice(max(j - reach, 0), min(j + reach + 1, dist.shape[1]))
        yy, xx = np.ogrid[rows, cols]
        np.minimum(dist[rows, cols], np.maximum(np.hypot(yy - i, xx - j) - r, 0.0), out=dist[rows, cols])
    return moved


def relocate(p, ctl, place, optimizer, room: np.ndarray, cover: np.ndarray, values, index,
             owner, c: RelocateSettings = RelocateSettings()) -> bool:
    """Move the most overlapped free marks of roomy closed layers into their holes
    (``cover (H, W)`` the ink raster) and forget their Adam momentum. Returns whether any
    moved."""
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
            limit = max(1, int(c.share * mine.sum()))
            moves = holes(cover, inside[layer].reshape(p.grid.shape), overlap, radius,
                          np.nonzero(mine & free)[0], p.grid, c.least * float(np.median(reach[mine])), limit)
            with torch.no_grad():
                for unit, (x, y) in moves:
                    place.t[unit, 0], place.t[unit, 1] = x, y
            if moves:
                forget(optimizer, (place.t,), [unit for unit, _ in moves])
                moved = True
    return moved


class Relocate(Rule):
    """Each settle window in the first quarter of the iterations: in groups with room whose
    overlap still keeps the scale from growing (jammed), move the most overlapped free marks
    into the container's holes. Needed by necked and holed containers where a pile jams on
    one side while the other stays empty."""

    name = "relocate"
    window = True
    reads = ("room", "overlap_g", "iteration", "cover", "values", "index", "owner", "ctl")
    writes = ("place", "optimizer", "since_best")
    Settings = RelocateSettings

    def applies(self, s):
        return measures_room(s.p, s.ctl)

    def __call__(self, s):
        p, c = s.p, self.settings
        jammed = s.room & (s.overlap_g > c.jammed)
        if jammed.any() and s.iteration < p.max_iterations // c.early and \
                relocate(p, s.ctl, s.place, s.optimizer, jammed, s.cover, s.values.detach(),
                         s.index, s.owner, c):
            s.settle_more()
            return True
        return False
