"""The widget's place in a notebook's saved output: a static image after the live view.

Displaying a widget writes two outputs: the widget view, then a static output
holding the layout (``text/html`` with the SVG inline, ``image/svg+xml``,
``image/png``, ``text/plain``) under a ``display_id``, refreshed when a run ends.

Why a second output and not one more type in the view's bundle: nbconvert
``--execute`` saves the widget state, and nbconvert's HTML exporter then always
picks the widget view (it renders only with a widget manager from a CDN), so a
static type beside it never shows. The static output shows wherever the live
widget does not render (nbconvert HTML, static viewers, a notebook reopened
without a kernel); where it does render (JupyterLab, Notebook 7), a style rule in
the static output hides it right after a live ``.unitopia`` view.
"""
from __future__ import annotations

import base64
import re
import uuid
from html import unescape
from xml.sax.saxutils import escape

from ..io import svgsafe
from ..output.export import svg_size, to_png

PLAIN = "UnitoPia chart: {rows} rows in {layers} layer(s), {state}"
HIDE_AFTER_LIVE = ("<style>.jp-OutputArea-child:has(.unitopia[data-unitopia]) + "
                   ".jp-OutputArea-child:has(.unitopia-static){display:none}</style>")
_REFS = re.compile(r'(\bid="|href="#|url\(#)')
_STYLE = re.compile(r"(<style\b[^>]*>)(.*?)(</style>)", re.S)


def prefix_ids(svg: str, prefix: str) -> str:
    """``svg`` (serialised) with every id, ``#id`` reference and ``#id`` selector of its
    <style> elements renamed ``prefix-id``."""
    svg = _REFS.sub(lambda m: m.group(1) + f"{prefix}-", svg)
    rename = lambda name: f"{prefix}-{name}"
    return _STYLE.sub(lambda m: m[1] + escape(svgsafe.rename_ids(unescape(m[2]), rename)) + m[3],
                      svg)


class StaticDisplay:
    """The static output of one widget."""

    def __init__(self, widget):
        self.widget = widget
        self.display_id = f"unitopia-{uuid.uuid4().hex}"
        self.shown = False

    def plain(self) -> str:
        w = self.widget
        chart = w._chart
        state = "not laid out yet (run it)" if chart.placements is None else f"status {w.status}"
        return PLAIN.format(rows=len(chart.df), layers=len(chart.layers), state=state)

    def svg(self) -> str | None:
        """The current layout as exported (legend, title, caption), ids prefixed so that
        several charts inline in one page keep their own definitions; None without one."""
        try:
            svg = self.widget._chart.to_svg()
        except RuntimeError:   # no layout yet, or one that no longer matches the layers
            return None
        prefix = "c" + self.display_id[len("unitopia-"):][:8]
        return prefix_ids(svg, prefix)

    def bundle(self) -> dict:
        """The static output's MIME bundle."""
        plain = self.plain()
        svg = self.svg()
        if svg is None:
            return {"text/plain": plain,
                    "text/html": f'{HIDE_AFTER_LIVE}<div class="unitopia-static"><pre>{plain}</pre></div>'}
        png = base64.b64encode(to_png(svg, svg_size(svg), 1.0)).decode()
        return {"text/plain": plain, "image/svg+xml": svg, "image/png": png,
                "text/html": f'{HIDE_AFTER_LIVE}<div class="unitopia-static">{svg}</div>'}

    def show(self) -> None:
        from IPython.display import display
        display(self.bundle(), raw=True, display_id=self.display_id)
        self.shown = True

    def update(self) -> None:
        """Refresh every static output of the widget (no-op when it was never displayed)."""
        if self.shown:
            from IPython.display import update_display
            update_display(self.bundle(), raw=True, display_id=self.display_id)
