"""Forces: attractions that gather marks (paper eq. 5).

A force is a potential over mark centres; the solver adds
``strength * potential`` to the loss. Potentials are in canvas px, so a
strength of 1 pulls with the same pressure whatever the canvas size.
"""
from __future__ import annotations

import math

import torch

from .validate import check_finite, check_positive


class PointForce:
    """Attraction towards the point ``(x, y)`` (canvas px)."""

    kind = "point"

    def __init__(self, x: float, y: float, strength: float = 1.0):
        self.x = check_finite("PointForce", "x", x)
        self.y = check_finite("PointForce", "y", y)
        self.strength = check_positive("PointForce", "strength", strength, allow_zero=True)

    def to_json(self) -> dict:
        """The force as the design JSON holds it (``docs/protocol.md``)."""
        return {"kind": "point", "x": self.x, "y": self.y, "strength": self.strength}

    def __repr__(self) -> str:
        return f"PointForce({self.x:g}, {self.y:g}, strength={self.strength:g})"

    def __eq__(self, other) -> bool:
        return isinstance(other, PointForce) and self.to_json() == other.to_json()


class DirectionalForce:
    """A uniform pull towards ``angle_deg`` (0 = right, 90 = down, the canvas' y axis)."""

    kind = "direction"

    def __init__(self, angle_deg: float, strength: float = 1.0):
        self.angle = check_finite("DirectionalForce", "angle_deg", angle_deg)
        self.strength = check_positive("DirectionalForce", "strength", strength, allow_zero=True)

    @property
    def vector(self) -> tuple[float, float]:
        """The unit vector (x, y) of the pull, in canvas px (y down)."""
        a = math.radians(self.angle)
        return math.cos(a), math.sin(a)

    def to_json(self) -> dict:
        """The force as the design JSON holds it (``docs/protocol.md``)."""
        return {"kind": "direction", "angle": self.angle, "strength": self.strength}

    def __repr__(self) -> str:
        return f"DirectionalForce({self.angle:g}, strength={self.strength:g})"

    def __eq__(self, other) -> bool:
        return isinstance(other, DirectionalForce) and self.to_json() == other.to_json()


def force_from_json(d: dict):
    """A force from its protocol dict."""
    kind = d.get("kind") if isinstance(d, dict) else None
    if kind == "point":
        return PointForce(d["x"], d["y"], d.get("strength", 1.0))
    if kind == "direction":
        return DirectionalForce(d["angle"], d.get("strength", 1.0))
    raise ValueError(f"force: unknown kind {kind!r}; expected 'point' or 'direction'")


def net_pull(forces) -> tuple[float, float] | None:
    """The strength-weighted sum ``(vx, vy)`` of ``forces``' unit vectors when they are all
    directional, else None (none, or point forces among them)."""
    if not forces or not all(isinstance(f, DirectionalForce) for f in forces):
        return None
    return (sum(f.strength * f.vector[0] for f in forces),
            sum(f.strength * f.vector[1] for f in forces))


def potential(forces, center: torch.Tensor) -> torch.Tensor:
    """Per-mark potential ``(N,)`` of ``center (N, 2)`` canvas px under ``forces``.

    Point forces act together as one field: each mark is drawn to the nearest
    point (weighted by strength), so several points gather several piles.
    Directional forces add a linear potential along their direction.
    """
    total = torch.zeros(center.shape[0], dtype=center.dtype, device=center.device)
    points = [f for f in forces if isinstance(f, PointForce)]
    if points:
        # python scalars, not tensors: nothing is copied to the device each iteration
        dist = torch.stack([f.strength * torch.sqrt((center[:, 0] - f.x) ** 2 + (center[:, 1] - f.y) ** 2
                                                    + 1e-6) for f in points], dim=1)   # (N, K)
        total = total + dist.min(dim=1).values
    for f in forces:
        if isinstance(f, DirectionalForce):
            vx, vy = f.vector
            total = total - f.strength * (center[:, 0] * vx + center[:, 1] * vy)
    return total
