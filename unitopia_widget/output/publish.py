"""What a chart adds to its export to be published: legend, title, caption, outlines.

``export_svg(chart, ...)`` draws the chart's last layout (``chart.laid``, a
``layout.engine.Layout``) with the page settings it keeps (``chart.page``, a
``design.page.PageOptions``), the keyword arguments overriding them for one export.
"""
from __future__ import annotations

import numpy as np

from ..design.page import CAPTION_CHARS, TITLE_CHARS, check_text, legend_spec
from ..design.positions import POSITION_CHANNELS
from . import legend as legend_mod, legend_draw
from .composite import chart_png
from .export import to_svg
from .axes import axes_svg
from .outline import outlines
from .pile_labels import labels_svg
from ..io.svgsafe import SVG_NS, sanitize_svg
from .page import compose


def any_bound(chart) -> bool:
    """True when some layer binds a channel to a column (the legend's default)."""
    return any(isinstance(v, str) and v in chart.df.columns
               for layer in chart.layers for v in layer.encodings.values())


def sections(chart, units, room=None):
    """The legend's sections; ``room``: the height a size section's marks may take (default
    the canvas height)."""
    return legend_mod.sections(chart.df, chart.layers, units, chart.boxes(units),
                               room=chart.canvas[1] if room is None else room)


def mark_boxes(table) -> dict:
    """Layer name -> ``(k, 4)`` boxes ``x0, y0, x1, y1`` (canvas px) of its placed marks,
    turned as drawn, from the placements ``table``."""
    a = np.radians(table["angle"].to_numpy(dtype=float))
    w, h = table["width"].to_numpy(dtype=float), table["height"].to_numpy(dtype=float)
    hw = (np.abs(w * np.cos(a)) + np.abs(h * np.sin(a))) / 2
    hh = (np.abs(w * np.sin(a)) + np.abs(h * np.cos(a))) / 2
    x, y = table["x"].to_numpy(dtype=float), table["y"].to_numpy(dtype=float)
    box = np.stack([x - hw, y - hh, x + hw, y + hh], axis=1)
    names = table["layer"].to_numpy()
    return {name: box[names == name] for name in dict.fromkeys(names)}


def legend_image(chart) -> tuple[str, float, float] | None:
    """``(svg, width, height)``: the legend alone as a sanitised SVG document, px (None
    when the chart shows no legend). The widget's ``legend`` trait carries it."""
    opts = chart.page
    if not (opts.legend["visible"] and any_bound(chart)) or chart.units is None:
        return None
    svg, w, h = legend_draw.standalone(sections(chart, chart.units))
    return sanitize_svg(svg), w, h


AXES_PAD = 4.0   # px around the axes' box in their image: room for the text's estimated width


def axes_image(chart) -> tuple[str, tuple] | None:
    """``(svg, (x0, y0, x1, y1))``: the axes of the last layout (as ``axes=True`` draws
    them) alone as a sanitised SVG document whose view box is the box ``x0..x1, y0..y1``
    (canvas px, ``AXES_PAD`` around what they take; it may reach past the canvas). None
    when no layer binds ``x=``/``y=`` or before a layout that placed marks along one. The
    widget's ``axes_image`` trait carries it."""
    bound = any(layer.encodings.get(c) is not None
                for layer in chart.layers for c in POSITION_CHANNELS)
    if not bound or chart.laid is None or not chart.laid.axes:
        return None
    drawn, box = axes_svg(chart.laid.axes, mark_boxes(chart.laid.placements))
    x0, y0 = box[0] - AXES_PAD, box[1] - AXES_PAD
    w, h = box[2] - box[0] + 2 * AXES_PAD, box[3] - box[1] + 2 * AXES_PAD
    svg = (f'<svg xmlns="{SVG_NS}" width="{w:.1f}" height="{h:.1f}" '
           f'viewBox="{x0:.1f} {y0:.1f} {w:.1f} {h:.1f}">{drawn}</svg>')
    return sanitize_svg(svg), tuple(round(float(v), 1) for v in (x0, y0, x0 + w, y0 + h))


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
    drawn = chart.laid.axes if axes and chart.laid is not None else []
    if axes and not drawn:
        raise ValueError("axes=True draws the axes of x= and y=, but the layout binds neither; "
                         "bind a layer's x= or y= to a column and run the layout again")
    axes_drawn, axes_box = axes_svg(drawn, mark_boxes(chart.laid.placements)) if axes else ("", None)
    # above or below the chart a size section shows its two ends once its marks grow tall
    room = chart.canvas[1] / 4 if position in ("top", "bottom") else None
    page = compose(chart.canvas, sections(chart, units, room) if show else None, position, title,
                   caption, axes_box)
    under = (outlines(chart.layers, chart.canvas) if outline else "") + axes_drawn \
        + labels_svg(chart.layers, chart.canvas, chart.piles)
    return (chart.canvas, chart.laid.placements, chart.layers, units.colors, chart.titles(units),
            chart.background, page, under)
