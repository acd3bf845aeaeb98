"""What the front end draws, as trait values (``docs/protocol.md``): each unit's mark image
and size, and beside the marks the legend, the piles' labels and the axes; every image as an
SVG data URL."""
from __future__ import annotations

import base64

import numpy as np

from ..output.pile_labels import labels as pile_labels
from ..output.publish import axes_image, legend_image


def svg_url(svg: str) -> str:
    """``svg`` (a document) as a base64 ``data:image/svg+xml`` URL."""
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode()).decode()


def unit_marks(units, layers) -> tuple[list[dict], np.ndarray]:
    """``(marks, table)``: one ``{"layer", "mark", "aspect", "src"}`` image per (layer, mark,
    colour) the ``units`` use, and ``table (N, 4)`` float32 of each unit's layer, image index
    and base width and height px (the ``marks`` and ``units`` traits)."""
    keys, marks, index = {}, [], np.zeros(len(units.rows), dtype=np.float32)
    for k, (li, mi, color) in enumerate(zip(units.layer, units.mark, units.colors)):
        key = (int(li), int(mi), color)
        if key not in keys:
            keys[key] = len(marks)
            mark = layers[li].marks[mi]
            marks.append({"layer": layers[li].name, "mark": int(mi), "aspect": mark.aspect,
                          "src": svg_url(mark.to_svg(color, max_side=128))})
        index[k] = keys[key]
    table = np.stack([units.layer.astype(np.float32), index, (2 * units.half_w).astype(np.float32),
                      (2 * units.half_h).astype(np.float32)], axis=1)
    return marks, np.ascontiguousarray(table, dtype=np.float32)


def legend_trait(chart) -> dict:
    """``legend_image``: ``{}`` (no legend) or ``{"src", "width", "height"}`` px."""
    try:
        image = legend_image(chart)
    except Exception:   # a design the legend cannot draw yet: shown without one
        image = None
    if image is None:
        return {}
    return {"src": svg_url(image[0]), "width": image[1], "height": image[2]}


def labels_trait(chart) -> list[dict]:
    """``pile_labels``: ``[{"text", "x", "y", "anchor"}]`` (``[]`` without piles)."""
    try:
        return pile_labels(chart.layers, chart.canvas, chart.piles)
    except ValueError:   # a container off the canvas: refused by the next run, no labels
        return []


def axes_trait(chart) -> dict:
    """``axes_image``: ``{}`` or ``{"src", "x", "y", "width", "height"}`` (canvas px) of the
    shown layout's axes, as its marks are; ``{}`` once x= and y= are unbound."""
    axes = axes_image(chart)
    if axes is None:
        return {}
    x0, y0, x1, y1 = axes[1]
    return {"src": svg_url(axes[0]), "x": x0, "y": y0,
            "width": round(x1 - x0, 1), "height": round(y1 - y0, 1)}
