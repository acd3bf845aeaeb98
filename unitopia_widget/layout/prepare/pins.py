"""Pinned units in the solver's problem: held in place, obstacles for their container.

Every container that holds pins gets an *obstacle slab*: an extra raster layer drawn by
its pinned units alone, with no fill target and no forces. Each layer in that container
blocks on the slab (one-way: its ink is an obstacle with gradients stopped), whatever
the blocks between the layers say, so the pinned ink keeps every layer out. A pinned
unit neither moves nor turns; it scales with its layer's scale group (``design.pins``).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import torch

from ...design.emitters import CurveEmitter
from .lattice import container_region
from .start import footprint_radius
from .warm import free_room, replace_start


def pinned_units(units, layers, pins) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The units ``pins`` hold: indices ``(P,)``, centres ``(P, 2)`` canvas px and angles
    ``(P,)`` radians. Pins whose row no layer draws any more are skipped; a pin on a
    mark that follows an emitter curve is a ValueError (its track places it)."""
    names = [layer.name for layer in layers]
    where = {(names[li], row): k for k, (li, row) in enumerate(zip(units.layer, units.rows))}
    idx, xy, angle = [], [], []
    for pin in pins:
        k = where.get(pin.key)
        if k is None:
            continue
        emitter = layers[units.layer[k]].emitter
        if isinstance(emitter, CurveEmitter) and emitter.mode != "free":
            raise ValueError(f"pin of row {pin.row!r:.40}: layer {pin.layer!r:.60} strings its "
                             f"marks along its emitter curve (mode={emitter.mode!r}), which places "
                             f"them; pins need mode='free' or no emitter")
        idx.append(k)
        xy.append((pin.x, pin.y))
        angle.append(math.radians(pin.angle))
    return (np.array(idx, dtype=int), np.array(xy, dtype=float).reshape(-1, 2),
            np.array(angle, dtype=float))


def pin_problem(problem, units, layers, canvas, idx: np.ndarray, xy: np.ndarray,
                angle: np.ndarray, vacate: bool = True):
    """``problem`` with units ``idx (P,)`` held at ``xy (P, 2)``, ``angle (P,)`` radians, and
    drawn into one obstacle slab per (container, scale group) that every layer in the
    container blocks on. A free unit that starts with its centre on a pinned mark (or a
    pinned centre on it), where the overlap would push it nowhere, starts in the nearest
    free room instead (``warm.free_room``), unless ``vacate`` is False (a reflow moves it
    aside itself)."""
    if len(idx) == 0:
        return problem
    p, terms = problem, problem.terms
    n_layers = terms.penalty.shape[0]
    group = p.layer_groups()
    keys = [repr(layer.region.to_json()) for layer in layers]
    layer = np.array(p.layer, copy=True)
    slabs = {}   # (container key, scale group) -> (slab index, a layer of that container)
    for k in idx:
        own = int(p.layer[k])
        slot = (keys[own], int(group[own]))
        if slot not in slabs:
            slabs[slot] = (n_layers + len(slabs), own)
        layer[k] = slabs[slot][0]
    total = n_layers + len(slabs)
    source = [own for _, own in slabs.values()]
    blocks = torch.zeros((total, total), dtype=terms.blocks.dtype, device=terms.blocks.device)
    blocks[:n_layers, :n_layers] = terms.blocks
    for (key, _), (slab, _) in slabs.items():
        for a in range(n_layers):
            if keys[a] == key:
                blocks[a, slab] = 1.0
    rests = None
    if terms.rests is not None:
        rests = torch.zeros_like(blocks)
        rests[:n_layers, :n_layers] = terms.rests
    new_terms = dataclasses.replace(
        terms, penalty=torch.cat([terms.penalty, terms.penalty[source]]),
        outside=torch.cat([terms.outside, terms.outside[source]]),
        inside=torch.cat([terms.inside, torch.zeros_like(terms.inside[source])]),
        blocks=blocks, rests=rests, sweeps=tuple(terms.sweeps) + (None,) * len(slabs),
        sums=None, _cover=None, _tables=None, _rows=None, _onehot=None, _obstacle=None)
    center = p.placement.t.detach().cpu().numpy().astype(float)
    theta = p.placement.theta.detach().cpu().numpy().astype(float)
    movable = p.placement.movable.cpu().numpy().copy()
    turnable = p.placement.turnable.copy()
    drift = np.zeros_like(center) if p.placement.drift is None else p.placement.drift.cpu().numpy()
    center[idx], theta[idx], movable[idx], turnable[idx], drift[idx] = xy, angle, False, False, 0.0
    if vacate:
        _vacate(p, units, layers, canvas, keys, center, idx)
    stage = None if p.stage is None else np.where(np.isin(np.arange(len(layer)), idx), 0, p.stage)
    return dataclasses.replace(
        p, layer=layer, terms=new_terms, forces=list(p.forces) + [[] for _ in slabs],
        scale_group=np.concatenate([group, group[source]]),
        placement=replace_start(p.placement, center, theta, movable, turnable, drift),
        stage=stage)


def _vacate(p, units, layers, canvas, keys, center: np.ndarray, idx: np.ndarray) -> None:
    """Move (in ``center (N, 2)``) the free units whose start sits on a pin ``idx`` of their
    container (their centres closer than the larger footprint radius) into free room."""
    radius = footprint_radius(units) * p.group_scales()[p.layer_groups()[units.layer]]
    unit_key = np.array([keys[li] for li in units.layer], dtype=object)
    pinned = np.isin(np.arange(len(center)), idx)
    free = p.placement.movable.cpu().numpy() & ~pinned
    for key in set(unit_key[idx]):
        mine = unit_key == key
        pins = idx[unit_key[idx] == key]
        d = np.hypot(*(center[:, None, :] - center[None, pins, :]).transpose(2, 0, 1))
        on_pin = mine & free & (d < np.maximum(radius[:, None], radius[None, pins])).any(1)
        if on_pin.any():
            region = container_region(layers[keys.index(key)].region, canvas, p.grid.rho)
            center[on_pin] = free_room(region, center, radius, mine & ~on_pin, on_pin)
