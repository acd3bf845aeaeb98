"""The reflow's window: the units a change reaches, drawn on the raster box around them.

A ``Window`` holds the drawn units of a ``Problem`` (the active ones free to move, the
others frozen as obstacles), their placement, optimizer, render plan and canvas terms, on a
``Crop`` of the raster (``layout.reflow``)."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import torch

from .prepare.problem import Problem
from .step.losses import CanvasLoss, shares
from .step.optim import Adam
from .step.placement import Placement
from .step.raster import Planner, render_samples


@dataclass(frozen=True)
class Crop:
    """A box of a ``RasterGrid``'s pixels, drawn on as a grid of its own: ``offset`` (x, y)
    canvas px moves a centre from the full grid onto the crop (``render_samples`` reads
    ``rho``, ``pad`` and ``shape``)."""

    rho: float
    pad: int
    shape: tuple       # (H, W) raster px of the crop
    corner: tuple      # (row, column) of the crop's first pixel in the full raster

    @property
    def offset(self) -> np.ndarray:
        return np.array([self.corner[1], self.corner[0]], dtype=float) / self.rho


class Window:
    """The drawn units ``sub (K,)`` of ``p``, the active ones free to move: a placement,
    its optimizer, its render plan and terms (fill weight ``w_fill``), on the raster box
    around them (``box``: canvas px ``(x0, y0, x1, y1)``; None: the whole raster, as where a
    layer rests on another's swept shadow)."""

    def __init__(self, p: Problem, sub: np.ndarray, center: np.ndarray, active: np.ndarray,
                 foot_w: np.ndarray, foot_h: np.ndarray, lr: float, w_fill: float = 0.0,
                 box=None):
        dev = torch.device(p.device)
        self.sub, self.box = sub, box
        grid, terms = p.grid, p.terms
        self.offset = np.zeros(2)
        if box is not None:
            h, w = grid.shape
            c0, r0 = (max(int(np.floor(v * grid.rho)), 0) for v in box[:2])
            c1, r1 = min(int(np.ceil(box[2] * grid.rho)) + 2 * grid.pad, w), \
                min(int(np.ceil(box[3] * grid.rho)) + 2 * grid.pad, h)
            grid = Crop(grid.rho, grid.pad, (r1 - r0, c1 - c0), (r0, c0))
            n_layers = terms.penalty.shape[0]

            def cut(field):
                return field.view(n_layers, h, w)[:, r0:r1, c0:c1].reshape(n_layers, -1).contiguous()

            terms = dataclasses.replace(terms, penalty=cut(terms.penalty), outside=cut(terms.outside),
                                        inside=cut(terms.inside), shape=grid.shape)
            self.offset = grid.offset
        self.terms = dataclasses.replace(terms, w_fill=w_fill, sums=None, _cover=None,
                                         _tables=None, _rows=None, _onehot=None, _obstacle=None)
        theta = p.placement.theta.detach().cpu().numpy()[sub]
        self.place = Placement(center[sub] - self.offset, theta, active[sub],
                               np.zeros(len(sub), bool), dev)
        self.optimizer = Adam([{"params": [self.place.t], "lr": lr}], betas=(0.8, 0.95))
        rotating = np.abs(theta) > 1e-6
        planner = Planner(p.sprite[sub], p.sprite_sides, rotating, p.pyramids, grid, dev,
                          p.sprite_aspects)
        self.plan = planner.plan_for(foot_w[sub], foot_h[sub])
        self.layer = torch.as_tensor(p.layer[sub], device=dev, dtype=torch.long)
        self.sample_layer = self.layer[self.plan.owner] if self.terms.penalty.shape[0] > 1 else None
        self.hw = torch.as_tensor(foot_w[sub], device=dev, dtype=torch.float32)
        self.hh = torch.as_tensor(foot_h[sub], device=dev, dtype=torch.float32)
        self.grid, self.pyramids = grid, p.pyramids
        self.full = torch.as_tensor(p.grid.canvas, dtype=torch.float32)
        # (K,) the drawn units whose footprint lies wholly in the box: their shares are whole
        radius = np.hypot(foot_w[sub], foot_h[sub])[:, None]
        self.whole = np.ones(len(sub), bool) if box is None else \
            ((center[sub] - radius >= box[:2]) & (center[sub] + radius <= box[2:])).all(1)

    def centers(self) -> np.ndarray:
        """``(K, 2)`` the drawn units' centres, canvas px of the full grid."""
        return self.place.t.detach().cpu().numpy().astype(np.float64) + self.offset

    def render(self, center=None):
        center = self.place.transforms()[0] if center is None else center
        return render_samples(center, self.place.theta, self.hw, self.hh, self.plan,
                              self.pyramids, self.grid)

    def step(self, lr: float, ink: torch.Tensor) -> None:
        values, index, _ = self.render()
        loss = CanvasLoss.apply(values, index, self.sample_layer, self.terms)
        self.optimizer.param_groups[0]["lr"] = lr
        self.optimizer.zero_grad()
        loss.backward()
        self.optimizer.step()
        with torch.no_grad():   # on the full canvas, with all their ink
            off = torch.as_tensor(self.offset, dtype=torch.float32)
            low = torch.minimum(ink, self.full / 2)
            self.place.t.copy_(torch.minimum(torch.maximum(self.place.t + off, low),
                                             self.full - low) - off)

    @torch.no_grad()
    def shares(self, center=None) -> tuple[np.ndarray, np.ndarray]:
        """``(K,)`` each drawn unit's overlapped plus outside share of its ink, and ``(K,)``
        its ink (raster px^2 of alpha), at ``center`` (full-grid canvas px; None: where they
        are)."""
        if center is not None:
            center = torch.as_tensor(center - self.offset, dtype=torch.float32)
        values, index, owner = self.render(center)
        t = self.terms
        over = t.unit_overlap(values, index, owner, self.layer, len(self.sub))
        size = t.penalty.shape[1]
        outside = t.outside.reshape(-1).index_select(0, index.long() + self.layer[owner] * size)
        out = torch.zeros_like(over).index_add_(0, owner, values * outside)
        drawn = torch.zeros_like(over).index_add_(0, owner, values)
        return ((over + out) / drawn.clamp_min(1e-6)).cpu().numpy(), drawn.cpu().numpy()


def bounds(center: np.ndarray, radius: np.ndarray, slack: float) -> np.ndarray:
    """``(4,)`` canvas px ``(x0, y0, x1, y1)``: the box of the discs ``center (K, 2)``,
    ``radius (K,)``, widened by ``slack`` on every side."""
    return np.concatenate([(center - radius[:, None]).min(0) - slack,
                           (center + radius[:, None]).max(0) + slack])


def inside(center: np.ndarray, radius: np.ndarray, box: np.ndarray) -> np.ndarray:
    """``(N,)`` bool: the discs with some part in ``box``."""
    return ((center + radius[:, None] > box[:2]) & (center - radius[:, None] < box[2:])).all(1)


def final_stats(window: Window, center: np.ndarray, w_fill: float) -> dict:
    """The overlap, outside and fill shares and the loss (``w_fill`` its fill weight) of
    the units of ``window`` at ``center``."""
    with torch.no_grad():
        values, index, _ = window.render(torch.as_tensor(center, dtype=torch.float32))
        terms = dataclasses.replace(window.terms, w_fill=w_fill)
        loss = CanvasLoss.apply(values, index, window.sample_layer, terms)
        return dict(shares(terms.sums.sum(1).tolist(), terms.inside_total), loss=float(loss))
