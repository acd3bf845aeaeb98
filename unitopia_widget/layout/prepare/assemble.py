"""From bound units, layers and the canvas to the solver's ``Problem``: one sprite pyramid
per distinct mark (a layer may draw a group of marks, packed jointly), raster, fields,
blocks (one-way from ``layer.blocks``; two-way between layers that share a container and
do not block each other), starting positions from the emitters, the global scale."""
from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import torch

from ...design.encodings import footprint, MIN_DRAWN
from ...design.scene import block_order
from ...design.units import Units
from ..step.atlas import SpriteAtlas
from ..step.losses import CanvasTerms
from ..step.placement import Placement, frame
from ..step.raster import SPRITE_SIDE, RasterGrid, is_thin, snap_rho, sprite_pyramid
from ..step.strata import Radial, sweep_of
from . import arrange, fit, positions
from .fields import region_fields
from .hub import with_hub
from .kept import kept
from .lattice import start_rho
from .order import start_order
from .pack import thin
from .problem import Cancelled, Problem
from .scale import initial_scale, packed_scales, scale_cap
from .start import any_angle, emission_ranks, footprint_radius, orientation_targets, spot_cost, start_positions

TARGET_RADIUS = 10.0      # raster px: the mean footprint radius the raster resolution aims at
THIN_ACROSS = 1.5         # raster px: the least the median thin mark measures across
MAX_RASTER = 6_000_000    # raster px over all layer slabs together
UNSEEN_DEPTH = 0.5        # raster px: how deep two solid marks can meet and still read as apart
STILL_ITERATIONS = 20     # the iterations of a layout in which no mark moves and no scale grows


def build_problem(units: Units, layers, canvas, seed: int, device: str,
                  max_iterations: int | None = None, scales: str = "shared",
                  abort=None, on_start=None, scale_at=None) -> Problem:
    """Assemble the solver's problem for ``units`` laid out by ``layers``; ``abort()``
    returning True between its steps raises ``Cancelled``. ``on_start(frame)`` gets the start
    frame (``step.placement.frame``) as soon as the start positions are known, before the region
    fields and sprites: what ``solve`` would send first; ``abort`` is not asked after it.
    ``scale_at (G,)``: the scale groups start at these scales (and the raster is made for
    them) instead of those the start picks."""
    # without order=, the units start in an order drawn from the seed, not the rows' order
    units = dataclasses.replace(units, order=start_order(units, layers, seed))
    order = block_order(layers)
    # each layer's widest disc, measured once for the start scale and the packed one
    caps = [scale_cap(units, layers, canvas, i) for i in range(len(layers))]
    group_scale, group_free, scale_group = initial_scale(units, layers, canvas, scales, caps)
    group_scale = packed_scales(units, layers, order, canvas, group_scale, group_free,
                                scale_group, caps, seed)
    rho_start = start_rho(canvas)   # the start's region raster
    group_scale, group_free = arrange.grid_scales(units, layers, canvas, group_scale, group_free,
                                                  scale_group, rho_start)
    group_scale, group_free = positions.capped_scales(units, layers, canvas, group_scale,
                                                      group_free, scale_group, rho_start)
    if scale_at is not None:   # a layout's own scales (``engine.finer``): the raster aims at them
        group_scale = np.asarray(scale_at, dtype=float)
    scale, free_scale = float(group_scale[0]), bool(group_free.any())
    unit_scale = group_scale[scale_group[units.layer]]
    check_abort(abort)
    capped, aimed, r_mean = raster_rho(units, layers, canvas, unit_scale)
    unseen = unseen_depth(capped, aimed)
    margin = padded_margin(units, unit_scale, unseen)
    band = footprint(margin)
    w, h = canvas
    half = np.stack([units.half_w, units.half_h]) * band * unit_scale
    rho = snap_rho(capped, half[0], half[1], any_angle(layers))
    grid = RasterGrid((w, h), rho, pad=2)
    # solid marks this wide on the raster touch by more than its pixels: the raster reads
    # every contact (thin marks and rings' strokes are narrower); on a capped raster, at the
    # resolution aimed at, the footprints' unseen depth making up the rest
    across = 2 * np.minimum(units.half_w, units.half_h) * unit_scale * grid.rho * aimed / capped
    resolved = bool((units.ink_share >= 1.0).all() and (across >= TARGET_RADIUS).all())
    dev = torch.device(device)
    generator = torch.Generator().manual_seed(int(seed))
    start = start_positions(units, layers, order, canvas, unit_scale, grid, generator)
    arrange.snap(start, units, layers, canvas, unit_scale, lambda layer, pts: spot_cost(
        layer, layer.region, canvas, pts), rho_start)
    disc = footprint_radius(units)                   # (N,) the packed disc at scale 1
    footprints = disc * unit_scale                   # (N,) canvas px at the start scale
    anchor = positions.anchors(units, layers, canvas, footprints, rho_start)
    if anchor is not None:
        positions.dodge(start.center, units, layers, canvas, footprints,
                        *anchor[:3], lambda idx: emission_ranks(units.order[idx]), rho_start)
        anchor = positions.Anchor(*anchor, radius=r_mean, device=dev, band=units.band)
    placement = Placement(start.center, start.angle, start.movable, start.turnable, dev,
                          orientation=orientation_targets(units, layers, canvas, dev),
                          tracks=start.tracks(dev), drift=start.drift)
    if on_start is not None:   # the start is known: a live view shows it while the fields
        on_start(frame(placement, unit_scale))   # and sprites are made; a Stop from now on
        abort = None                             # keeps it (the solver ends at its start)
    check_abort(abort)
    fields = [_fields(layer.region, grid, r_mean * rho) for layer in layers]
    check_abort(abort)
    chain = torch.zeros(len(layers), len(layers))
    names = [layer.name for layer in layers]
    for a in order:   # blocking layers first, so their own obstacles are known: blocks chain
        for b in layers[a].blocks:
            chain[a, names.index(b)] = 1.0
            chain[a] = torch.maximum(chain[a], chain[names.index(b)])
    # a layer under directional or point forces rests on the layers it blocks on (their
    # shadow, strata.py); others see their ink
    resting = torch.tensor([sweep_of(layer.forces) is not None for layer in layers],
                           dtype=chain.dtype)[:, None]
    rests, blocks = chain * resting, chain * (1 - resting)
    # a point sweep sees past its cell by the largest footprint of the layers rested on
    bands = [float(footprints[np.isin(units.layer, np.nonzero(rests[a].numpy())[0])].max())
             if rests[a].any() else 0.0 for a in range(len(layers))]
    sweeps = tuple(sweep_of(layer.forces, band) for layer, band in zip(layers, bands))
    # layers swept alike share one radial shadow: its grids are made once
    shared = {}
    for a, s in enumerate(sweeps):
        if isinstance(s, Radial) and rests[a].any() and s not in shared:
            shared[s] = s.on(grid.shape, grid.rho, grid.pad, dev)
    sweeps = tuple(shared.get(s, s) if rests[a].any() else s for a, s in enumerate(sweeps))
    # layers that share a container and do not block each other collide both ways
    for a in range(len(layers)):
        for b in range(a + 1, len(layers)):
            if layers[a].region == layers[b].region and not (chain[a, b] or chain[b, a]):
                blocks[a, b] = blocks[b, a] = 1.0
    norm = float((units.area * band ** 2 * unit_scale ** 2).sum()) * rho ** 2
    terms = CanvasTerms(
        penalty=torch.stack([f[2] for f in fields]).to(dev),
        outside=torch.stack([f[1] for f in fields]).to(dev),
        inside=torch.stack([f[0] if layer.boundary == "closed" and layer.fill is None
                            else torch.zeros_like(f[0]) for f, layer in zip(fields, layers)]).to(dev),
        blocks=blocks.to(dev), rests=rests.to(dev) if rests.any() else None, sweeps=sweeps,
        shape=grid.shape, norm=norm, w_fill=0.15 if free_scale else 0.0)
    # one per distinct mark: a layer's units may draw different marks
    check_abort(abort)
    pyramids = [_pyramid(mark, str(dev)) for mark in units.sprites]
    check_abort(abort)
    cap = max_iterations or max(layer.iterations for layer in layers)
    if not start.movable.any() and not free_scale:   # nothing can move (a grid): one short polish
        cap = min(cap, STILL_ITERATIONS)
    # layers emitted on top of the layers they block on are poured in turn
    depth = {}
    for i in order:
        emitted = layers[i].emitter is not None
        depth[i] = max([depth[names.index(b)] + 1 for b in layers[i].blocks], default=0) if emitted else 0
    sides = [SPRITE_SIDE] * len(pyramids)
    aspects = [float(lv[0].shape[-1] / lv[0].shape[-2]) for lv in pyramids]
    if len(pyramids) > 1:   # one texture for all marks: the cost does not grow with their number
        pyramids = SpriteAtlas(pyramids)
    return Problem(grid=grid, pyramids=pyramids, sprite_sides=sides, sprite_aspects=aspects,
                   sprite=units.sprite, layer=units.layer, half_w=units.half_w,
                   half_h=units.half_h, margin=margin, unseen=unseen, placement=placement, terms=terms,
                   forces=[layer.forces for layer in layers], scale=scale,
                   free_scale=free_scale, max_iterations=cap, device=device,
                   scale_group=scale_group, group_scale=group_scale, group_free=group_free,
                   group_cap=fit.group_caps(units, layers, canvas, scale_group, group_free),
                   reach=room_reach(units), disc=disc, ink_share=units.ink_share, resolved=resolved,
                   stage=np.array([depth[i] for i in units.layer]),
                   travelling=any(layer.emitter is not None for layer in layers), anchor=anchor,
                   regions=tuple(layer.region for layer in layers))


def raster_rho(units: Units, layers, canvas, unit_scale: np.ndarray) -> tuple[float, float, float]:
    """``(rho, aimed, r_mean)``: the raster px per canvas px (before ``snap_rho``) for
    ``units`` drawn at ``unit_scale (N,)``; the resolution it aims at, ``rho`` unless capped
    (at most 4, or ``MAX_RASTER`` px over all layers); their mean footprint radius, canvas px."""
    foot = np.hypot(units.half_w, units.half_h) * footprint(units.margin) * unit_scale
    # marks drawn under MIN_DRAWN px across (a heavy tail's dust, warned about) do not set the
    # raster resolution: aiming it at them would make the raster, and every pass, many times larger
    seen = 2 * np.minimum(units.half_w, units.half_h) * unit_scale >= MIN_DRAWN
    r_mean = float(np.mean(foot[seen] if seen.any() else foot))
    rho = max(TARGET_RADIUS / r_mean, 0.25)
    across = thin_across(units, unit_scale)
    if across is not None:
        rho = max(rho, THIN_ACROSS / across)
    w, h = canvas
    return min(rho, 4.0, math.sqrt(MAX_RASTER / (w * h * len(layers)))), rho, r_mean


def unseen_depth(rho: float, aimed: float) -> float:
    """Canvas px each footprint reaches further on every side where the raster is capped at
    ``rho`` below the ``aimed`` resolution. Two solid marks can meet ``UNSEEN_DEPTH`` raster
    px deep and still read as apart (their edge pixels are partly covered); the capped
    raster's pixels are wider, and the two footprints carry the difference in depth, half
    each. 0 where the raster is not capped. Table 1 at 20,000 equal discs (rho 2.24 of the
    4.56 aimed at): 0.057 px, a 2.6% margin; the exact overlap 0.212 -> 0.006%."""
    return 0.5 * UNSEEN_DEPTH * max(1.0 / rho - 1.0 / aimed, 0.0)


def padded_margin(units: Units, unit_scale: np.ndarray, depth: float) -> np.ndarray:
    """``(N,)`` the margins of ``units`` drawn at ``unit_scale (N,)`` whose footprints reach
    ``depth`` canvas px further on every side (a box's geometric mean half side)."""
    if depth <= 0.0:
        return units.margin
    return units.margin + depth / (np.sqrt(units.half_w * units.half_h) * unit_scale)


def thin_across(units: Units, unit_scale: np.ndarray) -> float | None:
    """Canvas px across the median thin mark (box over 2:1, long side drawn at least
    ``MIN_DRAWN``) drawn at ``unit_scale (N,)``; None without one. Thin marks collide across
    their short side: two strands side by side in pixels wider than they are share a pixel,
    whose summed alpha stays under 1, and their overlap is lost."""
    long_side = 2 * np.maximum(units.half_w, units.half_h) * unit_scale
    slim = thin(units.half_w, units.half_h) & (long_side >= MIN_DRAWN)
    if not slim.any():
        return None
    return float(np.median(2 * np.minimum(units.half_w, units.half_h)[slim] * unit_scale[slim]))


def check_abort(abort) -> None:
    if abort is not None and abort():
        raise Cancelled("the layout was stopped during its setup")


@functools.lru_cache(maxsize=64)
def _pyramid(mark, device: str) -> list:
    """The sprite pyramid of ``mark`` on ``device``, made once per process (marks are
    immutable and the solver only reads it): a second layout skips the render."""
    alpha = mark.silhouette(SPRITE_SIDE)
    # a sun's rays stay thin lines when its disc is filled: the ink says whether it is drawn in lines
    ink = mark.as_footprint("ink").silhouette(SPRITE_SIDE) if mark.solid else alpha
    # a hollow mark (its footprint fills holes in its ink) keeps its coarse levels at least as
    # wide as its finest, as lines do: a contact a fraction of a raster pixel deep, little of
    # a solid mark's area, is much of a ring's ink, and the wider levels keep it in the gap
    hollow = float(alpha.sum()) > float(ink.sum())
    if mark.solid:   # a silhouette keeps others out of its hub too
        alpha = with_hub(alpha)
    return sprite_pyramid(alpha, device, keep_thin=is_thin(ink) or hollow)


def room_reach(units: Units) -> np.ndarray:
    """``(N,)`` at scale 1: the ink's area-equivalent radius less the margin band the room
    is seen through (the room the controller looks for is measured from the footprints, a
    checker measures it from the ink). Bands grow with their marks, and a mark borders room
    in proportion to its size: the band is its layer's mean, weighted by the marks' short
    half sides, so that the wide bands of a few large marks are not hidden by the median's."""
    side = np.minimum(units.half_w, units.half_h)
    band = (footprint(units.margin) - 1) * side
    seen = np.zeros_like(band)
    for layer in np.unique(units.layer):
        mine = units.layer == layer
        seen[mine] = float((band[mine] * side[mine]).sum() / max(float(side[mine].sum()), 1e-9))
    return np.maximum(np.sqrt(units.area / math.pi) - seen, 0.0)


_FIELDS: dict = {}   # (container JSON text, canvas, rho, pad, falloff) -> fields, the last few made
FIELDS_KEPT = 2


def _fields(container, grid: RasterGrid, falloff: float):
    """``(inside, outside, penalty)`` of ``container`` (``fields.region_fields``), flat
    ``(S,)`` tensors, made once per (container JSON, raster, falloff) among the last
    ``FIELDS_KEPT`` asked for, as ``lattice.container_region`` keeps regions: a second layout
    of the same container and marks skips the coverage and the distance transform (the terms
    copy the fields, which are only read)."""
    def make():
        cov = container.coverage(grid.canvas, grid.rho)
        return tuple(torch.from_numpy(a).reshape(-1) for a in region_fields(cov, grid, falloff))

    key = (repr(container.to_json()), tuple(grid.canvas), float(grid.rho), grid.pad, float(falloff))
    return kept(_FIELDS, key, make, FIELDS_KEPT)
