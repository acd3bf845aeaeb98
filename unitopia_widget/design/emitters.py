"""Emitters: where marks start (paper section 4.1.2).

* ``GridEmitter``: a uniform (hexagonal) grid that fills the container, marks
  assigned in ``order`` row by row from the top left, or along ``direction``.
* ``CurveEmitter``: cubic Bezier control points ``(3k + 1, 2)``; marks spaced
  by arc length in ``order``; ``mode`` "free" (the curve only places), "line"
  (marks stay on the curve, in order) or "band" (in order along the curve,
  free to stack along its normal).
* no emitter (``None``): marks start packed where the forces pull them, so a
  layout settles in few iterations.

``speed`` and ``direction`` give the marks an initial drift that decays;
``speed=0`` freezes translation, keeping the emitted arrangement (only the
global scale is optimised).
"""
from __future__ import annotations

import math
from numbers import Real

import numpy as np

from .bezier import Curve, fit_bezier
from .bounds import MAX_EMITTER_POINTS, check_length
from .validate import check_choice, check_finite, check_positive

MODES = ("free", "line", "band")


def _direction(owner: str, direction, named=("along", "normal")):
    if direction is None or (isinstance(direction, str) and direction in named):
        return direction
    if isinstance(direction, Real) and not isinstance(direction, bool):
        return check_finite(owner, "direction", direction)
    raise ValueError(f"{owner}: direction must be "
                     + ", ".join([*(repr(n) for n in named), "a number of degrees"])
                     + f" or None; got {direction!r}")


class GridEmitter:
    """Marks start on a uniform grid filling the container."""

    kind = "grid"

    def __init__(self, speed: float = 1.0, direction: float | None = None):
        self.speed = check_positive("GridEmitter", "speed", speed, allow_zero=True)
        self.direction = _direction("GridEmitter", direction, named=())

    def to_json(self) -> dict:
        """The emitter as the design JSON holds it (``docs/protocol.md``)."""
        return {"kind": "grid", "speed": self.speed, "direction": self.direction}

    def __eq__(self, other) -> bool:
        return isinstance(other, GridEmitter) and self.to_json() == other.to_json()

    def __repr__(self) -> str:
        return f"GridEmitter(speed={self.speed:g}, direction={self.direction!r})"

    def drift(self, centers: np.ndarray) -> np.ndarray:
        """Unit drift direction per mark ``(n, 2)`` (zeros without a direction)."""
        if self.direction is None:
            return np.zeros_like(centers)
        a = math.radians(self.direction)
        return np.tile([math.cos(a), math.sin(a)], (len(centers), 1))

    def place(self, lattice: np.ndarray, ranks: np.ndarray) -> np.ndarray:
        """Centres ``(n, 2)`` from the fitting ``lattice`` points, in rank order.

        Points are taken in reading order (rows top to bottom) or, with a
        direction, sorted along it; evenly thinned to ``n`` when more fit.
        """
        pts = lattice
        if self.direction is not None:
            a = math.radians(self.direction)
            pts = pts[np.argsort(-(pts[:, 0] * math.cos(a) + pts[:, 1] * math.sin(a)), kind="stable")]
        pick = np.round(np.linspace(0, len(pts) - 1, len(ranks))).astype(int)
        return pts[pick][ranks]


class CurveEmitter:
    """Marks start along a cubic Bezier curve."""

    kind = "curve"

    def __init__(self, points, speed: float = 1.0, direction="along", mode: str = "free"):
        check_length("CurveEmitter: points", points, MAX_EMITTER_POINTS)
        self.curve = Curve(points)
        self.speed = check_positive("CurveEmitter", "speed", speed, allow_zero=True)
        self.direction = _direction("CurveEmitter", direction)
        self.mode = check_choice("CurveEmitter", "mode", mode, MODES)

    @classmethod
    def from_stroke(cls, stroke, tolerance: float = 4.0, **kwargs) -> "CurveEmitter":
        """Fit a freehand stroke ``(k, 2)`` (canvas px) with cubic Beziers within ``tolerance`` px."""
        return cls(fit_bezier(np.asarray(stroke, dtype=float), tolerance), **kwargs)

    @property
    def points(self) -> np.ndarray:
        """The Bezier control points, shape (3k + 1, 2), canvas px."""
        return self.curve.points

    def to_json(self) -> dict:
        """The emitter as the design JSON holds it (``docs/protocol.md``)."""
        return {"kind": "curve", "points": self.points.tolist(), "speed": self.speed,
                "direction": self.direction, "mode": self.mode}

    def __eq__(self, other) -> bool:
        return isinstance(other, CurveEmitter) and self.to_json() == other.to_json()

    def __repr__(self) -> str:
        k = (len(self.points) - 1) // 3
        return f"CurveEmitter({k} segment{'s' * (k > 1)}, mode={self.mode!r}, speed={self.speed:g})"

    def arc_positions(self, lengths: np.ndarray, ranks: np.ndarray) -> np.ndarray:
        """Arc length ``(n,)`` of each mark's centre: marks of ``lengths`` (px along the
        curve) laid end to end in rank order, spread evenly over the whole curve."""
        order = np.argsort(ranks, kind="stable")
        total = self.curve.length
        room = max(total - lengths.sum(), 0.0)
        gap = room / max(len(lengths), 1)
        ends = np.cumsum(lengths[order] + gap)
        pos_sorted = ends - lengths[order] / 2 - gap / 2
        pos_sorted *= min(1.0, total / max(ends[-1], 1e-9))
        pos = np.empty(len(lengths))
        pos[order] = pos_sorted
        return pos

    def drift(self, arc: np.ndarray) -> np.ndarray:
        """Unit drift direction ``(n, 2)`` at arc positions ``arc``."""
        tangent, normal = self.curve.frame(arc)
        if self.direction == "along":
            return tangent
        if self.direction == "normal":
            return normal
        if self.direction is None:
            return np.zeros_like(tangent)
        a = math.radians(self.direction)
        return np.tile([math.cos(a), math.sin(a)], (len(arc), 1))


def emitter_from_json(d):
    """An emitter from its protocol dict (or None)."""
    if d is None:
        return None
    kind = d.get("kind") if isinstance(d, dict) else None
    if kind == "grid":
        return GridEmitter(d.get("speed", 1.0), d.get("direction"))
    if kind == "curve":
        return CurveEmitter(d["points"], d.get("speed", 1.0), d.get("direction", "along"),
                            d.get("mode", "free"))
    raise ValueError(f"emitter: unknown kind {kind!r}; expected 'grid' or 'curve'")
