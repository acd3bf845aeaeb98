"""Placement: the optimised parameters of every unit and their constraints.

``Placement`` maps parameters to transforms: centres ``(N, 2)`` canvas px and
angles ``(N,)`` radians (clockwise on screen). Free units move by their own
translation; frozen ones (an emitter with ``speed=0``) keep their emitted
centre. Angles are fixed, free (``rotate=True``) or pulled towards a target
direction by the orientation loss (paper eq. 6). Subclasses in
``curves.py`` tie centres to an emitter curve.
"""
from __future__ import annotations

import numpy as np
import torch

DRIFT_DECAY = 0.9


class Placement:
    """Free translations (masked by ``movable``) and optionally free angles."""

    def __init__(self, center: np.ndarray, angle: np.ndarray, movable: np.ndarray,
                 turnable: np.ndarray, device, orientation=None, orientation_weight: float = 2.0,
                 tracks=(), drift: np.ndarray | None = None):
        """``center (N, 2)``, ``angle (N,)`` radians, ``movable``/``turnable`` bool ``(N,)``.

        ``orientation``: None or a callable ``(center (N, 2), tangent (N, 2)) ->
        (target (N, 2), mask (N,))`` giving the direction each masked unit's up
        axis should point to. ``tracks``: ``CurveTrack``s whose units follow a
        curve. ``drift``: ``(N, 2)`` initial velocity, px per iteration,
        decaying by ``DRIFT_DECAY`` each iteration.
        """
        self.tracks = list(tracks)
        self.drift = None if drift is None or not np.any(drift) else \
            torch.tensor(drift, dtype=torch.float32, device=device)
        self.device = torch.device(device)
        self.t = torch.tensor(center, dtype=torch.float32, device=self.device, requires_grad=True)
        self.movable = torch.as_tensor(movable, device=self.device)
        # units move when movable and released (layers poured in turn are held back until then)
        self.keep = self.movable[:, None].to(torch.float32)
        self.t.register_hook(lambda g: g * self.keep)
        self.turnable = np.asarray(turnable, dtype=bool)
        self.theta = torch.tensor(angle, dtype=torch.float32, device=self.device,
                                  requires_grad=bool(self.turnable.any()))
        if self.turnable.any() and not self.turnable.all():
            turn = torch.as_tensor(self.turnable, device=self.device).to(torch.float32)
            self.theta.register_hook(lambda g: g * turn)
        self.orientation = orientation
        self.orientation_weight = orientation_weight
        self._fixed_angle = bool(np.any(np.abs(angle) > 1e-6))
        self._canvas = None   # (canvas, its size as a tensor) for ``project``

    def hold(self, held: np.ndarray) -> None:
        """Freeze the translation of the units where ``held (N,)`` is True; release the rest."""
        free = self.movable & ~torch.as_tensor(held, device=self.device)
        self.keep = free[:, None].to(torch.float32)

    def parameters(self) -> list[torch.Tensor]:
        return [self.t] + [p for track in self.tracks for p in track.parameters()]

    def angle_params(self) -> list[torch.Tensor]:
        return [self.theta] if self.theta.requires_grad else []

    def rotating(self) -> np.ndarray:
        """Bool ``(N,)``: units whose patch must hold any rotation."""
        if self._fixed_angle or self.turnable.any():
            return np.ones(len(self.turnable), dtype=bool)
        return self.turnable

    def transforms(self) -> tuple[torch.Tensor, torch.Tensor]:
        return self.centers_and_tangents()[0], self.theta

    def centers_and_tangents(self):
        """Centres ``(N, 2)`` and, for units on a curve track, the curve tangent (else 0)."""
        center, tangent = self.t, torch.zeros_like(self.t)
        for track in self.tracks:
            pos, tan = track.positions()
            center = center.index_copy(0, track.index, pos)
            tangent = tangent.index_copy(0, track.index, tan.detach())
        return center, tangent

    def penalty(self) -> torch.Tensor:
        """Orientation loss: mean ``1 - cos`` between up axis and target, weighted."""
        if self.orientation is None:
            return torch.zeros((), device=self.device)
        center, tangent = self.centers_and_tangents()
        target, mask = self.orientation(center.detach(), tangent)
        angle = self.theta
        up = torch.stack([torch.sin(angle), -torch.cos(angle)], dim=1)     # (N, 2)
        cos = (up * target).sum(1) / target.norm(dim=1).clamp_min(1e-6)
        return self.orientation_weight * ((1 - cos) * mask).sum() / mask.sum().clamp_min(1)

    @torch.no_grad()
    def project(self, canvas: tuple[float, float], iteration: int,
                half: torch.Tensor | None = None) -> None:
        """Apply the decaying drift, keep marks on the canvas and tracks in order.

        ``half``: ``(N, 2)`` half extents (canvas px) of each mark's ink: its
        centre stays that far from the canvas edge (at the middle when wider).
        """
        if self.drift is not None:
            self.t += self.drift * (DRIFT_DECAY ** iteration) * self.keep
        if self._canvas is None or self._canvas[0] != canvas:   # made once, not per iteration
            self._canvas = (canvas, torch.tensor(canvas, dtype=self.t.dtype, device=self.t.device))
        size = self._canvas[1]
        if half is None:
            half = torch.zeros_like(self.t)
        low = torch.minimum(half, size / 2)
        self.t.copy_(torch.minimum(torch.maximum(self.t, low), size - low))
        for track in self.tracks:
            track.project(low[track.index], size - low[track.index])


def frame(place: Placement, scale: np.ndarray) -> np.ndarray:
    """float32 ``(N, 4)``: x, y, angle (degrees), the unit's global scale."""
    with torch.no_grad():
        center, angle = place.transforms()
        out = torch.empty((center.shape[0], 4), dtype=torch.float32)
        out[:, :2] = center.cpu()
        out[:, 2] = torch.rad2deg(angle).cpu()
        out[:, 3] = torch.as_tensor(scale, dtype=torch.float32)
    return out.numpy()
