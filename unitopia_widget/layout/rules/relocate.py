"""Relocation: jammed marks of a closed container jump into the holes of its room.

Gradients only act where a mark's footprint lies, so a mark pressed into a
crowd never sees a hole a few radii away. Between settle windows the solver
moves the most overlapped marks that fit into the largest holes: a hole is a
container pixel free of ink, its size the distance to the nearest ink or to
the container's edge (the same room ``room.py`` measures). A mark fits a hole
as large as the disc the start packs it as (``hole_need``).
"""
from __future__ import annotations

import numpy as np
import torch
from scipy import ndimage

from ...design.encodings import footprint
from ..prepare.pack import thin
from ..step.raster import RasterGrid


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
