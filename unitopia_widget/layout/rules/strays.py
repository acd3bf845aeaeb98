"""``strays``: a mark left outside its container, poking out of it, or deep in another mark
is moved to a free spot.

The loss pulls ink outside a container back in with a gradient only near the container's
edge, and a mark that a gradient step carries past the wall late in a layout (a small one
squeezed between the wall and a large neighbour as the settle runs out) ends wholly outside
it, where nothing moves it again; a long one pressed out by its neighbours (a strand of hair
at the foot of a blob) keeps part of its ink out, and marks of a pile still jammed when the
budget ran out (a stage poured last) stay on top of each other: the legalising rounds shrink
the whole layout a little a round to mend either. After the last iteration, every movable
unit whose centre lies outside its region, or more than ``poke`` of whose ink lies outside
it, or more than ``poke`` of whose footprint lies under others (the most overlapped first),
each read on the layout's raster and, for a mark too faint for it (no pixel of its
footprint at half alpha there, so two on one spot read as no overlap), on the fine one too,
moves to the nearest spot (on the fine raster of ``step.fine``) where its footprint is wholly
inside, on no footprint it collides with and, in a layer resting on others, out of the shadow
they cast; in a layer others rest on, a spot short of them (their ink swept back against
their pull) is looked for first, so that a jammed mark of a lower stratum stays below the
strata on it, and any spot only where none is. A mark with a margin whose footprint has no
such spot (a closed fill at a wide margin, where the margins take all the room left) gives
its margin up, the wall's share first: its ink wholly inside and its footprint on no other,
else its ink wholly inside and on no footprint, the ink a fine px in from the wall either
way (``inset``). A mark of a curve emitter's band is looked for a spot only along the curve's
normal where it is (``state.sideways``), keeping its place along the curve and so the
emission order. Where no spot is within reach, it stays.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ...design.encodings import footprint
from ..step.fine import draw, drawn_runs, samples
from ..step.strata import swept_along
from .state import Rule, shift, sideways, unbound


@dataclass(frozen=True)
class StraysSettings:
    fine_rho: float = 2.0          # fine raster px per canvas px
    max_fine: int = 24_000_000     # fine raster px over all layer slabs at most (more get coarser)
    reach: float = 0.25            # the farthest spot looked at, as a share of the canvas diagonal
    spacing: float = 0.25          # spots looked at this share of the unit's footprint radius apart
    across: int = 150              # spots looked at on one line across the reach at most
    chunk: int = 4_000_000         # fine pixels looked up at once
    poke: float = 0.05             # the share of its ink a unit may leave outside its region,
                                   # and of its footprint under others


def outside(p, center: np.ndarray, units: np.ndarray) -> np.ndarray:
    """Bool ``(n,)``: which of ``units (n,)`` have their centre (``center (N, 2)`` canvas px)
    outside their layer's region (its coverage under half at that pixel, or off the canvas)."""
    rho = p.grid.rho
    out = np.zeros(len(units), bool)
    for a in np.unique(p.layer[units]):
        mine = p.layer[units] == a
        cover = p.regions[a].coverage(p.grid.canvas, rho)
        h, w = cover.shape
        xy = center[units[mine]]
        j, i = np.floor(xy[:, 0] * rho).astype(int), np.floor(xy[:, 1] * rho).astype(int)
        on = (i >= 0) & (i < h) & (j >= 0) & (j < w)
        inside = np.zeros(len(xy), bool)
        inside[on] = cover[i[on], j[on]] >= 0.5
        out[mine] = ~inside
    return out


def ink_outside(p, center: torch.Tensor, angle: torch.Tensor, unit_scale: np.ndarray,
                rotating: np.ndarray) -> np.ndarray:
    """``(N,)`` the share of each unit's ink (its mark drawn at ``unit_scale (N,)``, without
    its margin) outside the region its layer may draw in (``CanvasTerms.outside``), on the
    layout's raster."""
    values, index, owner = samples(p, p.grid, center, angle, p.half_w * unit_scale,
                                   p.half_h * unit_scale, rotating)
    layer = torch.as_tensor(p.layer, device=center.device, dtype=torch.long)[owner]
    out = values * p.terms.outside[layer, index.long()].to(values.dtype)
    n = len(p.layer)
    ink = torch.zeros(n, device=center.device).index_add_(0, owner, values)
    return (torch.zeros(n, device=center.device).index_add_(0, owner, out)
            / ink.clamp_min(1e-9)).cpu().numpy()


def overlapped(p, feet) -> np.ndarray:
    """``(N,)`` the share of each unit's footprint that the loss counts as overlapped by other
    footprints or lower strata (``CanvasTerms.unit_overlap``), from ``feet``: the footprints
    (margins included) drawn on the layout's raster (``step.fine.samples``)."""
    values, index, owner = feet
    n = len(p.layer)
    layer = torch.as_tensor(p.layer, device=values.device, dtype=torch.long)
    over = p.terms.unit_overlap(values, index, owner, layer, n)
    drawn = torch.zeros(n, device=values.device).index_add_(0, owner, values)
    return (over / drawn.clamp_min(1e-9)).cpu().numpy()


def faint(feet, n: int) -> np.ndarray:
    """Bool ``(n,)``: the units whose footprint ``feet`` (as for ``overlapped``) covers no
    pixel of the layout's raster by half or more. The loss counts the overlap of a pixel's
    alpha past 1, so two such footprints on one spot read as none: their overlaps, and their
    ink outside, are read on the fine raster too."""
    values, _, owner = feet
    peak = torch.zeros(n, device=values.device).scatter_reduce(0, owner, values, "amax")
    return (peak < 0.5).cpu().numpy()


def ink_off(fine, ink, units: np.ndarray) -> np.ndarray:
    """``(n,)`` the share of the ink px of each of ``units (n,)`` (``ink``, as ``ink_pixels``
    returns) outside its region on the fine raster ``fine`` (0 for a unit with none)."""
    out = np.zeros(len(units))
    for k, i in enumerate(units):
        pix = ink(i)
        if len(pix):
            out[k] = 1.0 - float(fine.inside[int(fine.layer[i]), pix].float().mean())
    return out


def strata_rooms(p, feet, fine) -> tuple[torch.Tensor, torch.Tensor] | None:
    """``(below, beyond)``, each ``(L, S)`` bool on the fine raster ``fine`` (``step.fine``),
    from the footprints ``feet`` (as for ``overlapped``) where they are, on the layout's
    raster; None where no layer rests on another (``strata``). ``below``: for a layer that
    rests on others, the shadow those cast, as the loss casts it (``CanvasTerms.obstacles``):
    a mark moved there would sit below them. ``beyond``, its mirror: for a layer others rest
    on, their ink swept back against their pull (``swept_along``): a mark moved there would
    sit beyond them."""
    terms = p.terms
    if terms.rests is None or not bool(terms.rests.any()):
        return None
    values, index, owner = feet
    layer = torch.as_tensor(p.layer, device=values.device, dtype=torch.long)
    _, own = terms.coverage(values, index, owner, layer)
    below = terms.obstacles(own) - terms.blocks.to(own) @ own
    below[~terms.rests.any(1).to(below.device)] = 0.0
    beyond = torch.zeros_like(own)
    for a, sweep in enumerate(terms.sweeps):
        if sweep is not None and bool(terms.rests[a].any()):
            back = swept_along(sweep, own[a].view(p.grid.shape), back=True).reshape(-1)
            for b in torch.nonzero(terms.rests[a]).reshape(-1).tolist():
                beyond[b] += back
    coarse, rho = p.grid, fine.grid.rho

    def at(k: int, pad: int, top: int) -> np.ndarray:   # each fine px's row (column) there
        canvas = (np.arange(k) - fine.grid.pad + 0.5) / rho
        return np.clip(np.floor(canvas * coarse.rho).astype(int) + pad, 0, top - 1)

    h, w = fine.grid.shape
    rows = torch.as_tensor(at(h, coarse.pad, coarse.shape[0]), device=own.device)
    cols = torch.as_tensor(at(w, coarse.pad, coarse.shape[1]), device=own.device)
    return tuple((x.view(-1, *coarse.shape).index_select(1, rows).index_select(2, cols) >= 0.5)
                 .reshape(len(x), -1) for x in (below, beyond))


def inset(room: torch.Tensor, shape: tuple) -> torch.Tensor:
    """``room (S,)`` bool on a raster of ``shape`` (rows, columns) less each pixel with a
    4-neighbour outside it: ink that gives its margin up keeps a fine px from the wall, where
    the engine's drawing of a mark and an exporter's may differ by one."""
    r = room.view(shape)
    out = r.clone()
    out[1:] &= r[:-1]
    out[:-1] &= r[1:]
    out[:, 1:] &= r[:, :-1]
    out[:, :-1] &= r[:, 1:]
    return out.view(-1)


def around(far: float, step: int) -> np.ndarray:
    """``(K, 2)`` (row, column) offsets on a grid ``step`` px apart out to ``far`` px, the
    nearest first."""
    span = np.arange(-int(far), int(far) + 1, step)
    dy, dx = np.meshgrid(span, span, indexing="ij")
    near = np.argsort(np.hypot(dy, dx).ravel(), kind="stable")
    return np.stack([dy.ravel()[near], dx.ravel()[near]], 1)


def along(normal: np.ndarray, far: float, step: int) -> np.ndarray:
    """``(K, 2)`` (row, column) offsets ``step`` px apart out to ``far`` px either way along
    ``normal`` (x, y), the nearest first, each rounded to a px."""
    span = np.arange(-int(far), int(far) + 1, step)
    span = span[np.argsort(np.abs(span), kind="stable")]
    return np.rint(span[:, None] * np.asarray(normal)[None, ::-1]).astype(int)


def nearest_spot(checks: list, shape: tuple, offsets: np.ndarray, chunk: int,
                 probe: int = 32) -> tuple[int, int] | None:
    """The first of ``offsets`` ``(K, 2)`` (row, column) that puts, for each ``(allowed (S,)
    bool, pix (P,) long)`` of ``checks``, every one of the flat pixels ``pix`` on an
    ``allowed`` pixel of a raster of ``shape`` (rows, columns); None where no offset does.
    Offsets that take a set's bounding box off the raster are dropped first; each other is
    tried on ``probe`` pixels spread over each ``pix`` first, and on all of them only where
    those pass."""
    rows, cols = shape
    device = checks[0][1].device
    offsets = torch.as_tensor(offsets, device=device)
    on = torch.ones(len(offsets), dtype=torch.bool, device=device)
    for _, pix in checks:
        if len(pix):
            r, c = pix // cols, pix % cols
            on &= (offsets[:, 0] >= -r.min()) & (offsets[:, 0] < rows - r.max()) \
                & (offsets[:, 1] >= -c.min()) & (offsets[:, 1] < cols - c.max())
    offsets = offsets[on]
    shift = offsets[:, 0] * cols + offsets[:, 1]   # (K,) each offset in flat px
    few = [pix[torch.linspace(0, len(pix) - 1, min(probe, len(pix)), device=device).long()]
           for _, pix in checks]
    every = [pix for _, pix in checks]

    def clear(part, sets):   # (d,) bool: every pixel of each set moved by each offset allowed
        ok = torch.ones(len(part), dtype=torch.bool, device=device)
        for (allowed, _), pix in zip(checks, sets):
            ok &= allowed[pix[None] + shift[part][:, None]].all(1)
        return ok

    n_few, n_all = sum(len(f) for f in few), sum(len(p) for p in every)
    order = torch.arange(len(offsets), device=device)
    done, size = 0, 256   # the nearest offsets first, in runs that double
    while done < len(offsets):
        part = order[done:done + size]
        done, size = done + len(part), min(2 * size, max(1, chunk // max(n_few, 1)))
        part = part[clear(part, few)]
        for sub in torch.split(part, max(1, min(size, chunk // max(n_all, 1)))):
            ok = torch.nonzero(clear(sub, every)).reshape(-1)
            if len(ok):
                row, column = offsets[sub[ok[0]]].tolist()
                return int(row), int(column)
    return None


def ink_pixels(p, grid, center: torch.Tensor, angle: torch.Tensor, unit_scale: np.ndarray,
               rotating: np.ndarray):
    """A function of unit ``i`` to its ink's flat px ``(P,)`` long on ``grid`` (the fine
    raster's), each mark drawn at ``center (N, 2)``, ``angle (N,)`` and ``unit_scale (N,)``
    without its margin, cut as ``step.fine.draw`` cuts the footprints."""
    index, _, bounds = drawn_runs(p, grid, center, angle, p.half_w * unit_scale,
                                  p.half_h * unit_scale, rotating)
    return lambda i: index[bounds[i]:bounds[i + 1]]


@torch.no_grad()
def bring_back(p, place, unit_scale: np.ndarray, c: StraysSettings = StraysSettings()) -> np.ndarray:
    """``(N, 2)`` canvas px each unit of the solver's ``Problem`` ``p`` moves (0 for most):
    the movable units of ``place`` (not bound to positions) whose centres lie outside their
    regions (``outside``) or more than ``poke`` of whose ink does (``ink_outside``), then
    those more than ``poke`` of whose footprint others overlap (``overlapped``; most first,
    each while it still is on the fine raster), the ink and the overlap of a ``faint`` unit
    read on the fine raster too (``ink_off``, ``FineRaster.crowded``), to the nearest free
    spot wholly inside and out of the shadow of the layers each rests on (``strata_rooms``),
    first also short of the layers resting on it, looked for on a grid ``spacing`` footprint
    radii apart out to ``reach`` of the canvas diagonal; where a unit with a margin finds
    none, the nearest spot with its ink inside (a fine px in from the wall) and its footprint
    free, else with its ink inside and free. A unit of a band (``sideways``) is looked for a
    spot only along its curve's normal (``along``)."""
    center, angle = place.transforms()
    xy = center.detach().cpu().numpy().astype(float)
    moved = np.zeros_like(xy)
    if not p.regions:
        return moved
    # a unit bound to an x=/y= position keeps it; one of a band moves along its curve's normal
    aside = sideways(p, place)
    free = np.flatnonzero(unbound(p, place) | aside.any(1))
    center, angle, rotating = center.detach(), angle.detach(), place.rotating()
    poking = ink_outside(p, center, angle, unit_scale, rotating)
    grow = footprint(p.margin) * unit_scale
    feet = samples(p, p.grid, center, angle, p.half_w * grow, p.half_h * grow, rotating)
    crowded = overlapped(p, feet)
    fine = ink = None   # the fine raster, each unit's ink px where it started: drawn when needed
    blind = free[faint(feet, len(p.layer))[free]]
    if len(blind):   # their overlaps and ink outside read on the fine raster too
        fine = draw(p, center, angle, unit_scale, rotating, c.fine_rho, c.max_fine)
        ink = ink_pixels(p, fine.grid, center, angle, unit_scale, rotating)
        crowded[blind] = np.maximum(crowded, fine.crowded())[blind]
        poking[blind] = np.maximum(poking[blind], ink_off(fine, ink, blind))
    out = outside(p, xy, free) | (poking[free] > c.poke)
    crowded = crowded[free]
    jammed = ~out & (crowded > c.poke)
    # the most overlapped first: a pair's other unit is then often free where it is
    strays = np.concatenate([free[out], free[jammed][np.argsort(-crowded[jammed], kind="stable")]])
    if not len(strays):
        return moved
    lost = int(out.sum())   # strays[lost:] are jammed: moved while they still are
    if fine is None:
        fine = draw(p, center, angle, unit_scale, rotating, c.fine_rho, c.max_fine)
    # where each layer may go: inside, out of the shadow of the layers it rests on, and first
    # also short of the layers resting on it (given up where that finds no spot)
    rooms, mirrored = [fine.inside], np.zeros(len(fine.inside), bool)
    strata = strata_rooms(p, feet, fine)
    if strata is not None:
        below, beyond = strata
        rooms = [fine.inside & ~below & ~beyond, fine.inside & ~below]
        mirrored = beyond.any(1).cpu().numpy()
    inner = {}   # (room, layer) -> the room less its rim (``inset``), made when first needed
    rows, cols = fine.grid.shape
    rho = fine.grid.rho
    far = c.reach * math.hypot(rows, cols)
    for k, i in enumerate(strays):
        pix = fine.pixels(i)
        if not len(pix):
            continue
        lay = int(fine.layer[i])
        fine.lift(i)
        if k >= lost and float((fine.seen[lay, pix] > 0.5).float().mean()) <= c.poke:
            fine.put(i)   # the units moved before it freed it
            continue
        step = max(1, int(c.spacing * math.sqrt(len(pix) / math.pi)), int(far / c.across))
        spots = along(aside[i], far, step) if aside[i].any() else around(far, step)
        clear = fine.seen[lay] < 0.5
        best = None
        for r, room in enumerate(rooms[:1 + int(mirrored[lay])]):
            best = nearest_spot([(room[lay] & clear, pix)], (rows, cols), spots, c.chunk)
            if best is None and p.margin[i] > 0:
                # no room for its margins: its ink inside and its footprint on no other's
                # (the wall gives up its share of the gap), else its ink on no footprint (its
                # own share of the gap to its neighbours given up too)
                if ink is None:
                    ink = ink_pixels(p, fine.grid, center, angle, unit_scale, rotating)
                if (r, lay) not in inner:
                    inner[r, lay] = inset(room[lay], fine.grid.shape)
                core = inner[r, lay]
                for checks in ([(clear, pix), (core, ink(i))], [(core & clear, ink(i))]):
                    best = nearest_spot(checks, (rows, cols), spots, c.chunk)
                    if best is not None:
                        break
            if best is not None:
                break
        if best is not None:
            fine.move_lifted(i, *best)
            moved[i] = (best[1] / rho, best[0] / rho)
        fine.put(i)
    return moved


class Strays(Rule):
    """Once, after the last iteration of a layout that was not cancelled: a movable unit whose
    centre ended outside its container, with more than ``poke`` of its ink outside it, or
    with more than ``poke`` of its footprint under others, moves to the nearest free spot
    wholly inside it (``bring_back``), out of the shadow of the layers it rests on. Needed by
    any layout where a late step carries a small mark past the wall, neighbours press a long
    one partly out, or the budget ends with marks still jammed. Corpus, seeds 0-4, ink
    outside: small triangles piled on a slope (m070) 0.05 -> 0.00% (at seed 4 one ended
    wholly outside, 0.25%), thin bars in twin discs (m109) 0.08 -> 0.04%, thin bars around a
    point (m056) 0.11 -> 0.09%; pressed partly out: thin strands in a blob (m049) 0.85 ->
    0.22%, spirals under two points (m110) 0.11 -> 0.02%, PNG marks on a slope (m037) 0.09
    -> 0.03%; under others: snowflakes piled in a blob (m066) overlap 0.43 -> 0.06%, shapes
    through a neck under two points (m054) 1.11 -> 0.63%, thin bars in twin discs (m102)
    0.52 -> 0.10%. Where wide margins leave no such spot, the margin gives way before the
    ink: strands in a blob at margin 1.0 (m049) outside 0.22 -> 0% (each of seeds 0-4),
    snowflakes piled in a blob at margin 0.4 (m066) overlap 0.062 -> 0.024%, outside 0.11 ->
    0.05%, snowflakes in a pen with holes at margin 0.7 (m029) outside 0.004 -> 0.001%; its
    ink half a px in from the wall, PNG strata on a slope (seed 1, m069) 0.002 -> 0%. Marks
    of a curve emitter's band move along its normal: raindrops on a band in a thin V carried
    out by a point force (corpus seed 2, m083) outside 10.3 -> 0.02%, overlap 2.5 -> 0.06%;
    around lettering (seed 1, m103) outside 1.03 -> 0.05%. Marks too faint for the layout's
    raster are read on the fine one too: shapes on a curve in an ellipse (seed 2, m052)
    overlap 5.96 -> 0%, rings in a V band (seed 2, m092) 3.01 -> 0%, triangles in twin rings
    (seed 1, m089) 1.11 -> 0.10%. A jammed mark of a layer others rest on looks first for a
    spot short of them, strata in order: shapes in three strata under two points (seed 2,
    m085) 0.944 -> 0.983, snowflakes in four strata under a point (seed 0, m066) 0.973 ->
    0.987, PNG marks in three strata (seed 0, m007) 0.994 -> 1.000."""

    name = "strays"
    phase = "finish"
    reads = ("ctl", "place")
    writes = ("place",)
    Settings = StraysSettings

    def applies(self, s):
        return bool(s.p.regions)

    def __call__(self, s):
        if not self.applies(s):
            return False
        return shift(s.place, bring_back(s.p, s.place, s.ctl.unit_scale(), self.settings))
