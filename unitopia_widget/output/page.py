"""The exported page: the canvas with its title, caption and legend around it.

The canvas keeps its own coordinates (canvas px, origin top-left); what lies
beside it grows the SVG's ``viewBox`` (negative origin to the left and above).
``compose`` returns the ``viewBox`` and the SVG text drawn over the canvas.
"""
from __future__ import annotations

import textwrap
from dataclasses import dataclass
from xml.sax.saxutils import escape

from . import legend_draw
from .legend import CHAR_W

TITLE_FONT, CAPTION_FONT = 18, 12
GAP = 16   # px between the canvas and what is beside it
BORDER = 8  # px around a page that has a legend, title or caption


@dataclass
class Page:
    view: tuple[float, float, float, float]   # viewBox x, y, w, h
    overlay: str                               # SVG text drawn after the units


def compose(canvas, sections=None, position="right", title=None, caption=None) -> Page:
    """The page around a ``canvas`` (w, h): the legend ``sections`` at ``position``
    (None: no legend), the title above, the caption below."""
    w, h = canvas
    x0, y0, x1, y1 = 0.0, 0.0, float(w), float(h)
    parts = []
    if sections:
        _, lw, lh = legend_draw.render(sections, 0, 0, across=position in ("top", "bottom"))
        if position == "right":
            at = (w + GAP, 0.0)
        elif position == "left":
            at = (-GAP - lw, 0.0)
        elif position == "bottom":
            at = (0.0, h + GAP)
        elif position == "top":
            at = (0.0, -GAP - lh)
        else:
            at = tuple(position)
        block, _, _ = legend_draw.render(sections, *at, across=position in ("top", "bottom"))
        parts.append(block)
        x0, y0 = min(x0, at[0]), min(y0, at[1])
        x1, y1 = max(x1, at[0] + lw), max(y1, at[1] + lh)
    if title:   # centred over the canvas (the chart), not over the chart and its legend
        y0 -= TITLE_FONT + GAP
        parts.append(f'<text class="title" x="{w / 2:.1f}" y="{y0 + TITLE_FONT:.1f}" '
                     f'font-size="{TITLE_FONT}" font-weight="bold" font-family="sans-serif" '
                     f'fill="#222" text-anchor="middle">{escape(title)}</text>')
        half = legend_draw.text_width(title, TITLE_FONT, bold=True) / 2
        x0, x1 = min(x0, w / 2 - half), max(x1, w / 2 + half)
    if caption:
        per_line = max(20, int((x1 - x0) / (CAPTION_FONT * CHAR_W)))
        lines = textwrap.wrap(caption, per_line) or [caption]
        spans = "".join(f'<tspan x="{x0:.1f}" dy="{CAPTION_FONT * 1.3 if i else CAPTION_FONT:.1f}">'
                        f'{escape(line)}</tspan>' for i, line in enumerate(lines))
        parts.append(f'<text class="caption" x="{x0:.1f}" y="{y1 + GAP / 2:.1f}" '
                     f'font-size="{CAPTION_FONT}" font-family="sans-serif" fill="#444">{spans}</text>')
        y1 += GAP / 2 + CAPTION_FONT * 1.3 * len(lines) + GAP / 2
    if parts:   # a quiet border, so text never touches the page's edge
        x0, y0, x1, y1 = x0 - BORDER, y0 - BORDER, x1 + BORDER, y1 + BORDER
    return Page(view=(x0, y0, x1 - x0, y1 - y0), overlay="".join(parts))

