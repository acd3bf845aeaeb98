"""Curve tracks: units tied to a curve emitter in "line" or "band" mode.

A track holds, per unit, its arc length ``u`` along the curve and (band
mode) its offset ``v`` along the curve's normal, both canvas px. After every
step ``project`` sorts the arc lengths back into the units' emission order,
so order along the curve is kept exactly while marks push each other along
(line) or stack sideways (band); a band's offsets keep the centres on the canvas, as
free units are kept. A warm start (``restarted``) puts units back where they ended.
"""
from __future__ import annotations

import copy

import numpy as np
import torch

from ...design.bezier import Curve


def normals(tangent: torch.Tensor) -> torch.Tensor:
    """``(n, 2)`` the curve's unit normals, its unit tangents ``(n, 2)`` turned a quarter
    (the direction a band's offsets ``v`` point)."""
    return torch.stack([-tangent[:, 1], tangent[:, 0]], dim=1)


class CurveTrack:
    """Units ``index (n,)`` on ``curve``, in ``ranks (n,)`` order, starting at arc lengths ``arc (n,)``."""

    def __init__(self, index: np.ndarray, curve: Curve, mode: str, arc: np.ndarray,
                 ranks: np.ndarray, movable: bool, device):
        self.index = torch.as_tensor(index, dtype=torch.long, device=device)
        self.curve = curve
        self.mode = mode
        self.by_rank = torch.as_tensor(np.argsort(ranks, kind="stable"), device=device)
        self.u = torch.tensor(arc, dtype=torch.float32, device=device, requires_grad=movable)
        self.v = torch.zeros(len(index), dtype=torch.float32, device=device,
                             requires_grad=movable and mode == "band")

    def restarted(self, center: np.ndarray, kept: np.ndarray) -> "CurveTrack":
        """A new track like this one whose units with ``kept (N,)`` (indexed like the whole
        layout) start at the curve point nearest their ``center (N, 2)``, canvas px, and
        (band mode) that centre's offset along the curve's normal there; the rest start at
        this track's arc lengths and offsets."""
        index = self.index.cpu().numpy()
        arc = self.u.detach().cpu().numpy().astype(float)
        offset = self.v.detach().cpu().numpy().astype(float)
        mine = kept[index]
        if mine.any():
            c = np.asarray(center, dtype=float)[index[mine]]
            arc[mine] = self.curve.nearest_arc(c)
            if self.mode == "band":   # along the normal ``positions`` turns the offset by
                at = torch.as_tensor(arc[mine], dtype=torch.float32)
                point, tangent = self.curve.torch_at(at)
                normal = normals(tangent).numpy().astype(float)
                offset[mine] = ((c - point.numpy().astype(float)) * normal).sum(1)
        track = copy.copy(self)   # the same units, curve, mode and order
        track.u, track.v = (torch.tensor(x, dtype=torch.float32, device=old.device,
                                         requires_grad=old.requires_grad)
                            for x, old in ((arc, self.u), (offset, self.v)))
        return track

    def parameters(self) -> list[torch.Tensor]:
        return [p for p in (self.u, self.v) if p.requires_grad]

    def sideways(self) -> torch.Tensor | None:
        """``(n, 2)`` each unit's unit normal to the curve where it is: the one way a move made
        by hand may carry a unit of a band, keeping its place along the curve (its emission
        order); None where the track holds its units on the curve ("line") or still."""
        if not self.v.requires_grad:
            return None
        return normals(self.curve.torch_at(self.u.detach())[1])

    @torch.no_grad()
    def step_aside(self, move: torch.Tensor) -> None:
        """Move each unit by the part of ``move (n, 2)`` canvas px along its ``sideways``
        normal (band mode; a track with none keeps its units where they are)."""
        normal = self.sideways()
        if normal is not None:
            self.v += (move * normal).sum(1)

    def positions(self):
        """Centres ``(n, 2)`` and unit tangents ``(n, 2)``."""
        point, tangent = self.curve.torch_at(self.u)
        return point + normals(tangent) * self.v[:, None], tangent

    @torch.no_grad()
    def project(self, low: torch.Tensor, high: torch.Tensor) -> None:
        """Clamp to the curve, restore the emission order along it and (band mode) keep each
        centre between ``low`` and ``high`` (``(n, 2)`` canvas px, as free units are kept on
        the canvas) by clamping its offset along the normal."""
        self.u.clamp_(0, self.curve.length)
        self.u[self.by_rank] = torch.sort(self.u).values
        if not self.v.requires_grad:
            return
        point, tangent = self.curve.torch_at(self.u)
        normal = normals(tangent)
        # per axis, the offsets v with low <= point + normal * v <= high (none where the
        # normal is flat along that axis); where no offset keeps the centre on, v stays
        safe = torch.where(normal.abs() > 1e-6, normal, torch.ones_like(normal))
        a, b = (low - point) / safe, (high - point) / safe
        flat = normal.abs() <= 1e-6
        lo = torch.where(flat, torch.full_like(a, -torch.inf), torch.minimum(a, b)).amax(1)
        hi = torch.where(flat, torch.full_like(a, torch.inf), torch.maximum(a, b)).amin(1)
        ok = lo <= hi
        self.v.copy_(torch.where(ok, torch.minimum(torch.maximum(self.v, lo), hi), self.v))
