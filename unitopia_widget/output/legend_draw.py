"""Draw legend ``Section``s (legend.py) as one ``<g class="legend">`` SVG block.

``render(sections, x, y, across)`` returns ``(svg_text, width, height)``: the block
with its top-left corner at canvas (x, y); sections stacked top to bottom, or side
by side when ``across`` (legends above or below the canvas). Marks are ``<use>``s
of definitions in the block's own ``<defs>`` (ids ``legend-d<k>``).
"""
from __future__ import annotations

from xml.sax.saxutils import escape, quoteattr

from ..design.encodings import SEQUENTIAL
from .legend import BAR, FONT, PAD, TITLE_FONT
from .text import text_width

TEXT = 'font-family="sans-serif" fill="#222"'


def _n(v: float) -> str:
    s = f"{float(v):.3f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


class _Defs:
    """One definition per (mark, colour) drawn in the legend."""

    def __init__(self):
        self.ids, self.parts = {}, []

    def use(self, mark, color, x, y, w, h) -> str:
        key = (id(mark), color)
        if key not in self.ids:
            self.ids[key] = f"legend-d{len(self.ids)}"
            self.parts.append(mark.svg_fragment(self.ids[key], color))
        bw, bh = mark.box_size
        return (f'<use class="legend-mark" href="#{self.ids[key]}" transform="translate({_n(x)} '
                f'{_n(y)}) scale({w / bw:.6g} {h / bh:.6g})"/>')


def _bar(span, ticks, defs: _Defs, x0: float, y: float) -> tuple[list[str], float, float]:
    """A colour bar over ``span`` (lo, hi) with ``ticks`` at canvas (x0, y), moved right as
    far as its first label reaches left of it: ``(parts, width, y below its labels)``."""
    lo, hi = span
    bw, bh = BAR
    at = [(0.0 if hi <= lo else (float(e.value) - lo) / (hi - lo)) * bw for e in ticks]
    half = [text_width(e.label) / 2 for e in ticks]
    left = max([h - x for x, h in zip(at, half)] + [0.0])
    right = max([x + h - bw for x, h in zip(at, half)] + [0.0])
    x0 += left
    gid = f"legend-bar{len(defs.parts)}"
    stops = "".join(f'<stop offset="{i / (len(SEQUENTIAL) - 1):.4g}" stop-color="{c}"/>'
                    for i, c in enumerate(SEQUENTIAL))
    defs.parts.append(f'<linearGradient id="{gid}">{stops}</linearGradient>')
    out = [f'<rect class="legend-bar" x="{_n(x0)}" y="{_n(y)}" width="{bw}" height="{bh}" '
           f'fill="url(#{gid})"/>']
    for e, x in zip(ticks, at):
        tx = x0 + x
        out.append(f'<g class="legend-entry" data-channel="color" data-value={quoteattr(e.value)}>'
                   f'<line x1="{_n(tx)}" y1="{_n(y)}" x2="{_n(tx)}" y2="{_n(y + bh + 3)}" '
                   f'stroke="#222"/><text x="{_n(tx)}" y="{_n(y + bh + 4 + FONT)}" '
                   f'font-size="{FONT}" text-anchor="middle" {TEXT}>{escape(e.label)}</text></g>')
    return out, left + bw + right, y + bh + 4 + FONT


def _section(sec, defs: _Defs, x0: float, y0: float) -> tuple[list[str], float, float]:
    out = [f'<text class="legend-title" x="{_n(x0)}" y="{_n(y0 + TITLE_FONT)}" '
           f'font-size="{TITLE_FONT}" font-weight="bold" {TEXT}>{escape(sec.title)}</text>']
    y = y0 + TITLE_FONT + PAD / 2
    width = text_width(sec.title, TITLE_FONT, bold=True)
    rows = sec.entries
    if sec.bar is not None:   # the bar with its ticks (entries without a mark), then swatches
        rows = [e for e in sec.entries if e.mark is not None]
        parts, bar_w, y = _bar(sec.bar, [e for e in sec.entries if e.mark is None], defs, x0, y)
        out.extend(parts)
        width = max(width, bar_w)
        y += PAD / 2 if rows else 0.0
    mark_w = max((e.w for e in rows), default=0.0)
    for e in rows:
        row_h = max(e.h, FONT + 2)
        cy = y + row_h / 2
        attrs = (f' data-channel="{e.channel}"' if e.channel else ' data-channel="unit"') + \
            f' data-value={quoteattr(e.value)}'
        body = defs.use(e.mark, e.color, x0 + (mark_w - e.w) / 2, cy - e.h / 2, e.w, e.h)
        label_x = x0 + mark_w + 6
        body += (f'<text x="{_n(label_x)}" y="{_n(cy + FONT * 0.35)}" font-size="{FONT}" '
                 f'{TEXT}>{escape(e.label)}</text>')
        out.append(f'<g class="legend-entry"{attrs}>{body}</g>')
        width = max(width, mark_w + 6 + text_width(e.label))
        y += row_h + PAD / 2
    if sec.more:
        more = f"\u2026 and {sec.more:,} more"
        out.append(f'<text class="legend-more" x="{_n(x0)}" y="{_n(y + FONT)}" '
                   f'font-size="{FONT}" {TEXT}>{escape(more)}</text>')
        width = max(width, text_width(more))
        y += FONT + PAD / 2
    return out, width, y + PAD - y0


def render(sections, x: float, y: float, across: bool = False) -> tuple[str, float, float]:
    """``(svg, width, height)`` of the legend block at canvas (x, y)."""
    defs, body = _Defs(), []
    cx = cy = 0.0
    width = height = 0.0
    for sec in sections:
        parts, w, h = _section(sec, defs, cx, cy)
        body.extend(parts)
        if across:
            cx += w + 2 * PAD
            width, height = cx - 2 * PAD, max(height, h)
        else:
            cy += h
            width, height = max(width, w), cy
    svg = (f'<g class="legend" transform="translate({_n(x)} {_n(y)})">'
           f'<defs>{"".join(defs.parts)}</defs>{"".join(body)}</g>')
    return svg, width, height


def standalone(sections) -> tuple[str, float, float]:
    """The legend alone as an SVG document (the widget's ``legend`` trait)."""
    from ..io.svgsafe import SVG_NS
    _, w, h = render(sections, 0, 0)
    w, h = max(w, 1.0) + 2, max(h, 1.0) + 2
    block, _, _ = render(sections, 1, 1)
    return (f'<svg xmlns="{SVG_NS}" width="{_n(w)}" height="{_n(h)}" '
            f'viewBox="0 0 {_n(w)} {_n(h)}">{block}</svg>'), w, h
