"""Piles: the layers of ``by=`` laid out side by side, one container per category.

``piles="columns"`` (a unit column chart: piles side by side, bottoms aligned, filled
from the bottom under a downward pull), ``"rows"`` (piles one under the other, left
edges aligned, pulled to the left, as ISOTYPE rows) or ``"grid"`` (piles wrapped into
rows of small multiples, each at the bottom of its cell). Every pile is a rectangle
whose area is proportional to its total (the footprint area of its marks at scale 1),
so under the one shared scale the piles fill alike and their areas compare. Below
each pile (left of it for rows) a band is kept free for its label, the names of the
layers in it. Layers that block on one another share a pile (the blocking layer rests
on the one it blocks on); every other layer is a pile of its own.
"""
from __future__ import annotations

import math

import numpy as np

from .containers import Container
from .forces import DirectionalForce
from .sharing import by_container
from .validate import check_choice

ARRANGEMENTS = ("columns", "rows", "grid")
PULL = {"columns": 90.0, "rows": 180.0, "grid": 90.0}   # degrees: down, left, down
LABEL_FONT = 12.0     # px
LABEL_GAP = 8.0       # px between a pile and its label (marks may poke out of it by a pixel or two)
LABEL_BAND = LABEL_FONT + 2 * LABEL_GAP   # px kept under a pile (columns, grid)
CHAR_W = 0.62         # a label's width per character in font sizes (DejaVu Sans, a little over)
MAX_BAND = 0.3        # the widest share of the canvas the labels of rows take
PAD = 8.0             # px kept free at the canvas' edges
MIN_SIDE = 2.0        # px: the thinnest pile
COVER = 0.75          # the share of a pile its marks are expected to cover (sizes the thinnest)
ROOMY = 1.0           # a pile at least as wide as its largest mark's footprint disc


def check_piles(value):
    """``piles``: None (no piles: layers without a container share the canvas) or one of
    :data:`ARRANGEMENTS`."""
    if value is None:
        return None
    return check_choice("UnitoPia", "piles", value, ARRANGEMENTS)


def pull(arrange: str) -> DirectionalForce:
    """The force that fills a pile of ``arrange`` from its base."""
    return DirectionalForce(PULL[arrange])


def groups(layers) -> list[list[int]]:
    """Layer indices grouped into piles: layers linked by ``blocks`` (either way) share
    one, in the order of their first layer."""
    names = {layer.name: i for i, layer in enumerate(layers)}
    root = list(range(len(layers)))

    def find(i):
        while root[i] != i:
            root[i] = root[root[i]]
            i = root[i]
        return i

    for i, layer in enumerate(layers):
        for b in layer.blocks:
            if b in names:
                a, c = find(i), find(names[b])
                root[max(a, c)] = min(a, c)
    out: dict[int, list[int]] = {}
    for i in range(len(layers)):
        out.setdefault(find(i), []).append(i)
    return list(out.values())


def has_container(layer) -> bool:
    """Whether ``layer`` has a container of its own (a pile's layers do)."""
    return layer.container is not None


def label_of(names) -> str:
    """A pile's label: the names of its layers."""
    return " / ".join(names)


def regions(totals, largest, labels, canvas, arrange: str) -> list[Container]:
    """One rectangle per pile, areas proportional to ``totals`` (``(K,)``, > 0: the
    footprint area of each pile's marks at scale 1), leaving the label bands free. A pile
    too thin for its largest mark (``largest (K,)``, footprint area at scale 1) at the scale
    the piles will take is made narrower and deeper instead, keeping its area; ``labels``
    (K texts) size the band of rows."""
    totals = np.asarray(totals, dtype=float)
    if not (totals.ndim == 1 and len(totals) and np.isfinite(totals).all() and (totals > 0).all()):
        raise ValueError(f"piles: every pile needs a positive, finite total, got {totals!r:.80}")
    w, h = canvas
    share = totals / totals.max()
    k = len(totals)
    if arrange == "columns":
        gap = min(max(0.15 * (w - 2 * PAD) / k, 4.0), 24.0)
        side = (w - 2 * PAD - (k - 1) * gap) / k
        tall = h - 2 * PAD - LABEL_BAND
        _fits(side, tall, k, canvas, arrange)
        need = _need(largest, side * tall, totals)
        out = []
        for i, s in enumerate(share):   # bottoms aligned, each centred in its slot
            across, deep = _shape(s * side * tall, side, tall, need[i])
            out.append(Container.rect(PAD + i * (side + gap) + (side - across) / 2,
                                      PAD + tall - deep, across, deep))
        return out
    if arrange == "rows":
        gap = min(max(0.15 * (h - 2 * PAD) / k, 4.0), 24.0)
        band = min(max(len(t) for t in labels) * CHAR_W * LABEL_FONT, MAX_BAND * w) + 2 * LABEL_GAP
        side = (h - 2 * PAD - (k - 1) * gap) / k
        wide = w - 2 * PAD - band
        _fits(wide, side, k, canvas, arrange)
        need = _need(largest, side * wide, totals)
        out = []
        for i, s in enumerate(share):   # left edges aligned, each centred in its slot
            across, long = _shape(s * side * wide, side, wide, need[i])
            out.append(Container.rect(PAD + band, PAD + i * (side + gap) + (side - across) / 2,
                                      long, across))
        return out
    cols = max(1, min(k, round(math.sqrt(k * w / h))))
    rows = math.ceil(k / cols)
    gap = 12.0
    cell_w = (w - 2 * PAD - (cols - 1) * gap) / cols
    cell_h = (h - 2 * PAD - (rows - 1) * gap) / rows - LABEL_BAND
    _fits(cell_w, cell_h, k, canvas, arrange)
    need = _need(largest, cell_w * cell_h, totals)
    out = []
    for i, s in enumerate(share):   # the cell's shape scaled down; at the foot of the cell
        r, c = divmod(i, cols)
        pw, ph = cell_w * math.sqrt(s), cell_h * math.sqrt(s)
        if pw < need[i]:
            pw, ph = _shape(pw * ph, cell_w, cell_h, need[i])
        elif ph < need[i]:
            ph, pw = _shape(pw * ph, cell_h, cell_w, need[i])
        x0, y0 = PAD + c * (cell_w + gap), PAD + r * (cell_h + LABEL_BAND + gap)
        out.append(Container.rect(x0 + (cell_w - pw) / 2, y0 + cell_h - ph, pw, ph))
    return out


def fits(count: int, canvas, arrange: str) -> bool:
    """Do ``count`` piles of ``arrange`` fit ``canvas`` (one-letter labels)?"""
    try:
        regions(np.ones(count), np.zeros(count), ["x"] * count, canvas, arrange)
    except ValueError:
        return False
    return True


def _need(largest, full: float, totals: np.ndarray) -> np.ndarray:
    """``(K,)`` px: the extent each pile needs for its largest mark at the scale at which
    the largest pile (``full`` px^2) is ``COVER`` covered."""
    scale = math.sqrt(COVER * full / totals.max())
    return 2 * np.sqrt(np.asarray(largest, dtype=float) / math.pi) * scale * ROOMY


def _shape(area: float, across: float, along: float, need: float) -> tuple[float, float]:
    """``(across, along)`` of a pile of ``area`` px^2 in a slot ``across`` wide and
    ``along`` deep: the slot's width and the depth that gives the area, unless that is less
    than ``need``; then ``need`` deep and narrower (never narrower than ``need``)."""
    deep = area / across
    if deep >= need:
        return across, max(deep, MIN_SIDE)
    deep = min(need, along)
    return min(max(area / deep, need, MIN_SIDE), across), deep


def _fits(side_a: float, side_b: float, k: int, canvas, arrange: str) -> None:
    if min(side_a, side_b) < 4 * MIN_SIDE:
        raise ValueError(f"piles={arrange!r}: {k} piles do not fit a {canvas[0]:g} x "
                         f"{canvas[1]:g} canvas; make the canvas larger, group the categories, "
                         f"use piles='grid' (wrapped) or piles=None (the layers packed together)")


def label_spots(layers, canvas, arrange: str) -> list[tuple[str, float, float, float, str]]:
    """``[(text, x, y, room, anchor), ...]``: each pile's label (the layers sharing a
    container), its baseline point, the width it may take (px) and its SVG text-anchor.
    Under the pile's box for columns and grid, left of it (right-aligned) for rows; layers
    without a container have none."""
    piles = [(layers[g[0]].container, [layers[i].name for i in g]) for g in by_container(layers, has_container)]
    boxes = [(x, y, x + bw, y + bh) for x, y, bw, bh in (c.bbox(canvas) for c, _ in piles)]
    w, h = canvas
    out = []
    for (_, names), (x0, y0, x1, y1) in zip(piles, boxes):
        text = label_of(names)
        if arrange == "rows":   # left of the pile; right of it when the canvas leaves no room
            left, right = x0 - PAD - LABEL_GAP, w - x1 - PAD - LABEL_GAP
            y = (y0 + y1) / 2 + LABEL_FONT / 3
            fits = left >= min(right, len(text) * CHAR_W * LABEL_FONT)
            out.append((text, x0 - LABEL_GAP, y, max(left, 0.0), "end") if fits
                       else (text, x1 + LABEL_GAP, y, right, "start"))
            continue
        # as wide as the pile and half of the gaps beside it: no neighbour's label touches
        left = max([b[2] for b in boxes if b[2] <= x0 and _overlap(b, (x0, y0, x1, y1))],
                   default=x0 - PAD)
        right = min([b[0] for b in boxes if b[0] >= x1 and _overlap(b, (x0, y0, x1, y1))],
                    default=x1 + PAD)
        room = (x1 - x0) + (x0 - left) / 2 + (right - x1) / 2 - 2
        if y1 + LABEL_BAND <= h or y0 < LABEL_BAND:   # under the pile; over it when no room
            y = min(y1 + LABEL_GAP + 0.8 * LABEL_FONT, h - 0.25 * LABEL_FONT)
        else:
            y = y0 - LABEL_GAP - 0.25 * LABEL_FONT
        out.append((text, (x0 + x1) / 2, y, room, "middle"))
    return out


def _overlap(a, b) -> bool:
    """Do boxes ``a`` and ``b`` (x0, y0, x1, y1) share a stretch of y (side by side)?"""
    return a[1] < b[3] and b[1] < a[3]
