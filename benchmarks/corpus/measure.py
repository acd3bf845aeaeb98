"""Ink measures of an exported chart (``chart.to_svg(legend=False)``), rendered by resvg.

Each unit is rendered alone, cropped to the square its transform can reach, at ``k`` px
per canvas px (as ``tests/ink.py`` renders whole canvases, but one small crop per unit). A
pixel is a unit's ink where its alpha > 0.5; its silhouette is the ink with enclosed holes
filled. ``ink_measures`` returns shares of all ink (``overlap``: ink drawn over other ink;
``outside``: ink beyond its own layer's container or the canvas), ``empty`` (share of the
closed containers farther than one median mark radius from any ink, as the independent
checker counts it), ``fill`` (per open container: the share its marks' silhouettes cover)
and ``join`` (the largest mark across a narrow join of its container, ``joins.py``, as a
multiple of the median mark's silhouette; 0 when none is).
"""
from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np
from scipy import ndimage

from unitopia_widget.io.svgsafe import SVG_NS
from . import joins
from unitopia_widget.output.export import png_array

_NUM = r"(-?[0-9.]+(?:e-?[0-9]+)?)"
_TRANSFORM = re.compile(rf"translate\({_NUM} {_NUM}\) rotate\({_NUM}\) scale\({_NUM} {_NUM}\) "
                        rf"translate\({_NUM} {_NUM}\)")


def filled(ink: np.ndarray) -> np.ndarray:
    """``ink`` (bool 2-D) with its enclosed holes filled."""
    return ndimage.binary_fill_holes(ink)


def reach(transform: str) -> tuple[float, float, float]:
    """(x, y, r): the unit's centre and the half diagonal of its drawn box, canvas px."""
    x, y, _, sx, sy, tx, ty = (float(v) for v in _TRANSFORM.fullmatch(transform).groups())
    return x, y, math.hypot(2 * tx * sx, 2 * ty * sy) / 2


def unit_crops(svg: str, k: int):
    """Yield ``(layer, row, x0, y0, ink)`` per unit: ``ink`` bool (h k, w k), whose top-left
    pixel is canvas (x0, y0) (integers; the crop may reach beyond the canvas)."""
    ET.register_namespace("", SVG_NS)
    root = ET.fromstring(svg)
    units = [el for el in root if el.get("class") == "unit"]
    for el in list(root):
        if el.tag != f"{{{SVG_NS}}}defs":
            root.remove(el)
    for el in units:
        x, y, r = reach(el.get("transform"))
        x0, y0 = math.floor(x - r) - 1, math.floor(y - r) - 1
        side = math.ceil(x + r) + 1 - x0
        root.set("viewBox", f"{x0} {y0} {side} {side}")
        root.set("width", str(side))
        root.set("height", str(side))
        root.append(el)
        ink = png_array(ET.tostring(root, encoding="unicode"), (side, side), k)[..., 3] > 127
        root.remove(el)
        yield el.get("data-layer"), el.get("data-row"), x0, y0, ink


def ink_measures(svg: str, canvas, containers: dict, closed: set, fills: dict, k: int = 2) -> dict:
    """Measure ``svg``; ``containers``: layer name -> uw.Container; ``closed``: names of
    closed layers; ``fills``: open layer name -> asked fill. Returns ``overlap``,
    ``outside``, ``empty`` (None when no layer is closed), ``fill`` (a list of
    ``(reached, asked)``, one per open container), ``join``, ``units`` and ``ink_px``."""
    w, h = int(round(canvas[0])), int(round(canvas[1]))
    masks, coarse_masks = {}, {}
    for name, c in containers.items():
        masks.setdefault(id(c), (c, np.asarray(c.coverage((w, h), float(k))) >= 0.5))
        if id(c) not in coarse_masks:
            m = np.asarray(c.coverage((w, h), 1.0)) >= 0.5
            coarse_masks[id(c)] = (m, joins.large_pieces(m, float(m.sum())))
    count = np.zeros((h * k, w * k), np.int32)
    solid = {key: np.zeros((h * k, w * k), bool) for key in masks}
    outside, total, areas, silhouettes, across = 0.0, 0.0, [], [], []
    for layer, _, x0, y0, ink in unit_crops(svg, k):
        n = float(ink.sum())
        total += n
        areas.append(n)
        # the crop's part on the canvas, in raster px (empty for a unit wholly off it)
        r0, c0 = y0 * k, x0 * k
        r1, c1 = max(r0, 0), max(c0, 0)
        rs = slice(r1, max(r1, min(r0 + ink.shape[0], h * k)))
        cs = slice(c1, max(c1, min(c0 + ink.shape[1], w * k)))
        part = ink[rs.start - r0:rs.stop - r0, cs.start - c0:cs.stop - c0]
        count[rs, cs] += part
        key = id(containers[layer])
        outside += n - float((part & masks[key][1][rs, cs]).sum())
        sil = filled(part)
        solid[key][rs, cs] |= sil
        silhouettes.append(float(sil.sum()))
        mask1, pieces = coarse_masks[key]
        rows, cols = slice(rs.start // k, rs.stop // k), slice(cs.start // k, cs.stop // k)
        if sil.any() and joins.splits(mask1, joins.coarse(sil, k), rows, cols, pieces):
            across.append(silhouettes[-1])
    total = max(total, 1.0)
    out = {"units": len(areas), "ink_px": total,
           "overlap": float(np.maximum(count - 1, 0).sum()) / total,
           "outside": outside / total, "empty": None, "fill": [],
           "join": max(across, default=0.0) / max(float(np.median(silhouettes or [1.0])), 1.0)}
    closed_keys = {id(containers[n]) for n in closed}
    if closed_keys and areas:
        region = np.logical_or.reduce([masks[key][1] for key in closed_keys])
        r_med = math.sqrt(float(np.median(areas)) / math.pi)
        far = ndimage.distance_transform_edt(count == 0) > r_med
        out["empty"] = float((far & region).sum()) / max(float(region.sum()), 1.0)
    asked = {}
    for name, share in fills.items():
        asked.setdefault(id(containers[name]), share)
    for key, share in asked.items():
        mask = masks[key][1]
        out["fill"].append((float((solid[key] & mask).sum()) / max(float(mask.sum()), 1.0), share))
    return out
