"""Draw legend ``Section``s (legend.py) as one ``<g class="legend">`` SVG block.

``render(sections, x, y, across)`` returns ``(svg_text, width, height)``: the block
with its top-left corner at canvas (x, y); sections stacked top to bottom, or side
by side when ``across`` (legends above or below the canvas). Marks are ``<use>``s
of definitions in the block's own ``<defs>`` (ids ``legend-d<k>``).
"""
from __future__ import annotations

import unicodedata
from xml.sax.saxutils import escape, quoteattr

from ..design.encodings import SEQUENTIAL
from .legend import BAR, CHAR_W, FONT, PAD, TITLE_FONT

TEXT = 'font-family="sans-serif" fill="#222"'


def _n(v: float) -> str:
    s = f"{float(v):.3f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


# advance widths of ASCII 32..126 in DejaVu Sans (the widest common sans-serif, what the
# PNG export draws with), in font sizes; bold runs about 12% wider
_ADVANCE = (0.32, 0.4, 0.46, 0.84, 0.64, 0.95, 0.78, 0.27, 0.39, 0.39, 0.5, 0.84, 0.32, 0.36,
            0.32, 0.34, *[0.64] * 10, 0.34, 0.34, 0.84, 0.84, 0.84, 0.53, 1.0, 0.68, 0.69, 0.7,
            0.77, 0.63, 0.58, 0.77, 0.75, 0.29, 0.29, 0.66, 0.56, 0.86, 0.75, 0.79, 0.6, 0.79,
            0.69, 0.63, 0.61, 0.73, 0.68, 0.99, 0.69, 0.61, 0.69, 0.39, 0.34, 0.39, 0.84, 0.5,
            0.5, 0.61, 0.63, 0.55, 0.63, 0.62, 0.35, 0.63, 0.63, 0.28, 0.28, 0.58, 0.28, 0.97,
            0.63, 0.61, 0.63, 0.63, 0.41, 0.52, 0.39, 0.63, 0.59, 0.82, 0.59, 0.59, 0.52, 0.64,
            0.34, 0.64, 0.84)
BOLD = 1.12


def text_width(text: str, size: float = FONT, bold: bool = False) -> float:
    """px width of ``text`` at font ``size`` px: per-character advances, non-ASCII at
    ``CHAR_W`` (wide East Asian characters a full size)."""
    em = 0.0
    for ch in text:
        code = ord(ch)
        if 32 <= code < 127:
            em += _ADVANCE[code - 32]
        else:
            em += 1.0 if unicodedata.east_asian_width(ch) in "WF" else CHAR_W
    return em * size * (BOLD if bold else 1.0)


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


def _section(sec, defs: _Defs, x0: float, y0: float) -> tuple[list[str], float, float]:
    out = [f'<text class="legend-title" x="{_n(x0)}" y="{_n(y0 + TITLE_FONT)}" '
           f'font-size="{TITLE_FONT}" font-weight="bold" {TEXT}>{escape(sec.title)}</text>']
    y = y0 + TITLE_FONT + PAD / 2
    width = text_width(sec.title, TITLE_FONT, bold=True)
    if sec.bar is not None:
        lo, hi = sec.bar
        bw, bh = BAR
        gid = f"legend-bar{len(defs.parts)}"
        stops = "".join(f'<stop offset="{i / (len(SEQUENTIAL) - 1):.4g}" stop-color="{c}"/>'
                        for i, c in enumerate(SEQUENTIAL))
        defs.parts.append(f'<linearGradient id="{gid}">{stops}</linearGradient>')
        out.append(f'<rect class="legend-bar" x="{_n(x0)}" y="{_n(y)}" width="{bw}" height="{bh}" '
                   f'fill="url(#{gid})"/>')
        for e in sec.entries:
            t = 0.0 if hi <= lo else (float(e.value) - lo) / (hi - lo)
            tx = x0 + t * bw
            out.append(f'<g class="legend-entry" data-channel="color" data-value={quoteattr(e.value)}>'
                       f'<line x1="{_n(tx)}" y1="{_n(y)}" x2="{_n(tx)}" y2="{_n(y + bh + 3)}" '
                       f'stroke="#222"/><text x="{_n(tx)}" y="{_n(y + bh + 4 + FONT)}" '
                       f'font-size="{FONT}" text-anchor="middle" {TEXT}>{escape(e.label)}</text></g>')
        return out, max(width, bw + text_width(sec.entries[-1].label) / 2), y + bh + 4 + FONT + PAD - y0
    mark_w = max(e.w for e in sec.entries)
    for e in sec.entries:
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
