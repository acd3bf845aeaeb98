"""The paper's Table 1 set-up as plain discs: sizes, a start, and the exact quality measure.

Shared by the engine's benchmark (``table1.py``) and its physics peer
(``peers.py``), so both see the same container, force, sizes and measure.
Conventions: canvas px, y down; a disc is a centre ``(x, y)`` and a radius.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

W, H = 1440, 830                  # canvas
CX, CY, R = 720.0, 415.0, 400.0   # the circular container
FX, FY = CX, CY + R               # the point force, at the container's bottom
FILL = 0.6                        # marks' area / container area (open layouts)
SIZES = {"equal": "equal", "10x": "10x areas", "heavy": "heavy-tailed"}
HEAVY_SIGMA, HEAVY_SPREAD = 1.0, 100.0


def values(n: int, sizes: str, seed: int = 0) -> np.ndarray:
    """``(n,)`` data values, drawn as mark areas.

    ``"equal"``: all 1. ``"10x"``: uniform on [1, 10]. ``"heavy"``: lognormal
    (sigma ``HEAVY_SIGMA``), clipped to ``HEAVY_SPREAD`` x around the median
    (10x below to 10x above it; about 2% of the marks on each side are clipped).
    """
    if sizes not in SIZES:
        raise ValueError(f"sizes={sizes!r}: expected one of {', '.join(SIZES)}")
    rng = np.random.default_rng(seed)
    if sizes == "equal":
        return np.ones(n)
    if sizes == "10x":
        return rng.uniform(1, 10, n)
    half = math.sqrt(HEAVY_SPREAD)
    return np.clip(rng.lognormal(0.0, HEAVY_SIGMA, n), 1 / half, half)


def radii(value: np.ndarray, fill: float = FILL) -> np.ndarray:
    """``(n,)`` disc radii, areas proportional to ``value``, together ``fill`` of the container."""
    area = value / value.sum() * fill * math.pi * R * R
    return np.sqrt(area / math.pi)


def lattice_start(r: np.ndarray) -> np.ndarray:
    """``(n, 2)`` centres packed where the force pulls: the start the engine uses without
    an emitter, rebuilt here (so a peer can take it without the engine).

    A hexagonal lattice of spacing 2 x rms radius x 1.02 over the container, the
    points at least the mean radius inside it, the ``n`` nearest the force point,
    handed to the discs in data order (lattice and clearance shrink by 3% until
    they hold ``n``).
    """
    spacing, clearance = 2 * math.sqrt(float((r ** 2).mean())) * 1.02, float(r.mean())
    while len(inside := _hex_inside(spacing, clearance)) < len(r):
        spacing, clearance = spacing * 0.97, clearance * 0.97   # tighter, as the engine does
    order = np.argsort(np.hypot(inside[:, 0] - FX, inside[:, 1] - FY), kind="stable")
    return inside[order[:len(r)]]


def random_start(r: np.ndarray, seed: int = 0) -> np.ndarray:
    """``(n, 2)`` centres uniform over the container, each disc inside it, overlapping
    freely: the discs poured in, the way a physics engine is usually started."""
    # a stream apart from values(seed)'s, or a disc's angle would follow its size
    rng = np.random.default_rng([seed, 1])
    angle = rng.uniform(0, 2 * math.pi, len(r))
    dist = (R - r) * np.sqrt(rng.uniform(0, 1, len(r)))
    return np.stack([CX + dist * np.cos(angle), CY + dist * np.sin(angle)], axis=1)


def _hex_inside(spacing: float, clearance: float) -> np.ndarray:
    """Hexagonal lattice points ``(k, 2)``, row by row, ``clearance`` px or more inside."""
    rows = []
    for k, y in enumerate(np.arange(CY - R + spacing / 2, CY + R, spacing * math.sqrt(3) / 2)):
        xs = np.arange(CX - R + spacing / 2 * (1 + k % 2), CX + R, spacing)
        rows.append(np.stack([xs, np.full_like(xs, y)], axis=1))
    pts = np.concatenate(rows)
    return pts[np.hypot(pts[:, 0] - CX, pts[:, 1] - CY) <= R - clearance]


def lens_area(d, a, b):
    """Area ``(k,)`` shared by discs of radii ``a``, ``b`` whose centres are ``d`` apart."""
    d, a, b = (np.asarray(v, dtype=float) for v in np.broadcast_arrays(d, a, b))
    out = np.zeros_like(d)
    inner = d <= np.abs(a - b)
    out[inner] = math.pi * np.minimum(a, b)[inner] ** 2
    cut = ~inner & (d < a + b)
    d, a, b = d[cut], a[cut], b[cut]
    x1 = np.clip((d * d + a * a - b * b) / (2 * d * a), -1, 1)
    x2 = np.clip((d * d + b * b - a * a) / (2 * d * b), -1, 1)
    k = 0.5 * np.sqrt(np.maximum((-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b), 0))
    out[cut] = a * a * np.arccos(x1) + b * b * np.arccos(x2) - k
    return out


def circle_metrics(center: np.ndarray, r: np.ndarray) -> dict:
    """Exact quality of discs ``center (n, 2)``, ``r (n,)`` in the container.

    ``overlap_%``: pairwise lens areas over the discs' area; ``outside_%``: the
    discs' area outside the container over theirs; ``density``: their area over
    the container's; ``mean_y``: mean centre height (the container's centre is at
    415, its bottom at 815).
    """
    area = float(np.sum(math.pi * r ** 2))
    pairs = cKDTree(center).query_pairs(2 * float(r.max()), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    overlap = lens_area(np.hypot(*(center[i] - center[j]).T), r[i], r[j]).sum()
    dist = np.hypot(center[:, 0] - CX, center[:, 1] - CY)
    out = dist + r > R   # discs that cross the rim: their area minus the part inside
    outside = np.sum(math.pi * r[out] ** 2 - lens_area(dist[out], r[out], np.full(out.sum(), R)))
    return {"overlap_%": 100 * float(overlap) / area, "outside_%": 100 * float(outside) / area,
            "density": area / (math.pi * R * R), "mean_y": float(center[:, 1].mean())}
