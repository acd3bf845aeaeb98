"""Fit caps: the largest scale at which a closed layer's largest marks still fit their
container, each by its own shape at its own angle.

The fill controller grows a closed container's scale while there is room. One mark much
larger than the rest (an outlier of the size column) may then outgrow every place in the
container long before the room is gone, and poke out whatever the layout does: snowflakes
filling the region around lettering, the largest 6x the median, were grown 13% past the
scale at which that flake fits anywhere, and ended 0.85% of the ink outside. The cap is
where the mark's silhouette, slid over the container raster, still finds a place with no
ink outside (``fits``); the controller grows no scale past it (``rules.fill_scale``).
Corpus: lettering at corpus seeds 2 and 3, outside 0.77 / 0.85 -> 0.07 / 0.005%, empty 5.5
/ 15.5 -> 14.9 / 32.1%; leaves with Pareto sizes in a V band (m008), outside 0.41 -> 0.01%,
empty 40.6 -> 48.5%; nothing else moved at corpus seed 0.

Only marks at a fixed angle are capped: a mark that turns (``rotate=True``, ``"to_center"``,
``"along_emitter"``, drawn angles) may fit a band lengthwise at an angle not tried here.
The widest disc bounds which marks need the test at all: a mark whose box fits inside it
fits anywhere the disc does, at any angle.
"""
from __future__ import annotations

import math

import numpy as np
from scipy import ndimage, signal

from ...design.scene import random_range
from .lattice import container_region, start_rho
from .start import layer_angle

GROW = 2.0           # the bracket's step past a scale at which the mark fits
BRACKET = 5          # the most steps the bracket takes
BISECT = 8           # halvings of the bracket (log scale: under 0.3% of the scale)


def fixed_angle(layer) -> float | None:
    """The angle (radians) every mark of ``layer`` keeps (the start's, ``start.layer_angle``),
    or None where its marks may turn or draw their own angles."""
    angle, turnable = layer_angle(layer)
    return None if turnable or random_range(layer.orientation) is not None else angle


def ink_at(mark, half_w: float, half_h: float, scale: float, rho: float,
           angle: float) -> np.ndarray:
    """Bool ``(h, w)``: where ``mark`` (box half sides ``half_w``, ``half_h`` canvas px at
    scale 1) has ink drawn at ``scale``, turned by ``angle`` radians clockwise, on a raster
    of ``rho`` px per canvas px."""
    side = max(int(round(2 * max(half_w, half_h) * scale * rho)), 1)
    if abs(angle) <= 1e-9:
        return mark.silhouette(side) >= 0.5
    # turned at twice the resolution, then any ink in a pixel counts: turning rounds off
    # sharp corners by about a pixel
    ink = ndimage.rotate(mark.silhouette(2 * side) >= 0.5, -math.degrees(angle), reshape=True,
                         order=0)
    ink = np.pad(ink, ((0, ink.shape[0] % 2), (0, ink.shape[1] % 2)))
    return ink.reshape(ink.shape[0] // 2, 2, ink.shape[1] // 2, 2).any(axis=(1, 3))


def fits(outside: np.ndarray, ink: np.ndarray) -> bool:
    """Whether ``ink (h, w)`` has a place on the canvas raster ``outside (H, W)`` (1 where
    the container is not) where none of it is outside: the sum of ``outside`` under the
    ink, at every place on the canvas, is 0 at the least."""
    if ink.shape[0] > outside.shape[0] or ink.shape[1] > outside.shape[1]:
        return False
    under = signal.fftconvolve(outside, ink[::-1, ::-1].astype(np.float32), mode="valid")
    return float(under.min()) < 0.5


def fit_scale(region, outside: np.ndarray, mark, half_w: float, half_h: float,
              angle: float) -> float:
    """The largest scale at which ``mark`` (half sides at scale 1) fits ``region`` (its
    ``outside`` raster): bracketed up from the scale at which its box's corners reach the
    widest disc's rim, then bisected on the log scale (a mark fits at every scale under its
    cap, but for a few raster px)."""
    rho = region.rho
    lo = float(region.depth.max()) / math.hypot(half_w, half_h)

    def ok(scale):
        return fits(outside, ink_at(mark, half_w, half_h, scale, rho, angle))
    if not ok(lo):
        return lo
    hi = lo * GROW
    for _ in range(BRACKET):
        if not ok(hi):
            break
        lo, hi = hi, hi * GROW
    else:
        return lo
    for _ in range(BISECT):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


def layer_cap(units, layer, canvas, i: int) -> float:
    """The largest scale at which every mark of layer ``i`` (at its fixed angle) fits its
    container: ``inf`` where its marks turn, or where even their ink filling the whole
    container leaves each inside the widest disc. Tested per mark shape (sprite): the unit
    widest and the one tallest."""
    angle = fixed_angle(layer)
    mine = np.flatnonzero(units.layer == i)
    if angle is None or len(mine) == 0:
        return math.inf
    region = container_region(layer.region, canvas, start_rho(canvas))   # made for the start
    widest = float(region.depth.max())
    full = math.sqrt(region.area / float(units.area[mine].sum()))   # ink covering it all
    corner = np.hypot(units.half_w, units.half_h)
    outside = (~region.inside).astype(np.float32)
    cap = math.inf
    for sprite in np.unique(units.sprite[mine]):
        own = mine[units.sprite[mine] == sprite]
        for j in {int(own[np.argmax(units.half_w[own])]), int(own[np.argmax(units.half_h[own])])}:
            if corner[j] * min(full, cap) > widest:
                cap = min(cap, fit_scale(region, outside, units.sprites[sprite],
                                         float(units.half_w[j]), float(units.half_h[j]), angle))
    return cap


def group_caps(units, layers, canvas, scale_group: np.ndarray, group_free: np.ndarray) -> np.ndarray:
    """``(G,)`` the largest scale the fill controller may grow each controlled group to: the
    least ``layer_cap`` of its closed layers (``inf`` for fixed groups and where none caps)."""
    caps = np.full(len(group_free), math.inf)
    for i, layer in enumerate(layers):   # a controlled group's layers are all closed, no fill=
        g = int(scale_group[i])
        if group_free[g]:
            caps[g] = min(caps[g], layer_cap(units, layer, canvas, i))
    return caps
