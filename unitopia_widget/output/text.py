"""Text metrics for laying out the page: how wide a label is drawn, without a browser.

``text_width(text, size, bold)`` over-estimates a little, so laid-out text never touches.
"""
from __future__ import annotations

import unicodedata

CHAR_W = 0.6   # text width per non-ASCII character, in font sizes (a safe over-estimate)


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


def text_width(text: str, size: float = 12.0, bold: bool = False) -> float:
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


def fit(text: str, room: float, size: float = 12.0) -> str:
    """``text``, cut and ended with an ellipsis where it is wider than ``room`` px at font
    ``size`` px (no space left before the ellipsis)."""
    if text_width(text, size) <= room:
        return text
    while text and text_width(text + "…", size) > room:
        text = text[:-1]
    return text.rstrip() + "…"
