"""Axes of the position channels in the export (``axes=True``).

Each bound ``x=``/``y=`` of a layer (a ``layout.prepare.positions.Axis`` the layout
kept in ``result.axes``) is drawn as ``<g class="axis" data-channel="x|y"
data-layer=...>``: a line along the extent the values were mapped to, below the
container and its layer's marks (x) or left of them (y), ticks at round values
whose labels do not touch (decades on a log scale, dates for datetimes) or one
label per band at its centre, and the column's name: at the right end under the
x axis, above the y axis on its left. Axes lie outside the marks; the page grows
around them (``axes_svg`` returns their bounding box).
"""
from __future__ import annotations

import math
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from .legend import date_ticks, round_values, spaced_ticks
from .legend_draw import TEXT
from .text import fit, text_width

FONT = 11          # px, tick labels
GAP = 6            # px between the marks (or the container's edge) and the axis line
TICK = 4           # px, tick length
MAX_LABEL = 16     # characters of a band label on a y axis
MOST_TICKS = 6     # numeric ticks on an axis at most
DESCENT = 0.3      # of a font size, below a label's baseline


def axes_svg(axes, marks: dict) -> tuple[str, tuple | None]:
    """``(svg, box)``: every distinct axis in ``axes``, and the box ``(x0, y0, x1, y1)``
    (canvas px) they take (None without axes). ``marks``: layer name -> ``(k, 4)`` boxes
    ``x0, y0, x1, y1`` of its placed marks (canvas px). Layers that share an axis (the
    layers ``by=`` or a colour made over one extent) have it drawn once, clear of all
    their marks."""
    shared = {}
    for axis in axes:
        key = (axis.channel, axis.scale.column, round(axis.lo, 1), round(axis.hi, 1),
               round(axis.cross, 1))
        shared.setdefault(key, []).append(axis)
    out, boxes = [], []
    for group in shared.values():
        layers = dict.fromkeys(a.layer for a in group)
        clear = np.concatenate([np.zeros((0, 4)), *(marks.get(name, np.zeros((0, 4)))
                                                    for name in layers)])
        svg, box = _axis(group[0], clear)
        out.append(svg)
        boxes.append(box)
    if not boxes:
        return "", None
    b = np.array(boxes)
    return "".join(out), (b[:, 0].min(), b[:, 1].min(), b[:, 2].max(), b[:, 3].max())


def ticks(axis) -> list[tuple[float, str]]:
    """``[(fraction of the extent, label), ...]`` of an axis: on an x axis as many round
    values as keep their labels apart, on a y axis one per two label heights."""
    scale = axis.scale
    length = abs(axis.hi - axis.lo)
    if scale.kind == "band":
        count = len(scale.domain)
        room = length / count - 2 * TICK   # a label stays within its band on an x axis
        return [((k + 0.5) / count, fit(str(v), room, FONT) if axis.channel == "x" else _clip(str(v)))
                for k, v in enumerate(scale.domain)]
    lo, hi = scale.domain
    if scale.kind == "log":
        return [(_fraction(scale, v), f"{v:.6g}") for v in _decades(lo, hi)]
    if axis.channel == "y":
        most = max(2, min(MOST_TICKS, int(length / (2 * FONT))))
        picked = (date_ticks(lo, hi, most) if scale.temporal else
                  [(v, f"{v:.6g}") for v in round_values(lo, hi, most, positive=False)])
    else:
        picked = spaced_ticks(lo, hi, scale.temporal, length, MOST_TICKS, FONT,
                              lambda v: _fraction(scale, v))
    return [(_fraction(scale, v), label) for v, label in picked]


def _fraction(scale, value: float) -> float:
    lo, hi = scale.domain
    f = (lambda v: math.log10(v)) if scale.kind == "log" else (lambda v: v)
    return 0.5 if hi <= lo else (f(value) - f(lo)) / (f(hi) - f(lo))


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


def _axis(axis, marks: np.ndarray) -> tuple[str, tuple]:
    """The SVG of one axis, clear of ``marks`` (``(k, 4)`` boxes), and its box."""
    band = axis.scale.kind == "band"
    parts = []
    title = _clip(axis.scale.column)
    span_lo, span_hi = min(axis.lo, axis.hi), max(axis.lo, axis.hi)
    if axis.channel == "x":   # under the container and every mark of the layer
        y = max([axis.cross, *marks[:, 3]]) + GAP
        parts.append(f'<line stroke="#555" x1="{_n(axis.lo)}" y1="{_n(y)}" x2="{_n(axis.hi)}" y2="{_n(y)}"/>')
        x0, x1 = span_lo, span_hi
        for t, label in ticks(axis):
            x = float(axis.at(t))
            if not band:
                parts.append(f'<line stroke="#555" x1="{_n(x)}" y1="{_n(y)}" x2="{_n(x)}" y2="{_n(y + TICK)}"/>')
            parts.append(f'<text x="{_n(x)}" y="{_n(y + TICK + FONT)}" font-size="{FONT}" '
                         f'text-anchor="middle" {TEXT}>{escape(label)}</text>')
            half = text_width(label, FONT) / 2
            x0, x1 = min(x0, x - half), max(x1, x + half)
        base = y + TICK + 2.2 * FONT
        parts.append(f'<text x="{_n(span_hi)}" y="{_n(base)}" font-size="{FONT}" '
                     f'text-anchor="end" font-weight="bold" {TEXT}>{escape(title)}</text>')
        x0 = min(x0, span_hi - text_width(title, FONT, bold=True))
        box = (x0, y, x1, base + DESCENT * FONT)
    else:   # left of the container and every mark of the layer, its labels before it
        x = min([axis.cross, *marks[:, 0]]) - GAP
        parts.append(f'<line stroke="#555" x1="{_n(x)}" y1="{_n(axis.lo)}" x2="{_n(x)}" y2="{_n(axis.hi)}"/>')
        widest = 0.0
        for t, label in ticks(axis):
            y = float(axis.at(t))
            if not band:
                parts.append(f'<line stroke="#555" x1="{_n(x - TICK)}" y1="{_n(y)}" x2="{_n(x)}" y2="{_n(y)}"/>')
            parts.append(f'<text x="{_n(x - TICK - 2)}" y="{_n(y + FONT / 3)}" font-size="{FONT}" '
                         f'text-anchor="end" {TEXT}>{escape(label)}</text>')
            widest = max(widest, text_width(label, FONT))
        base = span_lo - FONT   # the title above the top label, on the axis' side
        parts.append(f'<text x="{_n(x)}" y="{_n(base)}" font-size="{FONT}" '
                     f'text-anchor="end" font-weight="bold" {TEXT}>{escape(title)}</text>')
        left = min(x - TICK - 2 - widest, x - text_width(title, FONT, bold=True))
        box = (left, base - FONT, x, span_hi + FONT / 3 + DESCENT * FONT)
    return (f'<g class="axis" data-channel="{axis.channel}" data-layer={quoteattr(axis.layer)} '
            '>' + "".join(parts) + "</g>"), box
