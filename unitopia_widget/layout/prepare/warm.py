"""Warm starts: a layout re-run after a change starts from the last one.

A *snapshot* of a layout keeps, per unit, its layer name, row, centre, angle and drawn
footprint area. ``warm_problem`` starts the units it matches (same layer, same row) at
their old centre (and angle, where it turns), with no drift and no pouring wait. Rows
added since enter from their layer's emitter when it has one; without, each takes the
free room nearest where a fresh start would put it (the spot of the container whose
clearance from the container's edge, the kept marks and the pins holds its footprint
disc; the roomiest spot when none does). A kept mark whose old centre is now outside
its container is placed as an added one. Each controlled scale starts where the marks'
drawn footprint area covers as much as before (rows added, or sizes grown, shrink it by
the square root of the area ratio), and never above the kept marks' old scale: marks
start as large as they were, with no overlap, and the controller grows the scale into
the room removed rows left, as in any run, so the container fills again.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from ...design.encodings import footprint
from .lattice import Region, container_region
from .pack import STEP, Packing
from ..step.placement import Placement
from .start import footprint_radius


def replace_start(place: Placement, center=None, angle=None, movable=None, turnable=None,
                  drift=None, tracks=None) -> Placement:
    """A new ``Placement`` like ``place`` with the given starting arrays (and curve
    ``tracks``) replaced."""
    t, theta = place.t.detach().cpu().numpy(), place.theta.detach().cpu().numpy()
    old_drift = None if place.drift is None else place.drift.cpu().numpy()
    return Placement(t if center is None else center, theta if angle is None else angle,
                     place.movable.cpu().numpy() if movable is None else movable,
                     place.turnable if turnable is None else turnable, place.device,
                     orientation=place.orientation, orientation_weight=place.orientation_weight,
                     tracks=place.tracks if tracks is None else tracks,
                     drift=old_drift if drift is None else drift)


def snapshot(units, layers, result) -> pd.DataFrame:
    """The layout ``result`` of ``units`` as a warm start needs it: one row per unit
    (layer, row, x, y, angle degrees, area: drawn footprint area px^2, margins included)."""
    names = np.array([layer.name for layer in layers], dtype=object)
    scale = np.asarray(result.unit_scale, dtype=float)
    return pd.DataFrame({
        "layer": names[units.layer], "row": units.rows,
        "x": result.center[:, 0], "y": result.center[:, 1], "angle": result.angle,
        "area": units.area * footprint(units.margin) ** 2 * scale ** 2})


def unit_keys(layers, rows) -> list:
    """``(layer, row, n)`` per unit: the n-th unit of its layer drawing that row (a row of a
    ``count=`` column draws several), so a warm start matches each to its own old place."""
    seen, out = {}, []
    for key in zip(layers, rows):
        n = seen[key] = seen.get(key, -1) + 1
        out.append((*key, n))
    return out


def warm_problem(problem, units, layers, canvas, previous: pd.DataFrame,
                 pinned: np.ndarray, pin_xy: np.ndarray, placed: np.ndarray | None = None):
    """``problem`` started from the snapshot ``previous``; ``pinned (P,)`` unit indices held
    at ``pin_xy (P, 2)`` count as taken room for the added marks; ``placed (N,)`` bool: the
    units whose room the caller makes (``room.make_room``), added ones left where they are."""
    p = problem
    names = [layer.name for layer in layers]
    where = {key: k for k, key in enumerate(unit_keys(previous["layer"], previous["row"]))}
    found = np.array([where.get(key, -1) for key in
                      unit_keys([names[li] for li in units.layer], units.rows)])
    # a grid's marks stand in the cells the fresh start snapped them to (their container
    # may have moved): only marks that move start where they were
    still = ~p.placement.movable.cpu().numpy().astype(bool)
    kept = (found >= 0) & ~still
    if not kept.any():
        return problem
    old = previous.iloc[found[kept]]
    group_of, group_scale, free = p.layer_groups(), p.group_scales(), p.group_controlled()
    unit_group = group_of[units.layer]
    foot = units.area * footprint(units.margin) ** 2
    old_group = group_of[[names.index(n) if n in names else 0 for n in previous["layer"]]]
    old_known = previous["layer"].isin(names).to_numpy()
    ratio = np.sqrt(old["area"].to_numpy(dtype=float) / foot[kept])   # each kept unit's old scale
    for g in np.nonzero(free)[0]:
        before = float(previous["area"][old_known & (old_group == g)].sum())
        now = float(foot[unit_group == g].sum())
        mine = unit_group[kept] == g
        if before > 0 and now > 0 and mine.any():
            # never above the old scale: the controller grows it into the room it finds
            group_scale[g] = min(np.sqrt(before / now), float(np.median(ratio[mine])))
    scale = group_scale[unit_group]
    place = p.placement
    center = place.t.detach().cpu().numpy().astype(float)
    angle = place.theta.detach().cpu().numpy().astype(float)
    drift = np.zeros_like(center) if place.drift is None else place.drift.cpu().numpy().copy()
    center[kept] = old[["x", "y"]].to_numpy(dtype=float)
    turn = kept & place.turnable
    angle[turn] = np.radians(previous["angle"].to_numpy(dtype=float)[found[turn]])
    drift[kept] = 0.0
    radius = footprint_radius(units) * scale
    rho = p.grid.rho
    regions = {}
    keys = [repr(layer.region.to_json()) for layer in layers]
    for i, (layer, key) in enumerate(zip(layers, keys)):
        if key not in regions:
            regions[key] = container_region(layer.region, canvas, rho)
        mine = units.layer == i
        outside = mine & kept & ~regions[key].contains(center)
        kept[outside] = False
    is_pinned = np.isin(np.arange(len(center)), pinned)
    center[pinned] = pin_xy
    unit_key = np.array(keys, dtype=object)[units.layer]
    for key, region in regions.items():
        inside = unit_key == key
        added = inside & ~kept & ~is_pinned & ~still & np.array([layers[li].emitter is None
                                                                 for li in units.layer])
        if placed is not None:
            added &= ~placed
        if added.any():
            taken = inside & (kept | is_pinned)
            center[added] = free_room(region, center, radius, taken, added)
    stage = None if p.stage is None else np.where(kept, 0, p.stage)
    arriving = ~kept & ~is_pinned & np.array([layers[li].emitter is not None for li in units.layer])
    tracks = [track.restarted(center, kept) for track in place.tracks]
    return dataclasses.replace(
        p, placement=replace_start(place, center, angle, drift=drift, tracks=tracks),
        group_scale=group_scale,
        scale=float(group_scale[0]), stage=stage, travelling=bool(arriving.any()))


def free_room(region: Region, center: np.ndarray, radius: np.ndarray, taken: np.ndarray,
               added: np.ndarray) -> np.ndarray:
    """Centres ``(k, 2)`` for the ``added (N,)`` units, largest first: each at the spot
    nearest its fresh start ``center`` whose clearance from the edge and the ``taken (N,)``
    discs holds its radius, else at the roomiest spot."""
    r = radius[added]
    packing = Packing(region, STEP * float(np.median(radius)), float(r.max()))
    packing.stamp(center[taken], radius[taken])
    out = center[added].copy()
    for i in np.argsort(-r, kind="stable"):
        fits = packing.clear >= r[i]
        if fits.any():
            gap = np.hypot(*(packing.points - out[i]).T)
            k = int(np.argmin(np.where(fits, gap, np.inf)))
        else:
            k = int(np.argmax(packing.clear))
        out[i] = packing.points[k]
        packing.stamp(out[i:i + 1], r[i:i + 1])
    return out
