"""Container outlines for the export (``outline=True``).

Vector containers give their own path data (``Container.svg_path``); image
masks and containers with eraser cuts have none, so their coverage raster is
traced by marching squares at level 0.5 into closed polylines (even-odd rings).
"""
from __future__ import annotations

from xml.sax.saxutils import quoteattr

import numpy as np

MAX_TRACE_SIDE = 1000   # raster px on the long side of a traced outline

# marching squares: for each of the 16 corner cases, the cell edges joined by a segment.
# corners: 1 top-left, 2 top-right, 4 bottom-right, 8 bottom-left; edges: 0 top, 1 right,
# 2 bottom, 3 left. Saddles (5, 10) are split as two segments.
_CASES = {1: [(3, 0)], 2: [(0, 1)], 3: [(3, 1)], 4: [(1, 2)], 5: [(3, 0), (1, 2)], 6: [(0, 2)],
          7: [(3, 2)], 8: [(2, 3)], 9: [(2, 0)], 10: [(0, 1), (2, 3)], 11: [(2, 1)],
          12: [(1, 3)], 13: [(1, 0)], 14: [(0, 3)]}


def trace(values: np.ndarray, level: float = 0.5) -> list[np.ndarray]:
    """Closed rings ``(k, 2)`` (x, y in raster index units: pixel (i, j) centred at (j, i)) where ``values``
    crosses ``level``; the array is padded so every ring closes."""
    v = np.pad(np.asarray(values, dtype=np.float64), 1, constant_values=0.0)
    inside = v >= level
    code = (inside[:-1, :-1] * 1 + inside[:-1, 1:] * 2 + inside[1:, 1:] * 4 + inside[1:, :-1] * 8)
    nxt: dict = {}
    points: dict = {}
    for i, j in zip(*np.nonzero((code > 0) & (code < 15))):
        for a, b in _CASES[int(code[i, j])]:
            ka, kb = _edge_key(i, j, a), _edge_key(i, j, b)
            nxt[ka] = kb
            for k in (ka, kb):
                if k not in points:
                    points[k] = _cross(v, k, level)
    rings = []
    while nxt:
        start, ring = next(iter(nxt)), []
        k = start
        while k in nxt:
            ring.append(points[k])
            k = nxt.pop(k)
        if len(ring) >= 3:
            rings.append(np.array(ring) - 1.0)   # undo the padding
    return rings


def _edge_key(i, j, edge):
    """A cell edge, shared by the two cells beside it: (row, col, horizontal?)."""
    return {0: (i, j, True), 2: (i + 1, j, True), 3: (i, j, False), 1: (i, j + 1, False)}[edge]


def _cross(v, key, level):
    """Where ``level`` crosses the edge ``key`` (x, y in padded pixel-centre units)."""
    i, j, horizontal = key
    a, b = (v[i, j], v[i, j + 1]) if horizontal else (v[i, j], v[i + 1, j])
    t = 0.5 if a == b else (level - a) / (b - a)
    return (j + t, i) if horizontal else (j, i + t)


def container_path(container, canvas) -> str:
    """SVG path data (fill even-odd) outlining ``container`` on ``canvas`` (w, h)."""
    d = container.svg_path(canvas)
    if d is not None:
        return d
    rho = min(1.0, MAX_TRACE_SIDE / max(canvas))
    rings = trace(container.coverage(canvas, rho))
    return "".join("M" + "L".join(f"{(x + 0.5) / rho:.1f} {(y + 0.5) / rho:.1f}" for x, y in ring) + "Z"
                   for ring in rings)


def outlines(layers, canvas) -> str:
    """One ``<path class="container">`` per layer with a container, beneath the units."""
    out = []
    for layer in layers:
        if layer.container is None:
            continue
        d = container_path(layer.container, canvas)
        out.append(f'<path class="container" data-layer={quoteattr(layer.name)} d="{d}" '
                   f'fill="none" fill-rule="evenodd" stroke="#555" stroke-width="1.5" '
                   f'stroke-dasharray="6 4"/>')
    return "".join(out)

