"""Room made for added rows, and closed over removed ones, in a container the marks fill.

Where a controlled scale fills a closed container, rows added make every mark smaller (the
scale shrinks by the square root of the footprint area ratio, as a warm start's does) and
rows removed make every mark larger; the room this takes or gives lies in thin gaps all over
the container, which no mark near a change sees. ``make_room`` moves the kept marks along
an area-preserving map instead, so that the layout stays nearly legal at the new scale:

* each added mark gets a *site*, the roomiest spot of its container (the clearance from the
  edge and from the marks at the new scale), away from the other sites;
* around each site, a radial map opens a hole of the mark's *cell* (its footprint area over
  the marks' packing density, ``a``) and compresses the disc of radius ``R`` around it by
  the kept marks' area ratio ``q`` (new scale / old scale, squared):
  ``r'^2 = a / pi + q r^2`` for ``r < R``, where ``R^2 = a / (pi (1 - q))`` so that the disc's
  rim stays where it is (the marks beyond it do not move);
* a removed mark's site is where it was, with a negative cell: the same map closes its hole
  and widens the disc around it as the marks grow.

The maps are applied one site after the other (each moves the marks the earlier ones moved).
The marks land near where a full run would put them; the reflow's window then clears what
overlap is left (``layout.reflow``).
"""
from __future__ import annotations

import math

import numpy as np

from ...design.encodings import footprint
from .lattice import Region, container_region
from .pack import STEP, Packing, thin
from .relax import relax
from .start import footprint_radius

RELAX = 300        # L-BFGS iterations of the discs after the maps at most (``relax``)
TOLERANCE = 0.003   # the deepest push left on a disc, in median radii (``relax``)


def radial_map(center: np.ndarray, site: np.ndarray, cell: float, q: float) -> np.ndarray:
    """``center (K, 2)`` moved by the hole of signed area ``cell`` px^2 opened (closed, when
    negative) at ``site (2,)``, the disc around it compressed (widened) by the area ratio
    ``q`` (module docstring)."""
    if abs(1.0 - q) < 1e-9 or cell == 0.0:
        return center
    reach2 = cell / math.pi / (1.0 - q)
    gap = center - site
    r2 = (gap ** 2).sum(1)
    near = r2 < reach2
    r2_new = np.maximum(cell / math.pi + q * r2[near], 0.0)
    out = center.copy()
    r = np.sqrt(r2[near])
    way = np.where(r[:, None] > 1e-9, gap[near] / np.maximum(r[:, None], 1e-9), [1.0, 0.0])
    out[near] = site + way * np.sqrt(r2_new)[:, None]
    return out


def sites(region: Region, center: np.ndarray, radius: np.ndarray, taken: np.ndarray,
          reach: np.ndarray) -> np.ndarray:
    """``(k, 2)`` a site for each of ``k`` added marks: the spot of ``region`` farthest from
    its edge and from the ``taken (N,)`` discs (``center (N, 2)``, ``radius (N,)``), and from
    the sites before it by their ``reach (k,)`` (the disc its map moves), among the spots a
    ``reach`` deep in the container where there are such."""
    packing = Packing(region, STEP * float(np.median(radius[taken])), float(radius[taken].max()))
    packing.stamp(center[taken], radius[taken])
    out = np.zeros((len(reach), 2))
    for i, r in enumerate(reach):
        deep = packing.depth >= r
        score = np.where(deep, packing.clear, -np.inf) if deep.any() else packing.clear
        out[i] = packing.points[int(np.argmax(score))]
        packing.stamp(out[i:i + 1], np.array([r]))
    return out


def regrown(p, units, layers, previous, found: np.ndarray) -> dict:
    """``{group: (scale, q)}`` for each controlled scale group of ``p`` whose rows changed
    since the snapshot ``previous`` (``found (N,)`` each unit's row there, -1 for an added
    one) while its kept marks' sizes did not, and each of whose containers keeps some of
    its marks: its scale at the footprint area ratio, and ``q``, the kept marks' area ratio
    (new scale / old, squared)."""
    names = [layer.name for layer in layers]
    group = p.layer_groups()
    old_group = np.array([group[names.index(n)] if n in names else -1 for n in previous["layer"]])
    old_area = previous["area"].to_numpy(dtype=float)
    foot = units.area * footprint(units.margin) ** 2
    kept = found >= 0
    matched = np.zeros(len(previous), bool)
    matched[found[kept]] = True
    keys = np.array([repr(layer.region.to_json()) for layer in layers], dtype=object)
    out = {}
    for g in np.nonzero(p.group_controlled())[0]:
        mine = group[units.layer] == g
        if not ((mine & ~kept).any() or ((old_group == g) & ~matched).any()):
            continue
        if any(not (mine & kept & (keys[units.layer] == key)).any()
               for key in set(keys[units.layer[mine]])):
            continue   # a container of the group keeps none of its marks: nothing to map
        ratio = old_area[found[mine & kept]] / foot[mine & kept]   # each kept unit's old scale^2
        if np.ptp(ratio) > 1e-6 * ratio.max():
            continue   # sizes or margins changed too: no one ratio to map by
        scale = math.sqrt(old_area[old_group == g].sum() / foot[mine].sum())
        out[int(g)] = (scale, scale ** 2 / float(ratio[0]))
    return out


def make_room(p, units, layers, canvas, previous, found: np.ndarray, pinned: np.ndarray,
              groups: dict):
    """Centres ``(N, 2)`` and scales ``(G,)`` for ``p`` (warm-started from the snapshot
    ``previous``; ``found (N,)`` each unit's row there, -1 for an added one; ``pinned (P,)``
    the pinned units), the marks of ``groups`` (``regrown``'s) moved by the maps of the
    module docstring and their discs relaxed."""
    names = [layer.name for layer in layers]
    group, scales = p.layer_groups(), p.group_scales().copy()
    for g, (scale, _) in groups.items():
        scales[g] = scale
    keys = [repr(layer.region.to_json()) for layer in layers]
    unit_key = np.array(keys, dtype=object)[units.layer]
    old_key = np.array([keys[names.index(n)] if n in names else None for n in previous["layer"]],
                       dtype=object)
    old_area, old_xy = previous["area"].to_numpy(dtype=float), previous[["x", "y"]].to_numpy(dtype=float)
    foot = units.area * footprint(units.margin) ** 2
    kept = found >= 0
    matched = np.zeros(len(previous), bool)
    matched[found[kept]] = True
    movable = p.placement.movable.cpu().numpy().astype(bool)
    movable[pinned] = False
    center = p.placement.t.detach().cpu().numpy().astype(np.float64)
    radius = footprint_radius(units) * scales[group[units.layer]]
    for g, (scale, q) in groups.items():
        mine = group[units.layer] == g
        was = np.array([n in names and group[names.index(n)] == g for n in previous["layer"]])
        for key in dict.fromkeys(unit_key[mine]):
            here, old_here = unit_key == key, (old_key == key) & was
            region = container_region(layers[units.layer[np.argmax(here & mine)]].region, canvas,
                                      p.grid.rho)
            density = old_area[old_here].sum() / region.area   # the marks' cover of it
            moving = here & mine & kept & movable
            for k in np.nonzero(old_here & ~matched)[0]:   # holes closed
                center[moving] = radial_map(center[moving], old_xy[k], -old_area[k] / density, q)
            new = np.nonzero(here & mine & ~kept & movable)[0]
            if len(new):   # holes opened
                cells = foot[new] * scale ** 2 / density
                reach = np.sqrt(cells / math.pi / max(1.0 - q, 1e-9) if q < 1 else cells / math.pi)
                taken = here.copy()
                taken[new] = False
                for k, site, cell in zip(new, sites(region, center, radius, taken, reach), cells):
                    center[moving] = radial_map(center[moving], site, cell, q)
                    center[k] = site
                    moving[k] = True
            if not thin(units.half_w[here], units.half_h[here]).any():   # discs stand for them
                center = relax(center, radius, np.nonzero(moving)[0], region, RELAX, TOLERANCE)
    return center, scales
