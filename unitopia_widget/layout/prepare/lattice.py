"""Hexagonal lattices inside a region: the starting positions emitters hand out."""
from __future__ import annotations

import functools
import math

import numpy as np

from ..step.distance import edt
from .kept import kept

START_SIDE = 600.0   # raster px along the canvas's long side (at most 1 per canvas px) on which
                     # the start reads its containers: widest discs, packing, fits


def start_rho(canvas) -> float:
    """Raster px per canvas px of the start's container regions on ``canvas`` (w, h)."""
    return min(1.0, START_SIDE / max(canvas))


class Region:
    """A container's inside, sampled on a raster, for placing points.

    ``coverage``: ``(H, W)`` inside share per raster pixel; ``rho`` raster px per canvas px.
    """

    def __init__(self, coverage: np.ndarray, rho: float):
        self.rho = rho
        self.inside = coverage >= 0.5
        if not self.inside.any():
            raise ValueError("container: the region has no inside pixels on the canvas")
        ys, xs = np.nonzero(self.inside)
        self.bbox = (xs.min() / rho, ys.min() / rho, (xs.max() + 1) / rho, (ys.max() + 1) / rho)
        self.area = float(coverage.sum()) / rho ** 2

    @functools.cached_property
    def depth(self) -> np.ndarray:
        """``(H, W)`` canvas px from each raster pixel to the outside (0 outside); made when
        first read."""
        return edt(self.inside) / self.rho

    @functools.cached_property
    def signed_depth(self) -> np.ndarray:
        """``(H, W)`` canvas px from each raster pixel's centre to the edge (half a pixel short
        of the nearest pixel across it; the raster's edge bounds too): positive inside,
        negative outside; made when first read."""
        padded = np.pad(self.inside, 1)
        inside = edt(padded)[1:-1, 1:-1]
        outside = edt(~padded)[1:-1, 1:-1]
        return (np.maximum(inside - 0.5, 0.0) - np.maximum(outside - 0.5, 0.0)) / self.rho

    def contains(self, points: np.ndarray) -> np.ndarray:
        """``(k,)`` bool: whether each point ``(k, 2)`` is inside (``depth_at(points) > 0``,
        with no distances made)."""
        h, w = self.inside.shape
        j = np.clip((points[:, 0] * self.rho).astype(int), 0, w - 1)
        i = np.clip((points[:, 1] * self.rho).astype(int), 0, h - 1)
        return self.inside[i, j]

    def axis(self) -> float:
        """Angle (radians, from +x towards +y) of the inside's long principal axis."""
        ys, xs = np.nonzero(self.depth > 0)
        cov = np.cov(np.stack([xs, ys]).astype(float))
        return 0.5 * math.atan2(2 * cov[0, 1], cov[0, 0] - cov[1, 1])

    def depth_at(self, points: np.ndarray) -> np.ndarray:
        """Distance (canvas px) from each point ``(k, 2)`` to the region's outside; 0 outside."""
        h, w = self.depth.shape
        j = np.clip((points[:, 0] * self.rho).astype(int), 0, w - 1)
        i = np.clip((points[:, 1] * self.rho).astype(int), 0, h - 1)
        return self.depth[i, j]


_REGIONS: dict = {}   # (container JSON text, canvas, rho) -> Region, the last few made
REGIONS_KEPT = 8


def container_region(container, canvas, rho: float) -> Region:
    """The ``Region`` of ``container`` on ``canvas`` at ``rho``, made once per (container
    JSON, canvas, rho) among the last ``REGIONS_KEPT`` asked for (a warm run asks again for
    the regions of the last; regions are only read)."""
    return kept(_REGIONS, (repr(container.to_json()), tuple(canvas), float(rho)),
                lambda: Region(container.coverage(canvas, rho), rho), REGIONS_KEPT)


def hex_points(bbox, spacing: float, phase: float = 0.0) -> np.ndarray:
    """Centres ``(k, 2)`` of a hexagonal lattice with ``spacing`` px over ``bbox``, row by row."""
    x0, y0, x1, y1 = bbox
    dy = spacing * math.sqrt(3) / 2
    rows = np.arange(y0 + dy / 2, y1, dy)
    pts = []
    for r, y in enumerate(rows):
        offset = (spacing / 2 if r % 2 else 0.0) + phase * spacing
        xs = np.arange(x0 + spacing / 2 + offset, x1, spacing)
        pts.append(np.stack([xs, np.full_like(xs, y)], axis=1))
    return np.concatenate(pts) if pts else np.zeros((0, 2))


def fitting_lattice(region: Region, count: int, spacing: float, clearance: float) -> np.ndarray:
    """At least ``count`` lattice points whose depth is >= ``clearance``.

    Starts at ``spacing`` (canvas px) and tightens it until enough points fit;
    with a too-small region, the tightest lattice holds them anyway (the
    optimiser then shrinks the marks). Returns all fitting points, row by row.
    """
    def fitting(scale: float) -> np.ndarray:
        pts = hex_points(region.bbox, spacing * scale)
        return pts[region.depth_at(pts) >= clearance * scale]

    loose = 1.0
    for _ in range(60):
        ok = fitting(loose * 0.97)
        if len(ok) >= count:
            # the loosest lattice that holds them, to within 0.2%: 3% steps leave an empty rim
            tight = loose * 0.97
            if len(fitting(loose)) >= count:
                return fitting(loose)
            while loose / tight > 1.002:
                middle = math.sqrt(loose * tight)
                ok_middle = fitting(middle)
                if len(ok_middle) >= count:
                    tight, ok = middle, ok_middle
                else:
                    loose = middle
            return ok
        loose *= 0.97
    spacing *= loose
    pts = hex_points(region.bbox, spacing)
    ok = pts[region.depth_at(pts) > 0]
    if len(ok) < count:
        raise ValueError(f"container: too small to place {count} marks (its area is "
                         f"{region.area:.1f} px^2 on the raster); use a larger container")
    return ok


def grid_spacing(region: Region, count: int) -> float:
    """The hex spacing (canvas px) at which ``count`` points tile the whole region."""
    return math.sqrt(region.area / count / (math.sqrt(3) / 2))
