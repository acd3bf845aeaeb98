"""Curve tracks: units tied to a curve emitter in "line" or "band" mode.

A track holds, per unit, its arc length ``u`` along the curve and (band
mode) its offset ``v`` along the curve's normal, both canvas px. After every
step ``project`` sorts the arc lengths back into the units' emission order,
so order along the curve is kept exactly while marks push each other along
(line) or stack sideways (band).
"""
from __future__ import annotations

import numpy as np
import torch

from ...design.bezier import Curve


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

    def parameters(self) -> list[torch.Tensor]:
        return [p for p in (self.u, self.v) if p.requires_grad]

    def positions(self):
        """Centres ``(n, 2)`` and unit tangents ``(n, 2)``."""
        point, tangent = self.curve.torch_at(self.u)
        normal = torch.stack([-tangent[:, 1], tangent[:, 0]], dim=1)
        return point + normal * self.v[:, None], tangent

    @torch.no_grad()
    def project(self) -> None:
        """Clamp to the curve and restore the emission order along it."""
        self.u.clamp_(0, self.curve.length)
        self.u[self.by_rank] = torch.sort(self.u).values
