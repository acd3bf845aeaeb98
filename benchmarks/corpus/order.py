"""Measures of where marks lie, read from the placements table (centres and drawn boxes).

``strata_in_order``: for each layer that blocks on another and is pulled by one kind of
force, the share of its marks that lie beyond the lower layer's envelope swept along the
force (above its upper envelope under a directional force; outside its outer envelope
around the nearest point under point forces), averaged over such pairs.
``size_rho``: |Spearman rho| of mark area against position (the distance from the nearest
point force; the depth along a directional force; else the distance from the container's
centre), per layer, weighted by its marks.
``pull``: how far the forces gathered the marks, per forced layer weighted by its marks:
under a directional force the marks' mean depth along it, as a share of the container's
extent along it (1: against the far wall); under point forces one less the ratio of the
marks' mean distance from the nearest point to the container's (1: all at the points,
0: as spread as the container).
"""
from __future__ import annotations

import math

import numpy as np
from scipy import stats

import unitopia_widget as uw


def _discs(table, name):
    part = table[table["layer"] == name]
    xy = part[["x", "y"]].to_numpy(float)
    half = np.hypot(part["width"].to_numpy(float), part["height"].to_numpy(float)) / 4 + \
        np.minimum(part["width"].to_numpy(float), part["height"].to_numpy(float)) / 4
    return xy, half   # centres (n, 2); radius between the inscribed and the circumscribed


def _beyond_directional(lower, upper, angle_deg) -> np.ndarray:
    """Bool per upper disc: its centre above the lower discs' envelope against the force."""
    a = math.radians(angle_deg)
    down, across = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
    (lxy, lr), (uxy, _) = lower, upper
    lu, ld = lxy @ across, lxy @ down
    uu, ud = uxy @ across, uxy @ down
    gap = np.abs(uu[:, None] - lu[None, :])                       # (n_upper, n_lower)
    rise = np.sqrt(np.maximum(lr[None, :] ** 2 - gap ** 2, 0))
    top = np.where(gap < lr[None, :], ld[None, :] - rise, np.inf).min(axis=1)
    return ud <= top


def _beyond_points(lower, upper, points) -> np.ndarray:
    """Bool per upper disc: its centre farther from its nearest point than the lower discs'
    outer envelope around that point, in its direction."""
    (lxy, lr), (uxy, _) = lower, upper
    near = np.argmin(np.linalg.norm(uxy[:, None, :] - points[None], axis=2), axis=1)
    lnear = np.argmin(np.linalg.norm(lxy[:, None, :] - points[None], axis=2), axis=1)
    out = np.ones(len(uxy), bool)
    for j, p in enumerate(points):
        u, low = uxy[near == j] - p, lxy[lnear == j] - p
        if not len(u) or not len(low):
            continue
        dist_u = np.linalg.norm(u, axis=1)
        unit = u / np.maximum(dist_u, 1e-9)[:, None]
        along = unit @ low.T                                        # (n_u, n_low)
        side = np.abs(unit[:, 0:1] * low[None, :, 1] - unit[:, 1:2] * low[None, :, 0])
        r = lr[lnear == j][None, :]
        rise = np.sqrt(np.maximum(r ** 2 - side ** 2, 0))
        reach = np.where((side < r) & (along > -r), along + rise, 0)
        out[near == j] = dist_u >= reach.max(axis=1)
    return out


def strata_in_order(table, layers) -> float | None:
    """Share in [0, 1] (None when no layer blocks on another under one kind of force)."""
    shares = []
    for layer in layers:
        points = [f for f in layer.forces if isinstance(f, uw.PointForce)]
        pushes = [f for f in layer.forces if isinstance(f, uw.DirectionalForce)]
        if bool(points) == bool(pushes):
            continue
        for below in layer.blocks:
            lower, upper = _discs(table, below), _discs(table, layer.name)
            if not len(lower[0]) or not len(upper[0]):
                continue
            if pushes:
                angle = math.degrees(math.atan2(sum(f.vector[1] for f in pushes),
                                                sum(f.vector[0] for f in pushes)))
                shares.append(float(_beyond_directional(lower, upper, angle).mean()))
            else:
                centres = np.array([[f.x, f.y] for f in points])
                shares.append(float(_beyond_points(lower, upper, centres).mean()))
    return float(np.mean(shares)) if shares else None


def position(xy: np.ndarray, layer, centre) -> np.ndarray:
    """Per mark, the position its size is compared with (see module doc)."""
    points = np.array([[f.x, f.y] for f in layer.forces if isinstance(f, uw.PointForce)])
    pushes = [f for f in layer.forces if isinstance(f, uw.DirectionalForce)]
    if len(points):
        return np.linalg.norm(xy[:, None, :] - points[None], axis=2).min(axis=1)
    if pushes:
        return xy @ np.array([sum(f.vector[0] for f in pushes), sum(f.vector[1] for f in pushes)])
    return np.linalg.norm(xy - np.asarray(centre), axis=1)


def size_rho(table, layers, canvas) -> float | None:
    rhos, weights = [], []
    for layer in layers:
        part = table[table["layer"] == layer.name]
        area = (part["width"] * part["height"]).to_numpy(float)
        if len(part) < 5 or np.ptp(area) <= 1e-6 * area.max():
            continue
        pos = position(part[["x", "y"]].to_numpy(float), layer, layer.region.centroid(canvas))
        rho = stats.spearmanr(area, pos).statistic
        if np.isfinite(rho):
            rhos.append(abs(float(rho)))
            weights.append(len(part))
    return float(np.average(rhos, weights=weights)) if rhos else None


def pull(table, layers, canvas) -> float | None:
    values, weights = [], []
    for layer in layers:
        part = table[table["layer"] == layer.name]
        points = np.array([[f.x, f.y] for f in layer.forces if isinstance(f, uw.PointForce)])
        pushes = [f for f in layer.forces if isinstance(f, uw.DirectionalForce)]
        if not len(part) or bool(len(points)) == bool(pushes):
            continue
        ys, xs = np.nonzero(np.asarray(layer.region.coverage(canvas, 1.0)) >= 0.5)
        room = np.c_[xs, ys] + 0.5
        xy = part[["x", "y"]].to_numpy(float)
        if pushes:
            down = np.array([sum(f.vector[0] for f in pushes), sum(f.vector[1] for f in pushes)])
            depth, span = xy @ down, room @ down
            values.append(float(np.mean((depth - span.min()) / max(np.ptp(span), 1e-9))))
        else:
            def near(p):
                return np.linalg.norm(p[:, None, :] - points[None], axis=2).min(axis=1)
            values.append(1.0 - float(near(xy).mean() / max(near(room[::7]).mean(), 1e-9)))
        weights.append(len(part))
    return float(np.average(values, weights=weights)) if values else None
