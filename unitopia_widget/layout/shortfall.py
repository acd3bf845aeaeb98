"""What a layout could not give, said after the solve: an open container whose marks do not
reach the fill asked of it, and a closed container left empty because its largest mark caps
the scale or because its marks are tied to an emitter's curve too short to hold them. Read
from the final scales (``Result.unit_scale``) and, for a capped scale, from where the marks
ended; warnings only, nothing moves."""
from __future__ import annotations

import math
import warnings

import numpy as np

from ..design.encodings import footprint
from ..design.sharing import by_container
from .prepare.fit import layer_cap
from .prepare.lattice import container_region
from .prepare.pack import thin
from .prepare.scale import DEFAULT_OPEN_FILL, MAX_COVER, widest_disc, scale_cap
from .prepare.start import footprint_radius
from .step.distance import edt
from .step.strata import sweep_of

SHORT = 0.85      # an open fill whose marks' ink covers under this share of the ask is warned
#                   (the bound is 0.8; ink that pokes out or overlaps costs a little more)
EMPTY = 0.5       # a closed container whose footprints cover under this share is left empty
#                   (a full one's cover most of it: discs pack into about 0.9)
CAPPED = 0.8      # a final scale at least this share of a layer's cap (its longest mark in the
#                   container's widest disc, or where its largest marks no longer fit at
#                   their angle: ``fit.layer_cap``, the fill controller's ceiling) is held by
#                   that mark
OUTLIER = 3.0     # the capping mark's long side over the median mark's: one mark, not the band
LEFT_EMPTY = 0.25  # a capped container with more than this share farther than a median mark's
#                    radius from every mark is left empty (footprint area alone misreads thin
#                    marks: strands on a height_range= cover 31% of a container they leave full)
SEEN = 300.0      # raster px along the canvas's long side that the share left empty is read on
STACK = 4         # warnings point at the user's call: warn_* <- warn_shortfalls <- Chart.layout <- it
FREE_HELP = "use CurveEmitter(mode='free') so that the curve only places the marks"


def warn_shortfalls(units, layers, canvas, result, df) -> None:
    """Every warning of this module for a layout of ``units`` ended as ``result`` (a
    ``solver.Result``: its final scales, centres and angles); ``df``: the rows, by index label
    (``warn_capped_scale``)."""
    warn_unreached_fill(units, layers, canvas, result.unit_scale)
    warn_capped_scale(units, layers, canvas, result, df)
    warn_curve_held(units, layers, canvas, result.unit_scale)


def emptied(units, layers, canvas, unit_scale: np.ndarray):
    """Each closed container whose marks' footprints, at ``unit_scale (N,)``, cover under
    ``EMPTY`` of it: ``(members, mine (N,) bool, covered, full)``, its layers, their units,
    the share covered and the px per unit side at which the footprints would cover
    ``MAX_COVER`` of it."""
    foot = units.area * footprint(units.margin) ** 2
    for members in by_container(layers, lambda layer: layer.boundary == "closed"):
        mine = np.isin(units.layer, members)
        area = layers[members[0]].region.area(canvas)
        covered = float((foot[mine] * unit_scale[mine] ** 2).sum()) / area
        if covered < EMPTY:
            yield members, mine, covered, math.sqrt(MAX_COVER * area / float(foot[mine].sum()))


def warn_unreached_fill(units, layers, canvas, unit_scale: np.ndarray) -> None:
    """Warn for each open container whose marks, at their final scales ``unit_scale (N,)``,
    cover under ``SHORT`` of the fill asked of it (its first layer's ``fill=``, else the
    default): the fill it was laid out at, why (the container's widest part against the
    largest mark, the footprints' and margins' share of it, a curve that holds the marks,
    layers resting in strata, the shrink that cleared the overlaps) and what would help."""
    for members in by_container(layers, lambda layer: layer.boundary == "open"):
        asked = next((layers[i].fill for i in members if layers[i].fill is not None),
                     DEFAULT_OPEN_FILL)
        mine = np.isin(units.layer, members)
        area = layers[members[0]].region.area(canvas)
        covered = float((units.area[mine] * unit_scale[mine] ** 2).sum()) / area
        if covered >= SHORT * asked:
            continue
        at_ask = math.sqrt(asked * area / float(units.area[mine].sum()))   # px per unit side
        why, margin = [], float(np.median(units.margin[mine]))
        longest = 2 * float(np.max(np.maximum(units.half_w[mine], units.half_h[mine]))) * at_ask
        wide = 2 * widest_disc(layers[members[0]].region, canvas)
        if longest > 0.95 * wide:
            why.append(f"the container is {wide:.0f} px across at its widest and the largest "
                       f"mark would be {longest:.0f} px long")
        discs = float((math.pi * footprint_radius(units)[mine] ** 2).sum()) * at_ask ** 2 / area
        slender = thin(units.half_w[mine], units.half_h[mine]).mean() > 0.5
        if discs > MAX_COVER and not slender:
            with_margin = f", margin={margin:g} included" if margin > 0 else ""
            why.append(f"the marks' footprints (the discs they pack as{with_margin}) would cover "
                       f"{discs:.0%} of it, and discs pack into at most {MAX_COVER:.0%}")
        if slender:
            why.append("long thin marks jam across each other before they pack side by side")
        held = held_by_curve(units, layers, members, at_ask)
        if held:
            why.append(held)
        resting = [layers[i].name for i in members if layers[i].blocks
                   and sweep_of(layers[i].forces) is not None]
        if resting:
            rest = (("layers", "rest", "they block") if len(resting) > 1
                    else ("layer", "rests", "it blocks"))
            why.append(f"{rest[0]} {', '.join(map(repr, resting))} {rest[1]} on the layers "
                       f"{rest[2]} on, in strata: a stratum's marks do not sift into the "
                       "gaps of the one below, so strata pack looser than one layer")
        size = math.sqrt(covered / asked)
        drawn = f"the marks were drawn at {size:.0%} of the size that fill asks, where they " \
            f"neither overlap nor poke out"
        because = f"{'; '.join(why)}; so {drawn}" if why else drawn
        names = ("layers " if len(members) > 1 else "layer ") + \
            ", ".join(repr(layers[i].name) for i in members)
        helps = [f"lower fill= (to about {covered:.2g})"] + (["lower margin="] if margin > 0 else []) \
            + ([FREE_HELP] if held else []) + ["give the marks a wider container",
                                                "or use boundary='closed' to fill it as far as they pack"]
        helps = ", ".join(helps)
        warnings.warn(f"{names}: fill={asked:g} is more than its marks reach in the container; "
                      f"laid out at fill={covered:.2g}: {because}. {helps[0].upper()}{helps[1:]}",
                      stacklevel=STACK)


def held_by_curve(units, layers, members, scale: float) -> str | None:
    """Why marks of the layers ``members`` tied to their emitter's curve (mode "line" or
    "band": they keep their order along it) stay small: end to end at ``scale`` (px per
    unit side: the size their container asks), their footprints would need more than the
    curve's length (layers on one curve together); None where every curve holds its marks."""
    curves = {}   # (the curve's points, mode) -> (length, layer names, px the marks need)
    radius = footprint_radius(units)
    for i in members:
        emitter = layers[i].emitter
        if getattr(emitter, "mode", "free") == "free":
            continue
        key = (emitter.curve.points.tobytes(), emitter.mode)
        length, names, need = curves.get(key, (emitter.curve.length, [], 0.0))
        need += 2 * float(radius[units.layer == i].sum()) * scale
        curves[key] = (length, names + [repr(layers[i].name)], need)
    held = [f"the marks of layer{'s' * (len(names) > 1)} {', '.join(names)} are tied to "
            f"{'their' if len(names) > 1 else 'its'} emitter's curve (mode={mode!r}), "
            f"{length:.0f} px long, which holds them end to end only at {length / need:.0%} "
            f"of that size" for (_, mode), (length, names, need) in curves.items() if need > length]
    return "; ".join(held) or None


def warn_curve_held(units, layers, canvas, unit_scale: np.ndarray) -> None:
    """Warn for each closed container whose marks' footprints, at their final scales
    ``unit_scale (N,)``, cover under ``EMPTY`` of it while some of them are tied to a curve
    too short to hold them end to end at the size that would fill it (``held_by_curve``)."""
    for members, _, covered, full in emptied(units, layers, canvas, unit_scale):
        held = held_by_curve(units, layers, members, full)
        if held:
            warnings.warn(f"the marks cover {covered:.0%} of their closed container: {held}. "
                          f"{FREE_HELP[0].upper()}{FREE_HELP[1:]}, or give it a longer curve",
                          stacklevel=STACK)


def warn_capped_scale(units, layers, canvas, result, df) -> None:
    """Warn for each closed container (its scale grown by the solver) left empty (its
    footprints cover under ``EMPTY`` of it, and more than ``LEFT_EMPTY`` of it is far from
    every mark where ``result`` left them) because one mark, ``OUTLIER`` times the median or
    longer, holds the scale at its cap: the row, its value in the bound size channels (from
    ``df``, the rows by index label), the sizes drawn, and the ``*_range=`` that would help."""
    unit_scale = result.unit_scale
    for members, mine, covered, _ in emptied(units, layers, canvas, unit_scale):
        if any(layers[i].fill is not None for i in members):
            continue   # a fixed scale: the fill asked for, not a cap
        empty = None   # read once per container, when a capping mark is found
        long = 2 * np.maximum(units.half_w, units.half_h) * unit_scale   # px
        for i in members:
            at = units.layer == i
            cap = scale_cap(units, layers, canvas, i)
            if unit_scale[at][0] < CAPPED * cap:   # held where its largest marks stop fitting?
                cap = min(cap, layer_cap(units, layers[i], canvas, i))
            if unit_scale[at][0] < CAPPED * cap:
                continue
            j = int(np.flatnonzero(at)[np.argmax(long[at])])
            median = float(np.median(long[mine]))
            if long[j] < OUTLIER * median:
                continue
            if empty is None:
                empty = left_empty(units, mine, layers[i].region, canvas, result)
            if empty <= LEFT_EMPTY:
                continue
            row = units.rows[j]
            bound = [(c, layers[i].encodings[c]) for c in ("size", "width", "height")
                     if isinstance(layers[i].encodings[c], str)]
            values = ", ".join(f"{c}={_shown(df.loc[row, col])}" for c, col in bound)
            ranges = " or ".join(f"{c}_range=(min_px, max_px)" for c, _ in bound) or \
                "size_range=, width_range= or height_range="
            warnings.warn(f"layer {layers[i].name!r}: row {row!r}"
                          f"{f' ({values})' if values else ''} is the largest mark and caps "
                          f"the scale: {long[j]:.0f} px long, the most the container holds, "
                          f"{long[j] / median:.0f}x the median mark "
                          f"({median:.2g} px), so the marks cover {covered:.0%} of the closed "
                          f"container and leave {empty:.0%} of it empty. Map the column onto a "
                          f"range of drawn sizes ({ranges}), bind a log-scaled column "
                          f"(np.log1p), or leave the row out", stacklevel=STACK)


def left_empty(units, mine: np.ndarray, container, canvas, result) -> float:
    """The share of ``container`` farther than the median mark's ink radius from every mark
    ``mine (N,) bool`` where ``result`` left it (``center``, ``angle`` degrees, ``unit_scale``):
    each mark drawn as its box shrunk to the area of its ink, on a raster of ``SEEN`` px
    along the canvas's long side."""
    rho = min(1.0, SEEN / max(canvas))
    inside = container_region(container, canvas, rho).inside
    h, w = inside.shape
    ink = np.zeros((h, w), bool)
    shrink = np.sqrt(np.minimum(units.fill_fraction[mine], 1.0)) * result.unit_scale[mine] * rho
    half = np.stack([units.half_w[mine], units.half_h[mine]], 1) * shrink[:, None]
    for (x, y), a, (u, v) in zip(result.center[mine] * rho, np.radians(result.angle[mine]),
                                 np.maximum(half, 0.5)):
        reach = math.hypot(u, v)
        i0, i1 = max(int(y - reach), 0), min(int(y + reach) + 2, h)
        j0, j1 = max(int(x - reach), 0), min(int(x + reach) + 2, w)
        if i0 >= i1 or j0 >= j1:
            continue
        dy, dx = np.ogrid[i0:i1, j0:j1]
        dx, dy = dx + 0.5 - x, dy + 0.5 - y
        along, across = dx * math.cos(a) + dy * math.sin(a), dy * math.cos(a) - dx * math.sin(a)
        ink[i0:i1, j0:j1] |= (np.abs(along) <= u) & (np.abs(across) <= v)
    if not ink.any():
        return 1.0
    radius = math.sqrt(float(np.median(units.area[mine] * result.unit_scale[mine] ** 2)) / math.pi)
    return float((inside & (edt(~ink) > radius * rho)).sum()) / max(int(inside.sum()), 1)


def _shown(value) -> str:
    """A cell of the data as the warning shows it: numbers to 4 significant digits."""
    return f"{value:.4g}" if isinstance(value, (int, float, np.number)) else repr(value)
