"""The footprints drawn once on a raster finer than the layout's, as a checker draws them.

The solver judges the marks on a raster aimed at a mean footprint a few raster px across; a
move made after the last iteration (``rules.strays``, ``rules.drop``, ``rules.contacts``) is
judged on this one instead: ``fine_rho`` px per canvas px (capped in size), each footprint
cut at alpha 0.5, with per layer the count of footprints that may not share a pixel with it
and the pixels inside its region.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ...design.encodings import footprint
from .raster import Planner, RasterGrid, render_samples


@dataclass
class FineRaster:
    """Every footprint's pixels on one fine raster. ``S`` pixels, ``M`` drawn footprint pixels."""

    grid: RasterGrid
    index: torch.Tensor     # (M,) long, flat fine px, each unit's in one run (``bounds``)
    owner: torch.Tensor     # (M,) long, the unit of each pixel
    bounds: np.ndarray      # (N + 1,) unit i's pixels are index[bounds[i]:bounds[i + 1]]
    layer: torch.Tensor     # (N,) long, each unit's layer
    collide: torch.Tensor   # (L, L) float, 1 where two layers' footprints may not share a pixel
    seen: torch.Tensor      # (L, S) float, footprints on each pixel that layer a collides with
    inside: torch.Tensor    # (L, S) bool, pixels at least half inside layer a's region

    def pixels(self, i: int) -> torch.Tensor:
        """``(P,)`` unit ``i``'s flat fine px (a view of ``index``)."""
        return self.index[self.bounds[i]:self.bounds[i + 1]]

    def lift(self, i: int) -> None:
        """Take unit ``i``'s pixels off ``seen``."""
        a = int(self.layer[i])
        self.seen[:, self.pixels(i)] -= self.collide[:, a:a + 1]

    def put(self, i: int) -> None:
        """Put unit ``i``'s pixels (as they are in ``index``) back on ``seen``."""
        a = int(self.layer[i])
        self.seen[:, self.pixels(i)] += self.collide[:, a:a + 1]

    def crowded(self) -> np.ndarray:
        """``(N,)`` the share of each unit's pixels that another footprint it collides with
        covers too."""
        n = len(self.bounds) - 1
        shared = (self.seen[self.layer[self.owner], self.index] > 1.5).float()
        hit = torch.zeros(n, device=shared.device).index_add_(0, self.owner, shared)
        return (hit / torch.bincount(self.owner, minlength=n).clamp_min(1)).cpu().numpy()

    def move_lifted(self, i: int, row: int, column: int) -> None:
        """Move lifted unit ``i``'s pixels by ``row``, ``column`` fine px on ``index`` alone
        (``put`` puts them back on ``seen`` where they then are)."""
        self.pixels(i).add_(row * self.grid.shape[1] + column)

    def shift(self, units: np.ndarray, by: np.ndarray) -> None:
        """Move each of ``units (n,)`` by ``by (n,)`` flat px (rows times columns plus columns)
        at once, on ``index`` and ``seen``."""
        step = torch.zeros(len(self.bounds) - 1, dtype=torch.long, device=self.index.device)
        step[torch.as_tensor(units, device=step.device)] = torch.as_tensor(by, device=step.device)
        moving = step[self.owner] != 0
        pix, lay = self.index[moving], self.layer[self.owner[moving]]
        for sign, at in ((-1.0, pix), (1.0, pix + step[self.owner[moving]])):
            for a in torch.unique(lay).tolist():
                mine = at[lay == a]
                self.seen.index_add_(1, mine, sign * self.collide[:, a:a + 1].expand(-1, len(mine)))
        self.index[moving] += step[self.owner[moving]]


def samples(p, grid: RasterGrid, center: torch.Tensor, angle: torch.Tensor,
            half_w: np.ndarray, half_h: np.ndarray, rotating: np.ndarray):
    """``(values, index, owner)`` ``(M,)``: the marks of the solver's ``Problem`` ``p`` drawn
    at ``center (N, 2)`` canvas px, ``angle (N,)`` radians and half sides ``half_w``,
    ``half_h`` ``(N,)`` canvas px on ``grid`` (``render_samples``); ``rotating (N,)``: units
    whose patch must hold any rotation."""
    plan = Planner(p.sprite, p.sprite_sides, rotating, p.pyramids, grid, center.device,
                   p.sprite_aspects).plan_for(half_w, half_h)
    as_t = lambda a: torch.as_tensor(a, device=center.device, dtype=torch.float32)   # noqa: E731
    return render_samples(center, angle, as_t(half_w), as_t(half_h), plan, p.pyramids, grid)


def drawn_runs(p, grid: RasterGrid, center: torch.Tensor, angle: torch.Tensor,
               half_w: np.ndarray, half_h: np.ndarray, rotating: np.ndarray):
    """``(index, owner, bounds)``: the flat px of ``grid`` each mark covers at alpha over
    0.5, drawn as ``samples`` draws them; ``index``, ``owner`` ``(M,)`` long, each unit's in
    one run: unit i's are ``index[bounds[i]:bounds[i + 1]]`` (``bounds (N + 1,)``)."""
    values, index, owner = samples(p, grid, center, angle, half_w, half_h, rotating)
    drawn = values > 0.5
    index, owner = index[drawn].long(), owner[drawn]
    order = torch.argsort(owner, stable=True)
    index, owner = index[order], owner[order]
    bounds = np.concatenate([[0], np.cumsum(
        torch.bincount(owner, minlength=len(p.layer)).cpu().numpy())])
    return index, owner, bounds


@torch.no_grad()
def draw(p, center: torch.Tensor, angle: torch.Tensor, unit_scale: np.ndarray,
         rotating: np.ndarray, fine_rho: float, max_fine: int) -> FineRaster:
    """The footprints of the solver's ``Problem`` ``p`` at ``center (N, 2)`` canvas px,
    ``angle (N,)`` radians and ``unit_scale (N,)`` on a raster of ``fine_rho`` px per canvas px
    (coarser where all layers' slabs would pass ``max_fine`` px, never coarser than the
    layout's); ``rotating (N,)``: units whose patch must hold any rotation."""
    w, h = p.grid.canvas
    n_layers = int(p.terms.blocks.shape[0])
    rho = max(p.grid.rho, min(fine_rho, math.sqrt(max_fine / (w * h * n_layers))))
    grid = RasterGrid((w, h), rho, pad=2)
    dev = center.device
    grow = footprint(p.margin) * unit_scale
    index, owner, bounds = drawn_runs(p, grid, center, angle, p.half_w * grow,
                                      p.half_h * grow, rotating)
    size = grid.shape[0] * grid.shape[1]
    layer = torch.as_tensor(p.layer, device=dev, dtype=torch.long)
    collide = _collisions(p.terms, n_layers).to(dev)
    count = torch.zeros(n_layers * size, device=dev).index_add_(
        0, layer[owner] * size + index, torch.ones_like(index, dtype=torch.float32))
    seen = collide @ count.reshape(n_layers, size)
    return FineRaster(grid, index, owner, bounds, layer, collide, seen, _inside(p.regions, grid, dev))


def _collisions(terms, n_layers: int) -> torch.Tensor:
    """``(L, L)`` float: 1 where two layers' footprints may not share a pixel (the same
    layer, or one blocks or rests on the other; either way round)."""
    pair = torch.eye(n_layers) + terms.blocks.cpu()
    if terms.rests is not None:
        pair = pair + terms.rests.cpu()
    return ((pair + pair.T) > 0).float()


def _inside(regions, grid: RasterGrid, dev) -> torch.Tensor:
    """``(L, S)`` bool: the fine pixels at least half inside each layer's region."""
    out, made = [], {}
    for region in regions:
        if id(region) not in made:
            cov = np.pad(region.coverage(grid.canvas, grid.rho), grid.pad)   # 0 on the padding
            made[id(region)] = torch.as_tensor(cov.reshape(-1) >= 0.5, device=dev)
        out.append(made[id(region)])
    return torch.stack(out)
