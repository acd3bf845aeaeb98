"""The exported page: the chart with its title, caption and legend laid out around it.

The canvas keeps its own coordinates (canvas px, origin top-left); the chart is the
canvas and what the export draws beside it (the axes); what lies around the chart
grows the SVG's ``viewBox`` (negative origin to the left and above). The title stands
over the chart (over a top legend), the caption right under the chart, wrapped to its
width (under it, a bottom legend), a side legend beside chart and caption: no block
overlaps another. ``compose`` returns the ``viewBox`` and the SVG text drawn over the
canvas.
"""
from __future__ import annotations

from dataclasses import dataclass
from xml.sax.saxutils import escape

from . import legend_draw
from .text import text_width

TITLE_FONT, CAPTION_FONT = 18, 12
GAP = 16   # px between the chart and what is beside it
BORDER = 8  # px around a page that has a legend, title or caption
LINE = 1.3  # caption line height, in font sizes


@dataclass
class Page:
    view: tuple[float, float, float, float]   # viewBox x, y, w, h
    overlay: str                               # SVG text drawn after the units


def compose(canvas, sections=None, position="right", title=None, caption=None,
            chart_box=None) -> Page:
    """The page around a ``canvas`` (w, h): the legend ``sections`` at ``position``
    (None: no legend), the title above, the caption below. ``chart_box``: ``(x0, y0, x1,
    y1)`` canvas px of what is drawn beside the canvas (the axes), or None."""
    w, h = canvas
    cx0, cy0, cx1, cy1 = 0.0, 0.0, float(w), float(h)
    if chart_box is not None:
        cx0, cy0 = min(cx0, chart_box[0]), min(cy0, chart_box[1])
        cx1, cy1 = max(cx1, chart_box[2]), max(cy1, chart_box[3])
    x0, y0, x1, y1 = cx0, cy0, cx1, cy1
    parts = []
    across = position in ("top", "bottom")
    legend = None   # the legend's (x, y, w, h)
    if sections:
        _, lw, lh = legend_draw.render(sections, 0, 0, across=across)
        if position == "right":
            legend = (cx1 + GAP, cy0, lw, lh)
        elif position == "left":
            legend = (cx0 - GAP - lw, cy0, lw, lh)
        elif position == "top":
            legend = (cx0, cy0 - GAP - lh, lw, lh)
        elif position != "bottom":   # [x, y]: where the user put it
            legend = (float(position[0]), float(position[1]), lw, lh)
    under = cy1   # the caption's top: under the chart, and under a legend placed over it
    if legend is not None:
        lx, ly, lw, lh = legend
        if lx < cx1 and lx + lw > cx0:
            under = max(under, ly + lh)
    if caption:
        lines = wrap(caption, cx1 - cx0, CAPTION_FONT)
        top = under + GAP / 2
        spans = "".join(f'<tspan x="{cx0:.1f}" dy="{CAPTION_FONT * LINE if i else CAPTION_FONT:.1f}">'
                        f'{escape(line)}</tspan>' for i, line in enumerate(lines))
        parts.append(f'<text class="caption" x="{cx0:.1f}" y="{top:.1f}" '
                     f'font-size="{CAPTION_FONT}" font-family="sans-serif" fill="#444">{spans}</text>')
        under = top + CAPTION_FONT * LINE * len(lines)
        x1 = max(x1, cx0 + max(text_width(line, CAPTION_FONT) for line in lines))
        y1 = max(y1, under)
    if sections:
        if legend is None:   # bottom: under the chart and its caption
            legend = (cx0, under + GAP, lw, lh)
        lx, ly, lw, lh = legend
        block, _, _ = legend_draw.render(sections, lx, ly, across=across)
        parts.append(block)
        x0, y0 = min(x0, lx), min(y0, ly)
        x1, y1 = max(x1, lx + lw), max(y1, ly + lh)
    if title:   # centred over the chart, not over the chart and its legend
        y0 -= TITLE_FONT + GAP
        mid = (cx0 + cx1) / 2
        parts.append(f'<text class="title" x="{mid:.1f}" y="{y0 + TITLE_FONT:.1f}" '
                     f'font-size="{TITLE_FONT}" font-weight="bold" font-family="sans-serif" '
                     f'fill="#222" text-anchor="middle">{escape(title)}</text>')
        half = text_width(title, TITLE_FONT, bold=True) / 2
        x0, x1 = min(x0, mid - half), max(x1, mid + half)
    if parts or chart_box is not None:   # a quiet border: text never touches the edge
        x0, y0, x1, y1 = x0 - BORDER, y0 - BORDER, x1 + BORDER, y1 + BORDER
    return Page(view=(x0, y0, x1 - x0, y1 - y0), overlay="".join(parts))


def wrap(text: str, width: float, size: float) -> list[str]:
    """``text`` broken at spaces into lines at most ``width`` px wide at ``size`` px (a
    word wider than that on a line of its own)."""
    lines: list[str] = []
    for word in text.split():
        if lines and text_width(f"{lines[-1]} {word}", size) <= width:
            lines[-1] = f"{lines[-1]} {word}"
        else:
            lines.append(word)
    return lines or [text]
