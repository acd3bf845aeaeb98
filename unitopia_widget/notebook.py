"""The widget's place in a notebook's saved output: a static image beside the live view.

A widget output holds the widget view (``application/vnd.jupyter.widget-view+json``)
and, once a layout exists, the layout as ``image/svg+xml`` and ``image/png``.
Where the live view cannot render (nbconvert HTML, static viewers, a notebook
reopened without a kernel and without saved widget state) the image shows.
Every display of one widget shares a ``display_id``, so ``update`` (called when
a run ends) refreshes the saved image of every output showing the widget.
"""
from __future__ import annotations

import base64
import uuid

from .export import to_png

PLAIN = "UnitoPia chart: {rows} rows in {layers} layer(s), {state}"


class StaticDisplay:
    """The display bookkeeping of one widget."""

    def __init__(self, widget):
        self.widget = widget
        self.display_id = f"unitopia-{uuid.uuid4().hex}"
        self.shown = False

    def bundle(self, view: dict) -> dict:
        """The MIME bundle: ``view`` (the widget's own bundle) plus the static layout."""
        w = self.widget
        chart = w._chart
        state = "not laid out yet (run it)" if chart.placements is None else f"status {w.status}"
        out = dict(view)
        out["text/plain"] = PLAIN.format(rows=len(chart.df), layers=len(chart.layers), state=state)
        svg = self.svg()
        if svg is not None:
            out["image/svg+xml"] = svg
            out["image/png"] = base64.b64encode(to_png(svg, _size(svg), 1.0)).decode()
        return out

    def svg(self) -> str | None:
        """The current layout as exported (legend, title, caption), or None without one."""
        try:
            return self.widget._chart.to_svg()
        except RuntimeError:   # no layout yet, or one that no longer matches the layers
            return None

    def show(self, view: tuple[dict, dict]) -> None:
        """Display ``view`` (data, metadata) with the static image, under the display_id."""
        from IPython.display import display
        display(self.bundle(view[0]), raw=True, metadata=view[1], display_id=self.display_id)
        self.shown = True

    def update(self, view: tuple[dict, dict]) -> None:
        """Refresh every output that shows the widget (no-op when it was never displayed)."""
        if not self.shown:
            return
        from IPython.display import update_display
        update_display(self.bundle(view[0]), raw=True, metadata=view[1], display_id=self.display_id)


def _size(svg: str) -> tuple[float, float]:
    from .chart import svg_size
    return svg_size(svg)
