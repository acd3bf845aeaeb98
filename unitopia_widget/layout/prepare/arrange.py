"""Grid arrangement (``arrange="grid"``): a layer snapped to rows and columns, a waffle in
any shape.

Every mark of a grid layer gets one square cell of a lattice aligned to the
canvas axes, as wide as the layer's largest footprint (margins included), and
stands still at the cell's centre. The cells are the lattice points whose
whole cell lies inside the container. A closed container without ``fill``
takes the largest cell at which it holds every mark (the layer's scale follows
from it); otherwise the scale is the one ``fill`` gives, shrunk until enough
cells fit. Of the cells, the cheapest (the forces' potential, or the distance to
the container's centre) are used, and the marks take them in ``order=``: row
by row (top to bottom; with forces, the row they pull hardest first), left to
right within a row.
"""
from __future__ import annotations

import math

import numpy as np

from ...design.encodings import footprint
from .lattice import Region

PHASES = (0.0, 0.25, 0.5, 0.75)   # lattice offsets tried, in cells, along x and y


def cells(region: Region, side: float) -> np.ndarray:
    """Centres ``(k, 2)`` of the square cells of ``side`` px lying inside ``region``, the
    lattice phase holding the most of them (rows first, then columns, in reading order)."""
    x0, y0, x1, y1 = region.bbox
    best = np.zeros((0, 2))
    for fx in PHASES:
        for fy in PHASES:
            xs = np.arange(x0 + (0.5 + fx) * side, x1, side)
            ys = np.arange(y0 + (0.5 + fy) * side, y1, side)
            if not len(xs) or not len(ys):
                continue
            gx, gy = np.meshgrid(xs, ys)
            pts = np.stack([gx.ravel(), gy.ravel()], 1)
            # the cell's corners lie inside when its centre is half a diagonal deep
            pts = pts[region.depth_at(pts) >= side / math.sqrt(2) * 0.999]
            if len(pts) > len(best):
                best = pts
    return best


def largest_cell(region: Region, count: int, upper: float) -> float:
    """The largest cell side (px, at most ``upper``) at which ``region`` holds ``count``
    cells (bisection on the log side, to 0.2%); ValueError when not even cells an eighth
    of the side that would tile its area do."""
    hi = min(upper, math.sqrt(region.area / count))   # count cells cannot cover more than the area
    lo = hi / 8
    if len(cells(region, hi)) >= count:
        return hi
    if len(cells(region, lo)) < count:
        raise ValueError(f"container: too small for a grid of {count} marks")
    for _ in range(12):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if len(cells(region, mid)) >= count else (lo, mid)
    return lo


def cell_side(units, idx) -> float:
    """A grid layer's cell side at scale 1: its largest footprint box side."""
    band = footprint(units.margin[idx])
    return float(np.max(2 * np.maximum(units.half_w[idx], units.half_h[idx]) * band))


def grid_scales(units, layers, canvas, group_scale, group_free, scale_group, rho: float):
    """``(group_scale, group_free)`` with every scale group holding a grid layer fixed (not
    controlled) at the largest scale, up to its start, whose cells hold that layer's marks."""
    scale, free = np.array(group_scale, dtype=float), np.array(group_free, dtype=bool)
    for i, layer in enumerate(layers):
        if layer.arrange != "grid":
            continue
        idx = np.nonzero(units.layer == i)[0]
        g, side = scale_group[i], cell_side(units, idx)
        region = Region(layer.region.coverage(canvas, rho), rho)
        fills = layer.boundary == "closed" and layer.fill is None
        upper = math.inf if fills else scale[g] * side
        try:
            fit = largest_cell(region, len(idx), upper) / side
        except ValueError as exc:
            raise ValueError(f"layer {layer.name!r}: {exc}") from None
        scale[g] = fit if free[g] else min(scale[g], fit)
        free[g] = False
    return scale, free


def snap(start, units, layers, canvas, unit_scale, cost_of, rho: float):
    """Place every grid layer's units at their cells, upright and held there, in place in
    ``start`` (a ``start.Start``); ``cost_of(layer, points)`` ranks cells."""
    for i, layer in enumerate(layers):
        if layer.arrange != "grid":
            continue
        idx = np.nonzero(units.layer == i)[0]
        region = Region(layer.region.coverage(canvas, rho), rho)
        side = cell_side(units, idx) * float(unit_scale[idx].max())
        spots = cells(region, side)
        if len(spots) < len(idx):   # the scale was set to fit; rounding lost a cell
            spots = cells(region, largest_cell(region, len(idx), side))
        used = spots[np.sort(np.argsort(cost_of(layer, spots), kind="stable")[:len(idx)])]
        if layer.forces:   # rows in the order the forces pull them, left to right in each
            row_cost = cost_of(layer, used)
            rows = np.unique(np.round(used[:, 1], 6))
            row_rank = {y: float(row_cost[np.isclose(used[:, 1], y)].mean()) for y in rows}
            key = np.array([row_rank[y] for y in np.round(used[:, 1], 6)])
            used = used[np.lexsort((used[:, 0], key))]
        else:
            used = used[np.lexsort((used[:, 0], used[:, 1]))]
        ranks = np.argsort(np.argsort(units.order[idx], kind="stable"), kind="stable")
        start.center[idx] = used[ranks]
        start.angle[idx], start.drift[idx] = 0.0, 0.0
        start.movable[idx] = start.turnable[idx] = False
