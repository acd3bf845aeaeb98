"""The labels of piles (``design.piles``): one ``<text class="pile-label">`` per pile,
under it (beside it, for rows), in the band the piles leave free, each clipped with an
ellipsis to the width it may take so that no label touches its neighbour's."""
from __future__ import annotations

from xml.sax.saxutils import escape

from ..design.piles import LABEL_FONT, label_spots
from .legend_draw import TEXT
from .text import fit

CLASS = "pile-label"


def labels(layers, canvas, arrange) -> list[dict]:
    """``[{"text", "x", "y", "anchor"}, ...]``: each pile's label (baseline point, SVG
    text-anchor); none when ``arrange`` is None."""
    if arrange is None:
        return []
    return [{"text": fit(text, room, LABEL_FONT), "x": round(x, 1), "y": round(y, 1), "anchor": anchor}
            for text, x, y, room, anchor in label_spots(layers, canvas, arrange)]


def labels_svg(layers, canvas, arrange) -> str:
    """The labels as one ``<g class="pile-labels">`` ("" when there are none)."""
    spots = labels(layers, canvas, arrange)
    if not spots:
        return ""
    return ('<g class="pile-labels">' + "".join(
        f'<text class="{CLASS}" x="{s["x"]:.1f}" y="{s["y"]:.1f}" font-size="{LABEL_FONT:g}" '
        f'text-anchor="{s["anchor"]}" {TEXT}>{escape(s["text"])}</text>' for s in spots) + "</g>")
