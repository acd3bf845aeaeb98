"""Position channels in the layout: targets, a beeswarm start, and the attraction to them.

A layer with ``x=`` (or ``y=``) has, per unit, a target along that axis: its
fraction of the extent (``design/positions``) mapped onto the span of the
container where it is at least a median mark radius deep (so the marks at
both ends fit). Marks start packed *dodge* fashion: one by one, each takes the
free spot (one whose clearance holds its footprint disc) nearest its target
along the bound axis, and along a free axis nearest the container's deepest
line; where its target is full it moves aside to the nearest room. During the
layout an ``Anchor`` pulls each unit towards its target (a Huber loss on the
distance beyond its band's half width, in mean radii), while overlap and
containment keep it packed: a beeswarm inside any shape.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ...design.positions import POSITION_CHANNELS, position_scale
from .lattice import Region
from .pack import Packing
from .start import footprint_radius

BIN = 4.0              # scale cap: bins along a bound axis, in median footprint radii
MAX_BINS = 200         # scale cap: bins along one axis at most
PACKED = 0.6           # scale cap: the share of a bin's area its discs may need
ANCHOR_WEIGHT = 0.05   # pull towards the target, relative to overlap (forces use 0.005 at rest)
BAND_PULL = 20.0       # the pull back into a band, times the pull towards a number
BOUND_COST = 10.0      # start: a px off the target costs as much as this many off the middle
DODGE_STEP = 0.5       # start: spot spacing in median footprint radii (the optimiser refines)
BAND_COST = 1000.0     # start: a px out of a band costs as much as this many off a number
BAND_GAP = 0.2         # the share of each band kept empty between bands (half at each side)


@dataclass
class Axis:
    """A bound axis of one layer, as drawn by the export (``output/axes``).

    ``lo``, ``hi``: canvas px of the extent's ends along the axis; ``cross``: the
    container's edge on the other axis (bottom for x, left for y) beyond which the axis
    line stands."""

    layer: str
    channel: str
    scale: object          # design.positions.Scale
    lo: float
    hi: float
    cross: float

    def at(self, fraction):
        """Canvas px of ``fraction`` (array or float) of the extent."""
        return self.lo + np.asarray(fraction, dtype=float) * (self.hi - self.lo)


def bind_positions(df, layers, layer_rows):
    """``(position (N, 2), band (N, 2), scales)`` of the units of ``layers`` (concatenated in
    layer order, as ``bind.bind`` does; see ``design.units.Units``), or ``(None, None, None)`` when
    no layer binds x or y. ValueError for a bad binding or ``arrange="grid"`` with one."""
    if not any(layer.encodings.get(c) is not None for layer in layers for c in POSITION_CHANNELS):
        return None, None, None
    positions, bands, scales = [], [], []
    for layer in layers:
        sub = layer_rows(df, layer)
        place, band = np.full((len(sub), 2), np.nan), np.zeros((len(sub), 2))
        mine = {}
        for dim, channel in enumerate(POSITION_CHANNELS):
            column = layer.encodings.get(channel)
            if column is None:
                continue
            if layer.arrange == "grid":
                raise ValueError(f"layer {layer.name!r}: arrange='grid' places marks in rows and "
                                 f"columns by order=, so it cannot take {channel}={column!r}; use "
                                 f"arrange='free' with {channel}=, or order={column!r} with the grid")
            mine[channel] = scale = position_scale(df, channel, column,
                                                   getattr(layer, f"{channel}_scale"))
            place[:, dim], band[:, dim] = scale.fraction(sub[column])
        positions.append(place)
        bands.append(band)
        scales.append(mine)
    return np.concatenate(positions), np.concatenate(bands), scales


def extent(region: Region, dim: int, reach: float) -> tuple[float, float]:
    """(lo, hi) canvas px along ``dim`` (0 x, 1 y) of the span where the region is at least
    ``reach`` px deep (its deepest part when nowhere is)."""
    deepest = region.depth.max(axis=0 if dim == 0 else 1)
    ok = np.nonzero(deepest >= min(reach, float(deepest.max())))[0]
    return (ok[0] + 0.5) / region.rho, (ok[-1] + 0.5) / region.rho


def anchors(units, layers, canvas, radius, rho: float):
    """``(target (N, 2), tolerance (N, 2), mask (N, 2) bool, axes)`` in canvas px for the
    position channels of ``units``; ``radius (N,)`` the footprint radii at the start
    scale. None when no layer binds x or y."""
    if units.position is None:
        return None
    n = len(units.layer)
    target, tol = np.zeros((n, 2)), np.zeros((n, 2))
    mask = np.isfinite(units.position)
    axes = []
    for i, layer in enumerate(layers):
        scales = units.position_scales[i]
        if not scales:
            continue
        idx = np.nonzero(units.layer == i)[0]
        region = Region(layer.region.coverage(canvas, rho), rho)
        reach = float(np.median(radius[idx]))
        x0, _, _, y1 = region.bbox
        for dim, channel in enumerate(POSITION_CHANNELS):
            if channel not in scales:
                continue
            lo, hi = extent(region, dim, reach)
            axis = Axis(layer.name, channel, scales[channel], lo, hi, y1 if dim == 0 else x0)
            axes.append(axis)
            target[idx, dim] = axis.at(units.position[idx, dim])
            inner = units.band[idx, dim] * (1.0 - BAND_GAP) * (hi - lo)   # 0 for numbers
            tol[idx, dim] = np.maximum(inner - radius[idx], 0.0)
    return target, tol, mask, axes


def capped_scales(units, layers, canvas, group_scale, group_free, scale_group, rho: float):
    """``(group_scale, group_free)`` with each scale group holding a layer with position
    channels fixed at most at the scale where its marks fit near their targets: along each
    bound axis, cut into bins ``BIN`` median footprint radii wide (or the bands), the discs
    aimed at each bin need at most ``PACKED`` of the container's area in it. (Two bound
    axes are checked one by one: where the container has no room at both targets, the
    marks move aside.)"""
    if units.position is None:
        return group_scale, group_free
    scale, free = np.array(group_scale, dtype=float), np.array(group_free, dtype=bool)
    r1 = footprint_radius(units)
    for i, layer in enumerate(layers):
        scales = units.position_scales[i]
        if not scales:
            continue
        idx, g = np.nonzero(units.layer == i)[0], scale_group[i]
        region = Region(layer.region.coverage(canvas, rho), rho)
        ys, xs = np.nonzero(region.depth > 0)
        pixels = (np.stack([xs, ys], 1) + 0.5) / rho
        s = scale[g]
        for _ in range(4):   # the bins widen with the marks: a few rounds settle the scale
            reach = float(np.median(r1[idx])) * s
            worst = 1.0
            for dim, channel in enumerate(POSITION_CHANNELS):
                if channel not in scales:
                    continue
                lo, hi = extent(region, dim, reach)
                if scales[channel].kind == "band":
                    count = len(scales[channel].domain)
                else:
                    count = int(np.clip((hi - lo) / (BIN * reach), 1, MAX_BINS))
                unit_bin = np.clip((units.position[idx, dim] * count).astype(int), 0, count - 1)
                along = (pixels[:, dim] - lo) / max(hi - lo, 1e-9) * count
                pixel_bin = np.clip(along.astype(int), 0, count - 1)
                inside = np.ones(len(along))
                if scales[channel].kind == "band":   # the gaps between bands hold no marks
                    inside = np.abs(along - pixel_bin - 0.5) <= (1.0 - BAND_GAP) / 2
                room = np.bincount(pixel_bin, weights=inside, minlength=count) / rho ** 2
                need = np.bincount(unit_bin, weights=np.pi * (r1[idx] * s) ** 2, minlength=count)
                used = need > 0
                worst = min(worst, float(np.min(PACKED * room[used] / need[used])))
            if worst >= 1.0:
                break
            s *= math.sqrt(max(worst, 1e-6))
        scale[g] = s if free[g] else min(scale[g], s)
        free[g] = False
    return scale, free


class Anchor:
    """The pull of anchored units towards their targets: ``ANCHOR_WEIGHT`` x the mean over
    them of a Huber loss (quadratic within one mean radius) on the distance past the band's
    half width, in mean radii; ``BAND_PULL`` times stronger out of a band (a category is
    kept, a number is near). ``target``, ``tol``: ``(N, 2)`` canvas px; ``mask`` ``(N, 2)``
    bool; ``band`` ``(N, 2)`` half band widths (``Units.band``)."""

    def __init__(self, target, tol, mask, axes, radius: float, device, band=None):
        dev = torch.device(device)
        self.target = torch.tensor(np.where(mask, target, 0.0), dtype=torch.float32, device=dev)
        self.tol = torch.tensor(tol, dtype=torch.float32, device=dev)
        pull = mask * np.where(band > 0, BAND_PULL, 1.0) if band is not None else mask
        self.mask = torch.tensor(pull, dtype=torch.float32, device=dev)
        self.count = max(int(mask.any(axis=1).sum()), 1)
        self.axes, self.radius, self.weight = axes, float(radius), ANCHOR_WEIGHT

    def loss(self, center: torch.Tensor) -> torch.Tensor:
        """Scalar loss of ``center (N, 2)``."""
        d = torch.relu((center - self.target).abs() - self.tol) / self.radius
        huber = torch.where(d < 1.0, 0.5 * d * d, d - 0.5)
        return self.weight * (huber * self.mask).sum() / self.count


def dodge(center: np.ndarray, units, layers, canvas, radius, target, tol, mask, ranks_of,
          rho: float) -> None:
    """Start the anchored units of each layer packed dodge fashion (module docstring), in
    place in ``center (N, 2)``; ``radius (N,)`` footprint radii; ``ranks_of(idx)`` each
    unit's placing order within its layer."""
    for i, layer in enumerate(layers):
        idx = np.nonzero((units.layer == i) & mask.any(axis=1))[0]
        if not len(idx):
            continue
        region = Region(layer.region.coverage(canvas, rho), rho)
        r = radius[idx]
        pack = Packing(region, DODGE_STEP * float(np.median(r)), float(r.max()))
        pts, clear, tree = pack.points, pack.clear, pack.tree
        if tree is None:
            raise ValueError(f"layer {layer.name!r}: its container has no room to place marks in")
        free_cost = _middle_cost(region, pts, mask[idx[0]])
        # a band is a category: leaving it misreads the mark, moving along a number does not
        weight = BOUND_COST * np.where(units.band[idx[0]] > 0, BAND_COST, 1.0) * mask[idx[0]]
        dim = int(np.argmax(mask[idx[0]]))   # spots sorted along a bound axis: a window on it
        by_axis = np.argsort(pts[:, dim], kind="stable")
        axis = pts[by_axis, dim]
        for k in np.argsort(ranks_of(idx), kind="stable"):
            u, ru = idx[k], float(r[k])
            j, width = -1, 4 * ru + tol[u, dim]
            while j < 0:
                # a spot farther than ``width`` off along ``dim`` costs more than BOUND_COST x width
                lo, hi = np.searchsorted(axis, [target[u, dim] - width, target[u, dim] + width])
                near = by_axis[lo:hi]
                off = np.maximum(np.abs(pts[near] - target[u]) - tol[u], 0.0)
                cost = np.where(clear[near] >= ru, off @ weight + free_cost[near], np.inf)
                best = int(np.argmin(cost)) if len(near) else 0
                if len(near) and cost[best] <= weight[dim] * width:
                    j = int(near[best])
                elif lo == 0 and hi == len(axis):   # no spot holds it: the roomiest one
                    j = int(near[best]) if len(near) and np.isfinite(cost[best]) else int(np.argmax(clear))
                width *= 2
            center[u] = pts[j]
            near = np.asarray(tree.query_ball_point(pts[j], ru + pack.reach), dtype=np.int64)
            clear[near] = np.minimum(clear[near], np.hypot(*(pts[near] - pts[j]).T) - ru)


def _middle_cost(region: Region, pts: np.ndarray, bound: np.ndarray) -> np.ndarray:
    """``(k,)`` canvas px from each spot to the container's deepest line along each free
    axis (the line a beeswarm grows out from); 0 when both axes are bound."""
    cost = np.zeros(len(pts))
    depth = region.depth
    for dim in (0, 1):
        if bound[dim]:
            continue
        other = 1 - dim
        # the deepest point of each raster line across the free axis, along the bound one
        line = np.argmax(depth, axis=0 if dim == 1 else 1)
        at = np.clip((pts[:, other] * region.rho).astype(int), 0, len(line) - 1)
        cost += np.abs(pts[:, dim] - (line[at] + 0.5) / region.rho)
    return cost
