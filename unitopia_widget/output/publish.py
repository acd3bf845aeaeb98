"""What a chart adds to its export to be published: legend, title, caption, outlines.

``PageOptions`` holds the chart's own settings (design JSON top-level keys
``"title"``, ``"caption"``, ``"legend": {"visible", "position"}``);
``export_svg(chart, ...)`` draws the laid-out chart with them, the keyword
arguments overriding them for one export.
"""
from __future__ import annotations

import numpy as np

from ..layout.prepare.scale import initial_scale
from . import legend as legend_mod, legend_draw
from .composite import chart_png
from .export import to_svg
from .axes import axes_svg
from .outline import outlines
from ..io.svgsafe import sanitize_svg
from .page import CAPTION_CHARS, TITLE_CHARS, check_position, check_text, compose


class PageOptions:
    """Title, caption and legend settings of one chart."""

    def __init__(self, title=None, caption=None, legend=True):
        self.title = check_text("title", title, TITLE_CHARS)
        self.caption = check_text("caption", caption, CAPTION_CHARS)
        self.legend = legend_spec(legend)

    def to_json(self) -> dict:
        return {"title": self.title, "caption": self.caption, "legend": dict(self.legend)}

    @classmethod
    def from_json(cls, d: dict) -> "PageOptions":
        return cls(d.get("title"), d.get("caption"),
                   d.get("legend") if d.get("legend") is not None else True)


def legend_spec(value) -> dict:
    """``{"visible": bool, "position": ...}`` from True/False, a position, or that dict."""
    if isinstance(value, dict):
        unknown = set(value) - {"visible", "position"}
        if unknown or not isinstance(value.get("visible", True), bool):
            raise ValueError(f"legend must be True, False, a position or {{\"visible\": bool, "
                             f"\"position\": ...}}; got {value!r:.80}")
        return {"visible": value.get("visible", True),
                "position": check_position(value.get("position", "right"))}
    if isinstance(value, bool):
        return {"visible": value, "position": "right"}
    try:
        return {"visible": True, "position": check_position(value)}
    except ValueError:
        raise ValueError(f"legend must be True, False, None, 'right', 'bottom', 'left', 'top' or "
                         f"[x, y]; got {value!r:.60}") from None


def any_bound(chart) -> bool:
    """True when some layer binds a channel to a column (the legend's default)."""
    return any(isinstance(v, str) and v in chart.df.columns
               for layer in chart.layers for v in layer.encodings.values())


def unit_boxes(chart, units) -> np.ndarray:
    """``(N, 2)`` drawn box width and height of ``units``, canvas px: the layout's when it
    placed these units, else at the last layout's (or the starting) global scale."""
    table, placed = chart.placements, getattr(chart, "_placed", None)
    if table is not None and placed is not None and placed.rows == units.rows \
            and np.array_equal(placed.layer, units.layer):
        return table[["width", "height"]].to_numpy(dtype=float)
    scale = np.asarray(chart.result.scale, dtype=float) if chart.result is not None else None
    if scale is None or scale.ndim:   # per-layer scales of another layout: start afresh
        scale = initial_scale(units, chart.layers, chart.canvas)[0]
    return np.stack([2 * units.half_w * scale, 2 * units.half_h * scale], axis=1)


def sections(chart, units):
    return legend_mod.sections(chart.df, chart.layers, units, unit_boxes(chart, units),
                               room=chart.canvas[1])


def legend_image(chart) -> tuple[str, float, float] | None:
    """``(svg, width, height)``: the legend alone as a sanitised SVG document, px (None
    when the chart shows no legend). The widget's ``legend`` trait carries it."""
    opts = chart.page
    if not (opts.legend["visible"] and any_bound(chart)) or chart._units is None:
        return None
    svg, w, h = legend_draw.standalone(sections(chart, chart._units))
    return sanitize_svg(svg), w, h


def export_svg(chart, units, legend=None, title=None, caption=None, outline=False,
               axes=False) -> str:
    """The laid-out chart of ``units`` with its page around it (see ``Chart.to_svg``)."""
    return to_svg(*_drawing(chart, units, legend, title, caption, outline, axes))


def export_png(chart, units, legend=None, title=None, caption=None, outline=False,
               axes=False, scale: float = 2.0) -> bytes:
    """PNG bytes of ``export_svg``'s chart at ``scale`` px per canvas px, each distinct
    mark rendered once (``composite``)."""
    if isinstance(scale, bool) or not isinstance(scale, (int, float)) or not 0 < scale <= 8:
        raise ValueError(f"to_png: scale must be a number in (0, 8], got {scale!r:.40}")
    canvas, table, layers, colors, _titles, background, page, under = _drawing(
        chart, units, legend, title, caption, outline, axes)
    return chart_png(canvas, table, layers, colors, background, page, under, scale)


def _drawing(chart, units, legend, title, caption, outline, axes) -> tuple:
    """``to_svg``'s arguments for the chart of ``units`` and the export's options."""
    opts = chart.page
    title = opts.title if title is None else check_text("title", title, TITLE_CHARS)
    caption = opts.caption if caption is None else check_text("caption", caption, CAPTION_CHARS)
    if legend is None:
        show, position = opts.legend["visible"] and any_bound(chart), opts.legend["position"]
    else:
        spec = legend_spec(legend)
        show, position = spec["visible"], (spec["position"] if not isinstance(legend, bool)
                                           else opts.legend["position"])
    if not isinstance(outline, bool):
        raise TypeError(f"outline must be True or False, got {outline!r:.40}")
    if not isinstance(axes, bool):
        raise TypeError(f"axes must be True or False, got {axes!r:.40}")
    drawn = chart.result.axes if axes and chart.result is not None else []
    if axes and not drawn:
        raise ValueError("axes=True draws the axes of x= and y=, but the layout binds neither; "
                         "bind a layer's x= or y= to a column and run the layout again")
    page = compose(chart.canvas, sections(chart, units) if show else None, position, title, caption)
    under = (outlines(chart.layers, chart.canvas) if outline else "") \
        + (axes_svg(drawn, chart.canvas) if axes else "")
    return (chart.canvas, chart.placements, chart.layers, units.colors, chart.titles(units),
            chart.background, page, under)
