"""Starting positions and orientation targets, layer by layer, from the emitters.

Layers are placed in block order, so a blocked layer starts where its
blocking layers left room; a layer resting on others (``strata.py``) starts
beyond their shadow, packed or on a grid, and sees an emitted layer where it
will rest (a packed stand-in), not where it is emitted. Without an emitter,
marks start packed on a hexagonal lattice at the spots the layer's forces
pull hardest (or nearest the container's centre), the way they would settle; spread
sizes at random spots of that room, unless ``order=`` asks for its order there
(``pack_layer``). Units take their turns in the start order (``order.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import torch
from scipy.spatial import cKDTree

from .curves import CurveTrack
from ...design.emitters import CurveEmitter, GridEmitter
from ...design.encodings import footprint
from ...design.forces import potential
from ...design.scene import random_range
from ..step.placement import DRIFT_DECAY
from ..step.strata import Radial, shadow, shadow_distance, sweep_of
from .lattice import Region, container_region, fitting_lattice, grid_spacing
from .pack import SPARSE, STEP, Packing, packable, rows, thin
from .scatter import pressed, scattered

DRIFT_SPEED = 0.5   # drift at speed 1, in mean footprint radii per iteration
DRIFT_TRAVEL = DRIFT_SPEED / (1 - DRIFT_DECAY)   # the whole decaying drift, in mean radii


@dataclass
class Start:
    """Starting transforms ``(N, ...)`` and the curve tracks to build."""

    center: np.ndarray
    angle: np.ndarray
    movable: np.ndarray
    turnable: np.ndarray
    drift: np.ndarray
    track_specs: list = field(default_factory=list)

    def tracks(self, device) -> list[CurveTrack]:
        return [CurveTrack(*spec, device=device) for spec in self.track_specs]


def start_positions(units, layers, order, canvas, scale, grid, generator) -> Start:
    """Place every unit; ``order`` is the block order of the layers."""
    n = len(units.layer)
    s = Start(center=np.zeros((n, 2)), angle=np.zeros(n), movable=np.ones(n, bool),
              turnable=np.zeros(n, bool), drift=np.zeros((n, 2)))
    radius = footprint_radius(units) * scale
    regions, taken, packings = {}, {}, {}
    rest = np.zeros((n, 2))      # where placed marks will rest
    placed, keys = [], {}        # the layers placed, their containers
    for i in order:
        layer = layers[i]
        idx = np.nonzero(units.layer == i)[0]
        ranks = emission_ranks(units.order[idx])
        container = layer.region
        key = repr(container.to_json())
        if key not in regions:
            try:
                regions[key] = container_region(container, canvas, grid.rho)
            except ValueError as exc:
                raise ValueError(f"layer {layer.name!r}: {exc}") from None
            taken[key] = (np.zeros((0, 2)), np.zeros(0))
        region, r = regions[key], radius[idx]
        emitter = layer.emitter
        # (N,) the marks of the layers it rests on (strata.py), placed before it
        under = np.isin(units.layer, [j for j in order[:order.index(i)] if resting(layers, i, j)])
        sweep = sweep_of(layer.forces, float(radius[under].max()) if under.any() else 0.0)
        under &= sweep is not None
        if isinstance(emitter, CurveEmitter) and emitter.mode == "free":
            s.center[idx], s.drift[idx] = emitted(emitter, region, r, ranks, taken[key])
        elif isinstance(emitter, CurveEmitter):
            arc = emitter.arc_positions(2 * r, ranks)
            s.center[idx] = emitter.curve.at(arc)
            s.drift[idx] = emitter.drift(arc)
            s.track_specs.append((idx, emitter.curve, emitter.mode, arc, ranks, emitter.speed > 0))
        elif isinstance(emitter, GridEmitter):
            # strata: the grid fills the room beyond the shadow of the layers it rests on
            room = _beyond(region, sweep, rest[under], radius[under]) if under.any() else region
            spacing = grid_spacing(room, len(idx)) * 0.98
            lattice = fitting_lattice(room, len(idx), spacing, min(float(r.mean()), spacing / 2))
            s.center[idx] = emitter.place(lattice, ranks)
            s.drift[idx] = emitter.drift(s.center[idx]) * _room_ahead(
                room, s.center[idx], emitter.drift(s.center[idx]), r)[:, None]
        else:
            try:
                if under.any() and key not in packings:
                    # on other layers (emitted, or started on a lattice): packed beyond
                    # where they will rest, out of the shadow they cast
                    packings[key] = Packing(region, STEP * float(np.median(r)), float(radius.max()))
                    packings[key].stamp(*taken[key])
                if key in packings and under.any():
                    # strata: the layers it rests on take the room they shadow
                    packings[key].lower(shadow_distance(packings[key].points, sweep,
                                                        rest[under], radius[under]))
                s.center[idx] = _still(layer, units, idx, region, r, ranks, scale, taken[key],
                                       packings, key, float(radius.max()), canvas,
                                       later_radius(units, layers, order, i, radius), generator)
            except ValueError as exc:
                raise ValueError(f"layer {layer.name!r}: {exc}") from None
        if key in packings and emitter is not None:   # emitted marks take room from packed ones
            packings[key].stamp(s.center[idx], r)
        rest[idx] = s.center[idx]
        if emitter is not None and layer.forces and any(resting(layers, j, i) for j in order):
            # the layers resting on it see it where it will rest, not where it is emitted
            near = np.isin(units.layer, [j for j in placed if keys[j] == key])
            rest[idx] = _stand_in(layer, region, r, ranks, canvas, (rest[near], radius[near]),
                                  sweep, rest[under], radius[under])
        keys[i] = key
        placed.append(i)
        taken[key] = (np.concatenate([taken[key][0], s.center[idx]]), np.concatenate([taken[key][1], r]))
        speed = 1.0 if emitter is None else emitter.speed
        s.movable[idx] = speed > 0
        s.drift[idx] *= speed * DRIFT_SPEED * float(r.mean())
        s.angle[idx], s.turnable[idx] = layer_angle(layer)
        span = random_range(layer.orientation)
        if span is not None:   # each mark turned by its own angle, drawn from the seed
            draw = torch.rand(len(idx), generator=generator, dtype=torch.float64).numpy()
            s.angle[idx] = np.radians(span[0] + (span[1] - span[0]) * draw)
        if _lengthwise(layer, units, idx):
            # thin marks start along the container's long axis, side by side: upright, the
            # longest spans a wide container's height and keeps the scale from growing
            s.angle[idx] = np.where(units.half_h[idx] > units.half_w[idx],
                                    region.axis() - math.pi / 2, region.axis())
    jitter = torch.rand((n, 2), generator=generator).numpy() - 0.5
    s.center += jitter * 1e-3 * radius[:, None] * s.movable[:, None]
    return s


def later_radius(units, layers, order, i, radius) -> float:
    """The largest footprint radius (``radius (N,)``) of the layers after ``i`` in ``order``
    that share its container: how far a packing's clearances must stay exact for them."""
    key = repr(layers[i].region.to_json())
    after = [j for j in order[order.index(i) + 1:] if repr(layers[j].region.to_json()) == key]
    return float(radius[np.isin(units.layer, after)].max()) if after else 0.0


def _still(layer, units, idx, region, r, ranks, scale, taken, packings, key, reach, canvas, later,
           generator):
    """Starting centres ``(n, 2)`` of a layer without an emitter: thin turnable marks in rows
    along the container, spread sizes packed disc by disc (one packing per container, shared by
    the layers in it), else lattice spots ranked by the forces. Spread sizes start
    ``scattered`` over the room they take, unless ``order=`` is bound: then they are packed
    in its order, the first at the spots the forces pull hardest (or the container's
    centre). ``later``: see ``later_radius``."""
    container = layer.region
    if _lengthwise(layer, units, idx) and key not in packings:
        hw, hh = units.half_w[idx] * scale[idx], units.half_h[idx] * scale[idx]
        band = footprint(units.margin[idx])
        return rows(region, 2 * np.maximum(hw, hh) * band, 2 * np.minimum(hw, hh) * band,
                    region.axis(), ranks)
    if packable(r, units.half_w[idx], units.half_h[idx]) or key in packings:
        if key not in packings:
            packings[key] = Packing(region, STEP * float(np.median(r)), reach)
            packings[key].stamp(*taken)
        pack = packings[key]
        cost = spot_cost(layer, container, canvas, pack.points)
        # too few to fill it (a shared scale held by a fuller container): spread over it
        sparse = closed_fill(layer) and float((math.pi * r ** 2).sum()) < SPARSE * region.area
        center = pack_layer(pack, layer, r, cost, ranks, later, generator, sparse)[0]
        if layer.forces and not closed_fill(layer) and layer.encodings["order"] is None \
                and not later and not len(taken[0]):   # a scattered pile alone in its container
            return pressed(center, r, region, layer.forces)
        return center
    return _settled(region, r, ranks, layer, taken[0], container, canvas)


def closed_fill(layer) -> bool:
    """Whether a layer fills its container (closed, no ``fill=`` share)."""
    return layer.boundary == "closed" and layer.fill is None


def pack_layer(pack, layer, r, cost, ranks, later, generator, sparse=False, until_miss=False):
    """``Packing.place`` for a layer's discs ``r (n,)`` (``cost (M,)`` per spot of ``pack``,
    ``ranks (n,)`` the start order): with ``order=`` bound, in its order from the cheapest
    spot out (order reads from the pile); ``sparse``: each at the roomiest spot; else
    ``scattered`` over the room they take. The scale search (``scale.packed_scales``) packs
    the same way."""
    if sparse:
        return pack.place(r, cost, ranks, largest_first=False, roomiest=True, later=later,
                          until_miss=until_miss)
    if layer.encodings["order"] is not None:
        return pack.place(r, cost, ranks, largest_first=False, later=later, until_miss=until_miss)
    return pack.place(r, scattered(pack, r, cost, ranks, closed_fill(layer), later, generator),
                      ranks, later=later, until_miss=until_miss)


def emitted(emitter, region: Region, r: np.ndarray, ranks: np.ndarray, taken):
    """Starting centres and drift directions ``(n, 2)`` of marks ``r (n,)`` (footprint discs,
    px) a free curve emitter places: end to end along the curve in ``ranks`` order
    (``arc_positions``), drifting as the emitter says. Where the curve is shorter than they
    are, each moves instead, in ``ranks`` order, to the free spot of ``region`` (the
    container) nearest its place on the curve, around the discs ``taken`` (centres, radii)
    already there, and starts at rest: it has left the curve. (Squeezed onto a short curve,
    alike marks started nearly on top of each other and stayed nested in stacks; drifting
    beside it as one block, a pile slid to one wall.)"""
    curve = emitter.curve
    arc = emitter.arc_positions(2 * r, ranks)
    if float(2 * r.sum()) <= curve.length:
        return curve.at(arc), emitter.drift(arc)
    pack = Packing(region, STEP * float(np.median(r)), float(r.max()))
    pack.stamp(*taken)
    return pack.place_near(r, curve.at(arc), ranks), np.zeros((len(r), 2))


def resting(layers, a: int, b: int) -> bool:
    """Whether layer ``a`` blocks on layer ``b``, directly or through a chain of blocks."""
    names = [layer.name for layer in layers]
    seen, todo = set(), list(layers[a].blocks)
    while todo:
        name = todo.pop()
        if name not in seen:
            seen.add(name)
            todo.extend(layers[names.index(name)].blocks)
    return layers[b].name in seen


def _beyond(region: Region, sweep, centers: np.ndarray, radii: np.ndarray) -> Region:
    """The part of ``region`` outside the shadow of the discs ``centers (k, 2)``, ``radii (k,)``
    along ``sweep``, on its raster as the loss sees it (``strata.shadow``, ``Radial.on``);
    all of it when the shadow leaves none."""
    h, w = region.depth.shape
    ink = np.zeros((h, w), np.float32)
    for (x, y), r in zip(centers * region.rho, radii * region.rho):   # raster px
        i0, i1 = max(int(y - r), 0), min(int(y + r) + 2, h)
        j0, j1 = max(int(x - r), 0), min(int(x + r) + 2, w)
        ii, jj = np.ogrid[i0:i1, j0:j1]
        ink[i0:i1, j0:j1] = np.maximum(ink[i0:i1, j0:j1], (ii + 0.5 - y) ** 2 + (jj + 0.5 - x) ** 2 <= r * r)
    ink = torch.from_numpy(ink)
    swept = sweep.on((h, w), region.rho, 0, "cpu")(ink) if isinstance(sweep, Radial) \
        else shadow(ink, *sweep)
    free = (region.depth > 0) & (swept.numpy() < 0.5)
    return Region(free.astype(np.float32), region.rho) if free.any() else region


def _stand_in(layer, region: Region, r, ranks, canvas, taken, sweep, centers, radii) -> np.ndarray:
    """``(n, 2)`` where an emitted layer's marks ``r (n,)`` will rest: packed in start order at
    the spots its forces pull hardest, around the marks ``taken`` (centres, radii) and beyond
    the shadow of the discs ``centers (k, 2)``, ``radii (k,)`` it rests on (along ``sweep``)."""
    pack = Packing(region, STEP * float(np.median(r)), float(r.max()))
    pack.stamp(*taken)
    if len(centers):
        pack.lower(shadow_distance(pack.points, sweep, centers, radii))
    cost = spot_cost(layer, layer.region, canvas, pack.points)
    return pack.place(r, cost, ranks, largest_first=False)[0]


def _lengthwise(layer, units, idx) -> bool:
    """Whether a layer's marks start laid along its container: turnable, no orientation
    asked for, no emitter, and every box thin (long side over ``ASPECT`` short sides)."""
    return bool(layer.rotate and layer.orientation is None and layer.emitter is None
                and thin(units.half_w[idx], units.half_h[idx]).all())


def _room_ahead(region: Region, center: np.ndarray, direction: np.ndarray, r: np.ndarray):
    """``(n,)`` in [0, 1]: the share of a full drift (``DRIFT_TRAVEL`` radii) each mark can
    travel along ``direction (n, 2)`` before its footprint ``r (n,)`` reaches the edge."""
    travel = DRIFT_TRAVEL * float(r.mean())
    steps = np.linspace(0.0, travel, 21)[1:]
    free = np.ones(len(center), dtype=bool)
    room = np.zeros(len(center))
    for d in steps:
        free &= region.depth_at(center + direction * d) >= r
        room = np.where(free, d, room)
    return room / travel


def _settled(region: Region, r: np.ndarray, ranks, layer, taken, container, canvas) -> np.ndarray:
    """Lattice spots ranked by the layer's forces (or closeness to the centre)."""
    count = len(r)
    spacing = 2 * float(np.sqrt((r ** 2).mean())) * 1.02
    if layer.boundary == "closed" and layer.fill is None:
        # spread over the whole container: the scale then grows with no mark to rearrange
        spacing = grid_spacing(region, count + len(taken))
    lattice = fitting_lattice(region, count + len(taken), spacing, min(float(r.mean()), spacing / 2))
    if len(taken):
        near = cKDTree(taken).query(lattice, k=1)[0]
        free = lattice[near > 0.9 * spacing]
        lattice = free if len(free) >= count else lattice[np.argsort(-near)[:max(count, 1)]]
    cost = spot_cost(layer, container, canvas, lattice)
    best = lattice[np.argsort(cost, kind="stable")[:count]]
    if len(best) < count:
        raise ValueError(f"layer {layer.name!r}: its container is too small for {count} marks")
    return best[ranks]


def spot_cost(layer, container, canvas, points: np.ndarray) -> np.ndarray:
    """``(k,)`` how little a layer's marks want to start at ``points (k, 2)``: the
    potential of its forces, or the distance to its container's centre."""
    if layer.forces:
        return potential(layer.forces, torch.tensor(points, dtype=torch.float64)).numpy()
    cx, cy = container.centroid(canvas)
    return np.hypot(points[:, 0] - cx, points[:, 1] - cy)


def emission_ranks(order: np.ndarray) -> np.ndarray:
    """``(n,)`` 0..n-1: each unit's place among its layer's units by emission rank ``order (n,)``."""
    return np.argsort(np.argsort(order, kind="stable"), kind="stable")


def footprint_radius(units) -> np.ndarray:
    """``(N,)`` at scale 1: the disc that holds a mark's footprint when packed,
    area-equivalent and widened for shapes less compact than a disc (a star needs more
    room than its area), margins included."""
    compact = np.minimum(units.fill_fraction / (math.pi / 4), 1.0)
    return np.sqrt(units.area / math.pi / compact) * footprint(units.margin)


def layer_angle(layer):
    """(starting angle in radians, turnable) for the units of ``layer``."""
    o = layer.orientation
    if isinstance(o, (int, float)) and o is not None:
        return math.radians(o), layer.rotate
    return 0.0, bool(layer.rotate or o in ("to_center", "along_emitter"))


def orientation_targets(units, layers, canvas, device):
    """A callable ``(center, tangent) -> (target (N, 2), mask (N,))``, or None when no layer
    asks for "to_center" or "along_emitter". Units on a curve track bring their tangent;
    others take the tangent of the nearest point of their layer's curve."""
    wanted = [i for i, layer in enumerate(layers) if layer.orientation in ("to_center", "along_emitter")]
    if not wanted:
        return None
    dev = torch.device(device)
    layer_t = torch.as_tensor(units.layer, device=dev)
    centers = torch.zeros((len(layers), 2), device=dev)
    for i in wanted:
        layer = layers[i]
        if layer.orientation == "along_emitter" and not isinstance(layer.emitter, CurveEmitter):
            raise ValueError(f"layer {layer.name!r}: orientation='along_emitter' needs a "
                             f"uw.CurveEmitter; this layer has {layer.emitter!r}")
        centers[i] = torch.tensor(layer.region.centroid(canvas), dtype=torch.float32)
    to_center = torch.tensor([layers[i].orientation == "to_center" for i in range(len(layers))],
                             device=dev)[layer_t]
    along = torch.tensor([layers[i].orientation == "along_emitter" for i in range(len(layers))],
                         device=dev)[layer_t]
    mask = (to_center | along).to(torch.float32)
    any_along = any(layers[i].orientation == "along_emitter" for i in wanted)   # read once, on the host

    def targets(center: torch.Tensor, tangent: torch.Tensor):
        target = centers[layer_t] - center
        if any_along:
            tan = tangent.clone()
            missing = along & (tangent.norm(dim=1) < 0.5)
            for i in wanted:
                sel = missing & (layer_t == i)
                if bool(sel.any()):
                    curve = layers[i].emitter.curve
                    arc = curve.nearest_arc(center[sel].cpu().numpy())
                    tan[sel] = torch.tensor(curve.frame(arc)[0], dtype=center.dtype, device=dev)
            up = torch.stack([tan[:, 1], -tan[:, 0]], dim=1)   # the tangent turned -90 degrees
            target = torch.where(along[:, None], up, target)
        return target, mask

    return targets


def any_angle(layers) -> bool:
    """Whether some layer's marks turn or stand at an angle (then every patch holds any rotation)."""
    return any(turn or abs(angle) > 1e-6 or random_range(layer.orientation) is not None
               for layer, (angle, turn) in zip(layers, map(layer_angle, layers)))
