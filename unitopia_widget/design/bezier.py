"""Piecewise cubic Bezier curves: arc-length sampling and fitting to strokes.

Control points are ``(3k + 1, 2)`` canvas px: segment ``j`` uses points
``3j .. 3j + 3``. A ``Curve`` keeps a dense polyline (``SAMPLES`` points per
segment) with cumulative arc length, so positions, tangents and nearest
points are lookups, in numpy or (for the solver) torch.
"""
from __future__ import annotations

import numpy as np
import torch

SAMPLES = 128


class Curve:
    """A piecewise cubic Bezier with an arc-length table."""

    def __init__(self, points):
        pts = np.asarray(points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 4 or (len(pts) - 1) % 3:
            shape = pts.shape if pts.ndim else "a scalar"
            raise ValueError(f"CurveEmitter: points must be cubic Bezier control points of shape "
                             f"(3k + 1, 2) with k >= 1 (4, 7, 10, ... points); got {shape}")
        if not np.isfinite(pts).all():
            raise ValueError("CurveEmitter: points must be finite numbers")
        self.points = pts
        t = np.linspace(0, 1, SAMPLES + 1)[:-1]
        segs = []
        for j in range(0, len(pts) - 1, 3):
            p0, p1, p2, p3 = pts[j:j + 4]
            u = 1 - t[:, None]
            segs.append(u ** 3 * p0 + 3 * u ** 2 * t[:, None] * p1 + 3 * u * t[:, None] ** 2 * p2
                        + t[:, None] ** 3 * p3)
        segs.append(pts[-1:])
        self.polyline = np.concatenate(segs)                       # (M, 2)
        steps = np.linalg.norm(np.diff(self.polyline, axis=0), axis=1)
        self.arc = np.concatenate([[0.0], np.cumsum(steps)])       # (M,)
        if self.arc[-1] <= 1e-6:
            raise ValueError("CurveEmitter: the curve has zero length; give distinct control points")
        self._poly_t = torch.tensor(self.polyline, dtype=torch.float32)
        self._arc_t = torch.tensor(self.arc, dtype=torch.float32)

    @property
    def length(self) -> float:
        return float(self.arc[-1])

    def at(self, arc: np.ndarray) -> np.ndarray:
        """Points ``(n, 2)`` at arc lengths ``(n,)`` px (clamped to the curve)."""
        s = np.clip(arc, 0, self.length)
        return np.stack([np.interp(s, self.arc, self.polyline[:, 0]),
                         np.interp(s, self.arc, self.polyline[:, 1])], axis=1)

    def frame(self, arc: np.ndarray):
        """Unit tangent and normal ``(n, 2)`` at arc lengths (normal = tangent turned +90 deg)."""
        eps = min(1.0, self.length / 1000)
        d = self.at(np.asarray(arc) + eps) - self.at(np.asarray(arc) - eps)
        tangent = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)
        normal = np.stack([-tangent[:, 1], tangent[:, 0]], axis=1)
        return tangent, normal

    def torch_at(self, arc: torch.Tensor):
        """Differentiable points and unit tangents ``(n, 2)`` at arc lengths ``(n,)``."""
        if self._poly_t.device != arc.device:   # moved once: no copy per iteration
            self._poly_t, self._arc_t = self._poly_t.to(arc.device), self._arc_t.to(arc.device)
        poly, table = self._poly_t, self._arc_t
        s = arc.clamp(0, self.length)
        i = torch.searchsorted(table, s.detach()).clamp(1, len(table) - 1)
        a0, a1 = table[i - 1], table[i]
        w = ((s - a0) / (a1 - a0).clamp_min(1e-9))[:, None]
        p0, p1 = poly[i - 1], poly[i]
        tangent = (p1 - p0) / (p1 - p0).norm(dim=1, keepdim=True).clamp_min(1e-9)
        return p0 + w * (p1 - p0), tangent

    def nearest_arc(self, points: np.ndarray) -> np.ndarray:
        """Arc length ``(n,)`` of the curve point nearest to each of ``points (n, 2)``: each
        point's foot on the nearest segment of the polyline (``torch_at``'s curve)."""
        start, step = self.polyline[:-1], np.diff(self.polyline, axis=0)       # (M - 1, 2)
        span = np.maximum((step ** 2).sum(1), 1e-18)
        rel = np.asarray(points, dtype=float)[:, None, :] - start[None]          # (n, M - 1, 2)
        t = np.clip((rel * step[None]).sum(-1) / span, 0.0, 1.0)
        gap = ((rel - t[..., None] * step[None]) ** 2).sum(-1)
        k = np.argmin(gap, axis=1)
        picked = t[np.arange(len(k)), k]
        return self.arc[k] + picked * (self.arc[k + 1] - self.arc[k])


def fit_bezier(stroke: np.ndarray, tolerance: float = 4.0, max_depth: int = 12) -> np.ndarray:
    """Control points ``(3k + 1, 2)`` of cubic Beziers fitting a stroke ``(m, 2)``.

    Least-squares fit from chord-length parameters refined by Newton steps; a
    segment whose worst point is further than ``tolerance`` px is split there
    (Schneider's method).
    """
    pts = np.asarray(stroke, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2:
        raise ValueError(f"stroke must be an (m, 2) array with m >= 2 points, got shape {pts.shape}")
    if not np.isfinite(pts).all():
        k = int(np.nonzero(~np.isfinite(pts).all(axis=1))[0][0])
        raise ValueError(f"stroke: point {k} is {pts[k].tolist()}, not finite; every point of a "
                         f"stroke must be a pair of finite numbers")
    keep = np.concatenate([[True], np.linalg.norm(np.diff(pts, axis=0), axis=1) > 1e-9])
    pts = pts[keep]
    if len(pts) < 2:
        raise ValueError("stroke: all points coincide; draw a longer stroke")
    out = _fit(pts, tolerance, max_depth)
    return np.concatenate([out[0][:1]] + [seg[1:] for seg in out])


def _fit(pts: np.ndarray, tol: float, depth: int) -> list[np.ndarray]:
    chord = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    t = chord / chord[-1]
    seg = _least_squares(pts, t)
    for _ in range(4):   # Newton steps move each point's parameter to its nearest curve point
        err = np.linalg.norm(_bezier(seg, t) - pts, axis=1)
        if err.max() <= tol:
            break
        t = _reparameterise(seg, pts, t)
        seg = _least_squares(pts, t)
    err = np.linalg.norm(_bezier(seg, t) - pts, axis=1)
    worst = int(np.argmax(err))
    if err[worst] <= tol or depth <= 0 or len(pts) < 4:
        return [seg]
    worst = min(max(worst, 1), len(pts) - 2)
    return _fit(pts[:worst + 1], tol, depth - 1) + _fit(pts[worst:], tol, depth - 1)


def _basis(t: np.ndarray) -> np.ndarray:
    return np.stack([(1 - t) ** 3, 3 * (1 - t) ** 2 * t, 3 * (1 - t) * t ** 2, t ** 3], axis=1)


def _bezier(seg: np.ndarray, t: np.ndarray) -> np.ndarray:
    return _basis(t) @ seg


def _least_squares(pts: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The cubic through the stroke's end points fitting ``pts`` at parameters ``t``."""
    p0, p3 = pts[0], pts[-1]
    if len(pts) <= 3:
        return np.stack([p0, p0 + (p3 - p0) / 3, p0 + 2 * (p3 - p0) / 3, p3])
    b = _basis(t)
    rhs = pts - np.outer(b[:, 0], p0) - np.outer(b[:, 3], p3)
    inner, *_ = np.linalg.lstsq(b[:, 1:3], rhs, rcond=None)
    return np.stack([p0, inner[0], inner[1], p3])


def _reparameterise(seg: np.ndarray, pts: np.ndarray, t: np.ndarray) -> np.ndarray:
    """One Newton-Raphson step on |B(t) - p|^2 for every point; ends stay at 0 and 1."""
    d1 = 3 * np.diff(seg, axis=0)                      # (3, 2) first-derivative control points
    d2 = 2 * np.diff(d1, axis=0)                       # (2, 2)
    u = 1 - t
    q = _bezier(seg, t) - pts
    q1 = (u ** 2)[:, None] * d1[0] + (2 * u * t)[:, None] * d1[1] + (t ** 2)[:, None] * d1[2]
    q2 = u[:, None] * d2[0] + t[:, None] * d2[1]
    num = (q * q1).sum(1)
    den = (q1 * q1).sum(1) + (q * q2).sum(1)
    step = np.where(np.abs(den) > 1e-12, num / np.where(den == 0, 1, den), 0.0)
    out = np.clip(t - step, 0.0, 1.0)
    out[0], out[-1] = 0.0, 1.0
    return np.maximum.accumulate(out)
