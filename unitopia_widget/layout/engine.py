"""From a design and a DataFrame to a solved layout.

``bind`` encodes every layer's rows into ``Units`` (one per row, layers
concatenated in drawing order). ``build_problem`` turns units, layers and the
canvas into the solver's ``Problem``: one sprite pyramid per distinct mark
(a layer may draw a group of marks, packed jointly), raster, fields, blocks
(one-way from ``layer.blocks``; two-way between layers that share a container
and do not block each other), starting positions from the emitters, the
global scale. ``layout`` runs the solver and
returns the placements table.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
import torch

from . import arrange, positions
from .atlas import SpriteAtlas
from ..design.encodings import (Encoded, capped_margin, check_column, continuous_values, encode,
                                footprint, linear_extent, is_continuous, missing_warning,
                                palette_for, unhashable, MIN_DRAWN)
from ..design.groups import mark_choice
from .heap import held
from .losses import CanvasTerms
from .pack import thin
from .placement import Placement
from .raster import SPRITE_SIDE, RasterGrid, is_thin, snap_rho, sprite_pyramid
from ..design.scene import block_order
from .solver import Cancelled, Problem, Result, frame, solve
from .strata import Radial, sweep_of
from .start import (any_angle, emission_ranks, footprint_radius, orientation_targets,
                    packed_scales, spot_cost, start_positions)
from .pins import pin_problem, pinned_units
from .warm import warm_problem

TARGET_RADIUS = 10.0      # raster px: the mean footprint radius the raster resolution aims at
THIN_ACROSS = 1.5         # raster px: the least the median thin mark measures across
MAX_RASTER = 6_000_000    # raster px over all layer slabs together
DEFAULT_OPEN_FILL = 0.5
MAX_COVER = 0.9           # the most of a container marks can cover (discs pack to about 0.907)
STILL_ITERATIONS = 20     # the iterations of a layout in which no mark moves and no scale grows


@dataclass
class Units:
    """Per-unit arrays, ``(N,)`` unless noted, layers concatenated in drawing order."""

    rows: list               # index label of each unit's row
    layer: np.ndarray        # layer index
    half_w: np.ndarray       # half box width at scale 1, canvas px
    half_h: np.ndarray       # half box height at scale 1
    area: np.ndarray         # silhouette area at scale 1, canvas px^2
    margin: np.ndarray       # margin fraction
    order: np.ndarray        # emission rank within the layer
    colors: list             # CSS hex colour per unit
    mark: np.ndarray         # index of the unit's mark within its layer's marks
    sprite: np.ndarray       # index of the unit's mark in ``sprites``
    sprites: list            # the distinct footprint Marks (Mark.as_footprint), one sprite pyramid each
    #: position channels (design/positions.py): (N, 2) place along x, y as a fraction of the
    #: container's extent, NaN where unbound; the half band width, same shape; per layer
    #: {"x": Scale, "y": Scale} of its bound channels
    position: np.ndarray | None = None
    band: np.ndarray | None = None
    position_scales: list | None = None

    @property
    def fill_fraction(self) -> np.ndarray:
        """``(N,)`` silhouette area / box area of each unit's mark."""
        return np.array([m.fill_fraction for m in self.sprites])[self.sprite]

    @property
    def ink_share(self) -> np.ndarray:
        """``(N,)`` ink area / footprint area of each unit's mark: 1 but for a mark whose
        footprint fills the holes its ink encloses (a ring: its ink over its filled disc)."""
        return np.array([min(m.as_footprint("ink").fill_fraction / m.fill_fraction, 1.0)
                         if m.solid else 1.0 for m in self.sprites])[self.sprite]

    @property
    def box_size(self) -> np.ndarray:
        """``(N, 2)`` box (w, h) of each unit's mark, in the mark's own units."""
        return np.array([m.box_size for m in self.sprites]).reshape(-1, 2)[self.sprite]


def layer_rows(df: pd.DataFrame, layer) -> pd.DataFrame:
    """The rows of ``df`` that ``layer.rows`` selects."""
    rows = layer.rows
    if rows is None:
        return df
    if "column" in rows:
        check_column(df, f"layer {layer.name!r} rows", rows["column"])
        return df[df[rows["column"]] == rows["value"]]
    missing = [i for i in rows["index"] if i not in df.index]
    if missing:
        raise ValueError(f"layer {layer.name!r}: {len(missing)} of its rows are not in the "
                         f"DataFrame (first missing index label: {missing[0]!r})")
    return df.loc[rows["index"]]


def bind(df: pd.DataFrame, layers) -> Units:
    """Encode all layers. Raises ValueError for empty layers or bad bindings."""
    color_cols = {layer.encodings["color"] for layer in layers
                  if isinstance(layer.encodings["color"], str) and layer.encodings["color"] in df.columns}
    palettes = {}
    for c in color_cols:
        if not is_continuous(df[c]):
            missing_warning(df[c], c)
            try:
                palettes[c] = palette_for(df[c], c)
            except TypeError:
                raise unhashable("color", c, df[c]) from None
    # numeric colours: one scale per column, shared by the layers (as the palettes are)
    domains = {c: _finite_range(df[c]) for c in color_cols if c not in palettes}
    parts, rows, sprites = [], [], {}
    position, band, position_scales = positions.bind_positions(df, layers, layer_rows)
    for i, layer in enumerate(layers):
        sub = layer_rows(df, layer)
        if len(sub) == 0:
            raise ValueError(f"layer {layer.name!r} has no rows to draw")
        e = layer.encodings
        enc: Encoded = encode(sub, size=e["size"], width=e["width"], height=e["height"],
                              color=e["color"], margin=e["margin"], order=e["order"],
                              palette=palettes.get(e["color"]), domain=domains.get(e["color"]))
        for attr, channel in (("area", "size"), ("width", "width"), ("height", "height")):
            span = getattr(layer, f"{channel}_range")
            if span is not None and e[channel] is None:
                raise ValueError(f"layer {layer.name!r}: {channel}_range={span!r} needs "
                                 f"{channel}=<column>; bind {channel} to a numeric column, or "
                                 f"set {channel}_range=None")
            if e[channel] is not None:   # encode normalises per layer; keep layers comparable
                column = sub[e[channel]].to_numpy(dtype=float)
                if span is None:
                    setattr(enc, attr, getattr(enc, attr) * column.mean() / _positive_mean(df[e[channel]]))
                else:   # linear extents over the whole column's range; size is their square
                    setattr(enc, attr, _ranged(column, df[e[channel]], span, channel == "size"))
        choice = mark_choice(df, sub, layer)
        feet = [m.as_footprint(layer.footprint) for m in layer.marks]   # what collides
        sprite = np.array([sprites.setdefault(m, len(sprites)) for m in feet])[choice]
        aspect = np.array([m.aspect for m in feet])[choice]
        fill = np.array([m.fill_fraction for m in feet])[choice]
        # the box whose silhouette has area enc.area: h0 * (aspect * h0) * fill_fraction = area
        h0 = np.sqrt(enc.area / (aspect * fill))
        half_w, half_h = h0 * aspect * enc.width / 2, h0 * enc.height / 2
        enc.margin = capped_margin(enc.margin, half_w, half_h, layer.margin_of)
        parts.append((i, half_w, half_h, enc, choice, sprite))
        rows.extend(sub.index.tolist())
    cat = lambda f: np.concatenate([f(p) for p in parts])  # noqa: E731
    return Units(rows=rows, layer=cat(lambda p: np.full(len(p[3].area), p[0])),
                 half_w=cat(lambda p: p[1]), half_h=cat(lambda p: p[2]),
                 area=cat(lambda p: p[3].area * p[3].width * p[3].height),
                 margin=cat(lambda p: p[3].margin), order=cat(lambda p: p[3].order),
                 colors=[c for p in parts for c in p[3].colors],
                 mark=cat(lambda p: p[4]), sprite=cat(lambda p: p[5]), sprites=list(sprites),
                 position=position, band=band, position_scales=position_scales)


def _ranged(values: np.ndarray, series: pd.Series, span, squared: bool) -> np.ndarray:
    """``(n,)`` factors of ``values`` on the linear scale ``span`` over the finite, positive
    values of ``series`` (mean 1 over the column), squared for an area."""
    full = series.to_numpy(dtype=float, na_value=np.nan)
    full = full[np.isfinite(full) & (full > 0)]
    power = 2 if squared else 1
    mapped = linear_extent(values, span, full.min(), full.max()) ** power
    return mapped / (linear_extent(full, span, full.min(), full.max()) ** power).mean()


def _positive_mean(series: pd.Series) -> float:
    """Mean of the finite, positive values of a numeric column (1 if none)."""
    v = series.to_numpy(dtype=float, na_value=np.nan)
    v = v[np.isfinite(v) & (v > 0)]
    return float(v.mean()) if len(v) else 1.0


def _finite_range(series: pd.Series):
    """(min, max) of the finite values of a numeric or datetime column, or None."""
    v = continuous_values(series)
    v = v[np.isfinite(v)]
    return (float(v.min()), float(v.max())) if len(v) else None


def pick_device(device) -> str:
    """"cuda" when asked for or (device None/"auto") available, else "cpu"."""
    if device in (None, "auto"):
        return "cuda" if torch.cuda.is_available() else "cpu"
    if device not in ("cpu", "cuda") and not str(device).startswith("cuda:"):
        raise ValueError(f"device must be None, 'auto', 'cpu' or 'cuda', got {device!r}")
    if str(device).startswith("cuda") and not torch.cuda.is_available():
        raise ValueError(f"device={device!r} but CUDA is not available here; use 'cpu' or None")
    return str(device)


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
    groups = []   # [(region, [layers])]: regions compare by value
    for layer in layers:
        if layer.boundary == "open" or layer.fill is not None:
            group = next((g for region, g in groups if region == layer.region), None)
            if group is None:
                groups.append((layer.region, [layer]))
            else:
                group.append(layer)
    out = []
    for _, group in groups:
        total = sum(layer.fill or DEFAULT_OPEN_FILL for layer in group)
        if len(group) > 1 and total > MAX_COVER:
            out.append(([layer.name for layer in group], total))
    return out


def scale_cap(units: Units, layers, canvas, i: int) -> float:
    """The largest scale at which layer ``i``'s longest mark fits its container's widest disc."""
    mine = units.layer == i
    longest = float(np.max(np.maximum(units.half_w[mine], units.half_h[mine])))
    return 0.95 * _widest_disc(layers[i].region, canvas) / longest


def _widest_disc(container, canvas) -> float:
    """Radius (canvas px) of the widest disc inside ``container`` on the canvas."""
    from .lattice import Region
    rho = min(1.0, 600.0 / max(canvas))
    return float(Region(container.coverage(canvas, rho), rho).depth.max())


def build_problem(units: Units, layers, canvas, seed: int, device: str,
                  max_iterations: int | None = None, scales: str = "shared",
                  abort=None, on_start=None) -> Problem:
    """Assemble the solver's problem for ``units`` laid out by ``layers``; ``abort()``
    returning True between its steps raises ``Cancelled``. ``on_start(frame)`` gets the start
    frame (``solver.frame``) as soon as the start positions are known, before the region
    fields and sprites: what ``solve`` would send first; ``abort`` is not asked after it."""
    order = block_order(layers)
    # each layer's widest disc, measured once for the start scale and the packed one
    caps = [scale_cap(units, layers, canvas, i) for i in range(len(layers))]
    group_scale, group_free, scale_group = initial_scale(units, layers, canvas, scales, caps)
    group_scale = packed_scales(units, layers, order, canvas, group_scale, group_free,
                                scale_group, caps)
    rho_start = min(1.0, 600.0 / max(canvas))   # the start's region raster
    group_scale, group_free = arrange.grid_scales(units, layers, canvas, group_scale, group_free,
                                                  scale_group, rho_start)
    group_scale, group_free = positions.capped_scales(units, layers, canvas, group_scale,
                                                      group_free, scale_group, rho_start)
    scale, free_scale = float(group_scale[0]), bool(group_free.any())
    unit_scale = group_scale[scale_group[units.layer]]
    _check(abort)
    band = footprint(units.margin)
    foot = np.hypot(units.half_w, units.half_h) * band * unit_scale
    # marks drawn under MIN_DRAWN px across (a heavy tail's dust, warned about) do not set the
    # raster resolution: aiming it at them would make the raster, and every pass, many times larger
    seen = 2 * np.minimum(units.half_w, units.half_h) * unit_scale >= MIN_DRAWN
    r_mean = float(np.mean(foot[seen] if seen.any() else foot))
    w, h = canvas
    rho = max(TARGET_RADIUS / r_mean, 0.25)
    # thin marks collide across their short side: two strands side by side in pixels wider
    # than they are share a pixel, whose summed alpha stays under 1, and their overlap is lost
    long_side = 2 * np.maximum(units.half_w, units.half_h) * unit_scale
    slim = thin(units.half_w, units.half_h) & (long_side >= MIN_DRAWN)
    if slim.any():
        across = 2 * np.minimum(units.half_w, units.half_h)[slim] * unit_scale[slim]
        rho = max(rho, THIN_ACROSS / float(np.median(across)))
    rho = min(rho, 4.0, math.sqrt(MAX_RASTER / (w * h * len(layers))))
    half = np.stack([units.half_w, units.half_h]) * band * unit_scale
    rho = snap_rho(rho, half[0], half[1], any_angle(layers))
    grid = RasterGrid((w, h), rho, pad=2)
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
    _check(abort)
    fields = [_fields(layer.region, grid, r_mean * rho) for layer in layers]
    _check(abort)
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
    sweeps = tuple(s.on(grid.shape, grid.rho, grid.pad, dev)
                   if isinstance(s, Radial) and rests[a].any() else s for a, s in enumerate(sweeps))
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
    _check(abort)
    pyramids = [_pyramid(mark, str(dev)) for mark in units.sprites]
    _check(abort)
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
                   half_h=units.half_h, margin=units.margin, placement=placement, terms=terms,
                   forces=[layer.forces for layer in layers], scale=scale,
                   free_scale=free_scale, max_iterations=cap, device=device,
                   scale_group=scale_group, group_scale=group_scale, group_free=group_free,
                   reach=_reach(units), disc=disc, ink_share=units.ink_share,
                   stage=np.array([depth[i] for i in units.layer]),
                   travelling=any(layer.emitter is not None for layer in layers), anchor=anchor,
                   regions=tuple(layer.region for layer in layers))


def _check(abort) -> None:
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
    return sprite_pyramid(alpha, device, keep_thin=is_thin(ink) or hollow)


def _reach(units: Units) -> np.ndarray:
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


def _fields(container, grid: RasterGrid, falloff: float):
    from .fields import region_fields
    cov = container.coverage(grid.canvas, grid.rho)
    inside, outside, penalty = region_fields(cov, grid, falloff)
    return tuple(torch.from_numpy(a).reshape(-1) for a in (inside, outside, penalty))


def placements(units: Units, layers, result: Result) -> pd.DataFrame:
    """The layout table: one row per unit (row, layer, x, y, angle, sx, sy, width, height,
    mark); ``mark`` indexes the layer's marks."""
    names = np.array([layer.name for layer in layers], dtype=object)
    width = 2 * units.half_w * result.unit_scale
    height = 2 * units.half_h * result.unit_scale
    box = units.box_size
    return pd.DataFrame({
        "row": units.rows, "layer": names[units.layer],
        "x": result.center[:, 0], "y": result.center[:, 1], "angle": result.angle,
        "sx": width / box[:, 0], "sy": height / box[:, 1], "width": width, "height": height,
        "mark": units.mark,
    })


def layout(df, layers, canvas, seed=0, device=None, on_frame=None, cancel=None,
           on_progress=None, frame_every: int = 3, scales: str = "shared", abort=None,
           pins=(), previous=None):
    """Bind, build and solve. Returns ``(units, result, placements DataFrame)``.

    ``cancel()`` returning True ends the solve, which keeps its last step (none taken: the
    start). ``abort()`` (a Stop) returning True during the setup or before the first step
    raises ``Cancelled``: there is no layout to keep; but once ``on_frame`` has shown the
    start (a fresh, unpinned run shows it before the fields are made), a Stop keeps the
    start as the layout. ``pins``: ``design.pins.Pin``s held in place (``layout.pins``);
    ``previous``: a ``warm.snapshot`` to start from (None: a fresh start)."""
    units = bind(df, layers)
    _check(abort)
    pinned, pin_xy, pin_angle = pinned_units(units, layers, pins)
    # a fresh, unpinned start is the solver's start: it is shown before the fields are made
    early = on_frame if previous is None and len(pinned) == 0 else None
    with held():   # the iterations' scratch tensors reuse the heap, not fresh pages
        problem = build_problem(units, layers, canvas, seed, pick_device(device), scales=scales,
                                abort=abort, on_start=early)
        if previous is not None:
            problem = warm_problem(problem, units, layers, canvas, previous, pinned, pin_xy)
        problem = pin_problem(problem, units, layers, canvas, pinned, pin_xy, pin_angle)
        result = solve(problem, on_frame=on_frame, cancel=cancel, on_progress=on_progress,
                       frame_every=frame_every, start_frame=early is None)
    if result.iterations == 0 and early is None and abort is not None and abort():
        raise Cancelled("the layout was stopped before its first step")
    table = placements(units, layers, result)
    return units, result, table
