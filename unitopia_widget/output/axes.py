"""Axes of the position channels in the export (``axes=True``).

Each bound ``x=``/``y=`` of a layer (a ``layout.prepare.positions.Axis`` the layout
kept in ``result.axes``) is drawn as ``<g class="axis" data-channel="x|y"
data-layer=...>``: a line along the extent the values were mapped to, below
the container (x) or left of it (y) (above or right of it when the canvas leaves no
room there), ticks at round values (decades on a log
scale, dates for datetimes) or one label per band at its centre, and the
column's name at the end. Lines and text stay on the canvas.
"""
from __future__ import annotations

import math
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from .legend import date_label, round_dates
from .legend_draw import TEXT

FONT = 11          # px, tick labels
GAP = 6            # px between the container's edge and the axis line
TICK = 4           # px, tick length
ROOM = 3 * FONT    # px kept between the axis line and the canvas edge for the labels
MAX_LABEL = 16     # characters of a band label


def axes_svg(axes, canvas) -> str:
    """SVG of every distinct axis in ``axes`` on ``canvas`` (w, h)."""
    seen, out = set(), []
    for axis in axes:
        key = (axis.channel, axis.scale.column, round(axis.lo, 1), round(axis.hi, 1),
               round(axis.cross, 1))
        if key not in seen:
            seen.add(key)
            out.append(_axis(axis, canvas))
    return "".join(out)


def ticks(axis) -> list[tuple[float, str]]:
    """``[(fraction of the extent, label), ...]`` of an axis."""
    scale = axis.scale
    if scale.kind == "band":
        count = len(scale.domain)
        return [((k + 0.5) / count, _clip(str(v))) for k, v in enumerate(scale.domain)]
    lo, hi = scale.domain
    if scale.temporal:
        return [(_fraction(scale, t), date_label(t, hi - lo)) for t in round_dates(lo, hi, 5)]
    values = _decades(lo, hi) if scale.kind == "log" else _round(lo, hi)
    return [(_fraction(scale, v), f"{v:.6g}") for v in values]


def _fraction(scale, value: float) -> float:
    lo, hi = scale.domain
    f = (lambda v: math.log10(v)) if scale.kind == "log" else (lambda v: v)
    return 0.5 if hi <= lo else (f(value) - f(lo)) / (f(hi) - f(lo))


def _round(lo: float, hi: float, most: int = 6) -> list[float]:
    """3 to ``most`` round values (1, 2 or 5 times a power of ten apart) in [lo, hi]."""
    if not hi > lo:
        return [lo]
    top = int(math.floor(math.log10(hi - lo))) + 1
    for step in (m * 10.0 ** e for e in range(top, top - 4, -1) for m in (5, 2, 1)):
        values = np.arange(math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9) + 1) * step
        if 3 <= len(values) <= most:
            return [float(f"{v:.6g}") for v in values]
    return [lo, hi]


def _decades(lo: float, hi: float) -> list[float]:
    """Powers of ten in [lo, hi], with 2 and 5 times them when fewer than three decades."""
    e0, e1 = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    steps = (1,) if e1 - e0 >= 3 else (1, 2, 5)
    values = [m * 10.0 ** e for e in range(e0, e1 + 1) for m in steps]
    inside = [v for v in values if lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9)]
    return inside if len(inside) >= 2 else [lo, hi]


def _clip(text: str) -> str:
    return text if len(text) <= MAX_LABEL else text[:MAX_LABEL - 1] + "…"


def _n(v: float) -> str:
    return f"{float(v):.1f}"


def _axis(axis, canvas) -> str:
    w, h = canvas
    band = axis.scale.kind == "band"
    parts = []
    if axis.channel == "x":
        # below the container; above it when the canvas ends below and there is room above
        below = axis.cross + GAP <= h - ROOM or axis.far - GAP < ROOM
        y = min(axis.cross + GAP, h - ROOM) if below else axis.far - GAP - ROOM
        parts.append(f'<line stroke="#555" x1="{_n(axis.lo)}" y1="{_n(y)}" x2="{_n(axis.hi)}" y2="{_n(y)}"/>')
        for t, label in ticks(axis):
            x = float(axis.at(t))
            if not band:
                parts.append(f'<line stroke="#555" x1="{_n(x)}" y1="{_n(y)}" x2="{_n(x)}" y2="{_n(y + TICK)}"/>')
            parts.append(f'<text x="{_n(x)}" y="{_n(y + TICK + FONT)}" font-size="{FONT}" '
                         f'text-anchor="middle" {TEXT}>{escape(label)}</text>')
        parts.append(f'<text x="{_n(axis.hi)}" y="{_n(y + TICK + 2.2 * FONT)}" font-size="{FONT}" '
                     f'text-anchor="end" font-weight="bold" {TEXT}>{escape(_clip(axis.scale.column))}</text>')
    else:
        # left of the container, its labels before it; right of it when the canvas leaves
        # no room on the left and does on the right
        left = axis.cross - GAP >= 2 * ROOM or axis.far + GAP > w - 2 * ROOM
        x = max(axis.cross - GAP, 2 * ROOM) if left else axis.far + GAP
        side, anchor = (-1, "end") if left else (1, "start")
        parts.append(f'<line stroke="#555" x1="{_n(x)}" y1="{_n(axis.lo)}" x2="{_n(x)}" y2="{_n(axis.hi)}"/>')
        for t, label in ticks(axis):
            y = float(axis.at(t))
            if not band:
                parts.append(f'<line stroke="#555" x1="{_n(x + side * TICK)}" y1="{_n(y)}" x2="{_n(x)}" y2="{_n(y)}"/>')
            parts.append(f'<text x="{_n(x + side * (TICK + 2))}" y="{_n(y + FONT / 3)}" font-size="{FONT}" '
                         f'text-anchor="{anchor}" {TEXT}>{escape(label)}</text>')
        parts.append(f'<text x="{_n(x)}" y="{_n(max(axis.lo - FONT, FONT))}" font-size="{FONT}" '
                     f'text-anchor="middle" font-weight="bold" {TEXT}>{escape(_clip(axis.scale.column))}</text>')
    return (f'<g class="axis" data-channel="{axis.channel}" data-layer={quoteattr(axis.layer)} '
            '>' + "".join(parts) + "</g>")
