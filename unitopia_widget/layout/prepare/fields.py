"""Allowed-region fields: a container's coverage -> containment penalty on the raster."""
from __future__ import annotations

import numpy as np

from ..step.distance import edt
from ..step.raster import RasterGrid


def padded(coverage: np.ndarray, grid: RasterGrid) -> np.ndarray:
    """``coverage (H, W)`` (no padding) placed on the padded raster: float32 ``grid.shape``,
    0 on the padding."""
    out = np.zeros(grid.shape, dtype=np.float32)
    h, w = coverage.shape
    out[grid.pad:grid.pad + h, grid.pad:grid.pad + w] = coverage
    return out


def region_fields(coverage: np.ndarray, grid: RasterGrid, falloff: float):
    """Fields of one allowed region on the padded raster.

    ``coverage``: ``(H, W)`` share of each raster pixel inside the region
    (without padding). ``falloff``: raster px over which the penalty grows by
    one outside the region. Returns float32 arrays of ``grid.shape``:
    ``inside`` (the coverage, 0 on the padding), ``outside = 1 - inside``, and
    ``penalty = outside + distance_outside / falloff``: flat outside plus a
    slope, so a mark far outside still feels which way is in.
    """
    inside = padded(coverage, grid)
    outside = 1.0 - inside
    if (inside >= 0.5).any():
        distance = edt(inside < 0.5).astype(np.float32)
    else:
        distance = np.zeros_like(inside)
    penalty = outside + np.maximum(distance - 0.5, 0.0) / max(falloff, 1e-3)
    return inside, outside, penalty
