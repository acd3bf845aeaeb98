"""The starting global scales: one per scale group, fixed by an open layer's ``fill`` or
controlled (grown by the solver) for a closed container, capped by the widest disc each
container holds."""
from __future__ import annotations

import math

import numpy as np
import torch

from ...design.encodings import footprint
from ...design.sharing import by_container
from ...design.units import Units
from .lattice import container_region, start_rho
from .pack import STEP, Packing, packable, thin
from .start import emission_ranks, footprint_radius, later_radius, pack_layer, spot_cost

DEFAULT_OPEN_FILL = 0.5
MAX_COVER = 0.9           # the most of a container marks can cover (discs pack to about 0.907)
CROWDED = 0.6      # footprint discs over container area past which an open fill is checked
# how much more footprint area a pile settles into than the start's greedy disc packing
# holds: open piles at the default steps settled without legalising up to 1.14x (circles),
# 1.18x (six-armed flakes) and 1.48x (stars) of it, and failed at 1.29x and 1.35x
PACK_SLACK = 1.15


def initial_scale(units: Units, layers, canvas, scales: str = "shared", caps=None):
    """The starting global scales and which of them are controlled during the layout.

    Open layers (and closed ones with a ``fill``) fix the scale so their marks
    cover ``fill`` of the container (lowered later where their footprints cannot pack:
    ``start.packed_scales``); closed layers without one start with
    their footprints (margins included) at 75% coverage and let the solver grow
    the scale until the container is full. No scale lets a layer's largest
    mark outgrow the widest disc its container holds. ``scales="shared"``: one
    scale for all layers (sizes comparable across layers; the smallest fixed
    one wins); ``"independent"``: one per layer. ``caps``: ``(L,)`` each layer's
    ``scale_cap``, when already known. Returns ``(group_scale (G,), group_free (G,)
    bool, scale_group (L,))``.
    """
    if caps is None:
        caps = [scale_cap(units, layers, canvas, i) for i in range(len(layers))]
    cap = dict(enumerate(caps))
    fixed, free = {}, {}
    foot = units.area * footprint(units.margin) ** 2
    for i, layer in enumerate(layers):
        area = layer.region.area(canvas)
        if area <= 0:
            raise ValueError(f"layer {layer.name!r}: its container does not overlap the canvas")
        shared = [j for j, other in enumerate(layers) if other.region == layer.region
                  and (scales == "shared" or j == i)]
        mine = units.layer == i
        if layer.boundary == "open" or layer.fill is not None:
            fill = layer.fill or DEFAULT_OPEN_FILL
            fixed[i] = math.sqrt(fill * area / units.area[np.isin(units.layer, shared)].sum())
        else:
            # start loose: compact marks at 75% coverage, spiky ones (stars) lower
            start = min(max(0.75 * units.fill_fraction[mine].mean() / 0.785, 0.35), 0.75)
            free[i] = math.sqrt(start * area / foot[np.isin(units.layer, shared)].sum())
        emitter = layer.emitter
        if getattr(emitter, "mode", None) == "line":
            # a line holds its marks end to end: at most the curve's length of diameters
            diameters = 2 * np.sqrt(units.area[mine] / math.pi) * footprint(units.margin[mine])
            (fixed if i in fixed else free)[i] = min((fixed if i in fixed else free)[i],
                                                     0.95 * emitter.curve.length / diameters.sum())
    if scales == "independent":
        group = np.arange(len(layers))
        scale = np.array([min(fixed.get(i, free.get(i)), cap[i]) for i in range(len(layers))])
        return scale, np.array([i not in fixed for i in range(len(layers))]), group
    start = min(fixed.values()) if fixed else min(free.values())
    return np.array([min(start, *cap.values())]), np.array([not fixed]), np.zeros(len(layers), int)


def overfilled(layers, scales: str) -> list:
    """Under ``scales="independent"`` an open layer (or one with a ``fill``) sets its own scale
    so that its marks alone cover its fill of its container: ``[(names, total fill), ...]``
    for the containers whose layers' fills add up past ``MAX_COVER``, where the layers packed
    last can only shrink to fit. With one shared scale the layers in a container share its
    fill, and nothing is listed."""
    if scales != "independent":
        return []
    out = []
    for members in by_container(layers, lambda a: a.boundary == "open" or a.fill is not None):
        group = [layers[i] for i in members]
        total = sum(layer.fill or DEFAULT_OPEN_FILL for layer in group)
        if len(group) > 1 and total > MAX_COVER:
            out.append(([layer.name for layer in group], total))
    return out


def scale_cap(units: Units, layers, canvas, i: int) -> float:
    """The largest scale at which layer ``i``'s longest mark fits its container's widest disc."""
    mine = units.layer == i
    longest = float(np.max(np.maximum(units.half_w[mine], units.half_h[mine])))
    return 0.95 * widest_disc(layers[i].region, canvas) / longest


def widest_disc(container, canvas) -> float:
    """Radius (canvas px) of the widest disc inside ``container`` on the canvas."""
    return float(container_region(container, canvas, start_rho(canvas)).depth.max())


def packed_scales(units, layers, order, canvas, group_scale, group_free, scale_group, caps, seed):
    """``(G,)`` starting scales. A controlled group with layers packed by size starts at the
    largest scale (up to ``caps (L,)``, the widest disc) at which those layers still pack
    into their containers as the start packs them (``start.pack_layer``, its random spots
    drawn from ``seed``; bisection on the log scale). A fixed group
    (open layers at their ``fill``) whose footprints crowd their containers past ``CROWDED``
    is lowered to ``PACK_SLACK`` times the largest scale at which they pack: spiky marks need
    more room than their ink (snowflakes, stars; margins too), and a fill their footprints
    cannot reach would start the pile overflowing the container (the layers resting on it
    outside it), never to settle."""
    out = np.array(group_scale, dtype=float)
    rho = start_rho(canvas)
    radius, regions = footprint_radius(units), {}
    for g in range(len(out)):
        members = [i for i in order if scale_group[i] == g and layers[i].emitter is None]
        if group_free[g]:
            if not any(packable(radius[m], units.half_w[m], units.half_h[m])
                       for m in (units.layer == i for i in members)):
                continue
        elif not members or any(thin(units.half_w[m], units.half_h[m]).any()
                                for m in (units.layer == i for i in members)):
            continue   # thin marks' discs overstate the room they need
        for i in members:
            key = repr(layers[i].region.to_json())
            if key not in regions:
                regions[key] = container_region(layers[i].region, canvas, rho)

        def fits(scale: float) -> bool:
            packings = {}
            for i in members:
                key, r = repr(layers[i].region.to_json()), radius[units.layer == i] * scale
                if key not in packings:
                    mine = np.isin(units.layer, members)
                    packings[key] = Packing(regions[key], STEP * float(np.median(radius[mine])) * scale,
                                            float(radius[mine].max()) * scale)
                pack = packings[key]
                ranks = emission_ranks(units.order[units.layer == i])
                cost = spot_cost(layers[i], layers[i].region, canvas, pack.points)
                later = later_radius(units, layers, members, i, radius) * scale
                draw = torch.Generator().manual_seed(int(seed))
                if not pack_layer(pack, layers[i], r, cost, ranks, later, draw, until_miss=True)[1]:
                    return False
            return True

        if not group_free[g]:
            # the solver packs shapes tighter than the start's discs (PACK_SLACK)
            probe = out[g] / math.sqrt(PACK_SLACK)
            if _crowding(units, layers, members, radius * probe, regions) > CROWDED \
                    and not fits(probe):
                hi = math.log(probe)
                lo = hi - math.log(2.0)
                for _ in range(4):
                    if fits(math.exp(lo)):
                        break
                    hi, lo = lo, lo - math.log(2.0)
                lo = _bisect(fits, lo, hi)
                out[g] = math.exp(lo) * math.sqrt(PACK_SLACK)
            continue
        top = math.log(min(caps[i] for i in members))
        lo, hi = math.log(out[g]), top
        if lo >= hi or not fits(out[g]):
            lo, hi = lo - math.log(2.0), min(lo, top)
        if fits(math.exp(hi)):
            lo = hi
        out[g] = math.exp(_bisect(fits, lo, hi) if lo < hi else lo)
    return out


def _bisect(fits, lo: float, hi: float) -> float:
    """The log scale in ``[lo, hi]`` (``fits(exp(lo))`` true) where ``fits`` turns false,
    to six halvings: the largest scale found that fits."""
    for _ in range(6):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if fits(math.exp(mid)) else (lo, mid)
    return lo


def _crowding(units, layers, members, radius, regions) -> float:
    """The largest share of one container's area that the footprint discs ``radius (N,)``
    (canvas px) of the layers ``members`` sharing it would cover."""
    covered = {}
    for i in members:
        key = repr(layers[i].region.to_json())
        covered[key] = covered.get(key, 0.0) + float((math.pi * radius[units.layer == i] ** 2).sum())
    return max(area / max(regions[key].area, 1e-9) for key, area in covered.items())
