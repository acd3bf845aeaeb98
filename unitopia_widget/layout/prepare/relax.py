"""Footprint discs pushed apart: a quick settle of many moved marks before the raster sees them.

Each mark stands for the disc a start packs it as (``start.footprint_radius`` at its scale);
``relax`` moves the free ones to lower the discs' overlap energy, the sum over pairs of their
overlap depth squared plus, per free disc, the square of how far it pokes out of its
container (``Region.signed_depth``, sampled bilinearly), by L-BFGS, until no disc is pushed
by more than ``tolerance`` of the median radius. Near a packing's jamming density, where a
gradient step on the raster clears overlap only slowly (each step moves a push one
neighbour on), L-BFGS on the discs settles a thousand marks in a few hundred cheap
iterations. The discs are the marks' as the start packs them; the raster window that
follows clears what their true shapes still overlap (``layout.reflow``).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import minimize
from scipy.spatial import cKDTree

from .lattice import Region

SKIN = 0.5   # largest radii the pairs' list reaches past touching; remade when a disc moved half


def sample(field: np.ndarray, rho: float, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``field (H, W)`` (values at raster pixel centres, ``rho`` raster px per canvas px)
    at ``points (K, 2)`` canvas px, interpolated bilinearly: the values ``(K,)`` and their
    gradients ``(K, 2)`` per canvas px."""
    h, w = field.shape
    fx = np.clip(points[:, 0] * rho - 0.5, 0, w - 1.001)
    fy = np.clip(points[:, 1] * rho - 0.5, 0, h - 1.001)
    j, i = fx.astype(int), fy.astype(int)
    a, b = fx - j, fy - i
    f00, f01, f10, f11 = field[i, j], field[i, j + 1], field[i + 1, j], field[i + 1, j + 1]
    top, bottom = f00 + a * (f01 - f00), f10 + a * (f11 - f10)
    grad = np.stack([(f01 - f00) * (1 - b) + (f11 - f10) * b, bottom - top], 1) * rho
    return top + b * (bottom - top), grad


class Discs:
    """The overlap energy of discs ``radius (N,)`` px in ``region``, the ``free (F,)`` ones
    (indices) moving, the others obstacles; its pairs' list is kept while no disc moved
    half its ``SKIN``."""

    def __init__(self, radius: np.ndarray, free: np.ndarray, region: Region):
        self.radius, self.free, self.region = radius, free, region
        self.reach = SKIN * float(radius.max())
        self.listed = None   # (N, 2) the centres the pairs were listed at

    def pairs(self, center: np.ndarray) -> np.ndarray:
        if self.listed is None or \
                float(np.abs(center - self.listed).max()) > self.reach / 2:
            self.listed = center.copy()
            near = cKDTree(center).query_pairs(2 * float(self.radius.max()) + self.reach,
                                               output_type="ndarray")
            i, j = near[:, 0], near[:, 1]
            span = self.radius[i] + self.radius[j] + self.reach
            self.near = near[((center[i] - center[j]) ** 2).sum(1) < span ** 2]
        return self.near

    def energy(self, center: np.ndarray) -> tuple[float, np.ndarray]:
        """The energy (module docstring) at ``center (N, 2)`` and its gradient ``(F, 2)``."""
        near, radius, free = self.pairs(center), self.radius, self.free
        i, j = near[:, 0], near[:, 1]
        gap = center[j] - center[i]
        dist = np.hypot(*gap.T)
        over = radius[i] + radius[j] - dist
        hit = over > 0
        i, j, over = i[hit], j[hit], over[hit]
        push = (2 * over / np.maximum(dist[hit], 1e-9))[:, None] * gap[hit]
        n = len(center)
        grad = np.stack([np.bincount(i, push[:, a], n) - np.bincount(j, push[:, a], n)
                         for a in range(2)], 1)
        inside, toward = sample(self.region.signed_depth, self.region.rho, center[free])
        out = np.maximum(radius[free] - inside, 0.0)
        return float((over ** 2).sum() + (out ** 2).sum()), grad[free] - 2 * out[:, None] * toward


def relax(center: np.ndarray, radius: np.ndarray, free: np.ndarray, region: Region,
          iterations: int, tolerance: float) -> np.ndarray:
    """``center (N, 2)`` with the ``free (F,)`` discs (indices) moved to lower the overlap
    energy of the discs ``radius (N,)`` in ``region`` (their container), for at most
    ``iterations`` L-BFGS iterations; the others stay as obstacles."""
    if len(free) == 0:
        return center
    discs, out = Discs(radius, free, region), center.copy()

    def energy(x):
        out[free] = x.reshape(-1, 2)
        return discs.energy(out)

    # a disc pushed by an overlap d deep feels a gradient 2 d
    found = minimize(energy, center[free].reshape(-1), jac=True, method="L-BFGS-B",
                     options={"maxiter": iterations,
                              "gtol": 2 * tolerance * float(np.median(radius[free]))})
    out[free] = found.x.reshape(-1, 2)
    return out
