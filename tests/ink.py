"""Independent measure of an exported chart: every unit of the SVG rendered alone (resvg).

Used by the mark-group tests and benchmarks/groups.py. A pixel (at ``k`` x the
canvas) is a unit's ink where its alpha > 0.5; overlap is the ink drawn over
other ink, outside the ink beyond an ellipse, both as shares of all ink. A unit's
silhouette is its ink with enclosed holes filled; ``nested`` is the share of the ink
inside other units' silhouettes, ``nested_max`` the largest such share of one unit's ink.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
from scipy import ndimage

from unitopia_widget.output.export import png_array
from unitopia_widget.io.svgsafe import SVG_NS


def unit_inks(svg: str, canvas, k: int = 2):
    """Yield ``(data-row, bool (H k, W k) ink)`` per unit of ``svg``, in document order."""
    ET.register_namespace("", SVG_NS)
    root = ET.fromstring(svg)
    units = [el for el in root if el.get("class") == "unit"]
    for el in units:
        root.remove(el)
    for el in units:
        root.append(el)
        yield el.get("data-row"), png_array(ET.tostring(root, encoding="unicode"), canvas, k)[..., 3] > 127
        root.remove(el)


def filled(ink: np.ndarray) -> np.ndarray:
    """``ink`` with its enclosed holes filled: ``binary_fill_holes`` on the ink's bounding box
    only (the same result: outside the box all is background, joined to the border)."""
    rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    out = np.zeros_like(ink)
    if len(rows):
        box = np.s_[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]
        out[box] = ndimage.binary_fill_holes(ink[box])
    return out


def ink_metrics(svg: str, canvas, ellipse=None, k: int = 2) -> dict:
    """``overlap``, ``outside`` (shares of the ink), ``nested``, ``nested_max`` (see above), ``areas`` and
    ``silhouettes`` {data-row: ink / silhouette px at k x}."""
    w, h = int(round(canvas[0])), int(round(canvas[1]))
    count = np.zeros((h * k, w * k), np.int32)
    solid = np.zeros((h * k, w * k), np.int32)
    areas, silhouettes, inks = {}, {}, {}
    for row, ink in unit_inks(svg, canvas, k):
        solid_ink = filled(ink)
        count += ink
        solid += solid_ink
        areas[row], silhouettes[row] = float(ink.sum()), float(solid_ink.sum())
        inks[row] = (ink, solid_ink)
    within = [(float((ink & (solid - filled > 0)).sum()), max(float(ink.sum()), 1.0))
              for ink, filled in inks.values()]
    total = max(float(count.sum()), 1.0)
    out = {"overlap": float(np.maximum(count - 1, 0).sum()) / total, "areas": areas,
           "silhouettes": silhouettes, "nested": sum(a for a, _ in within) / total,
           "nested_max": max((a / b for a, b in within), default=0.0), "outside": 0.0}
    if ellipse is not None:
        y, x = (np.mgrid[0:h * k, 0:w * k] + 0.5) / k
        cx, cy, rx, ry = ellipse
        inside = ((x - cx) / rx) ** 2 + ((y - cy) / ry) ** 2 <= 1
        out["outside"] = float(count[~inside].sum()) / total
    return out
