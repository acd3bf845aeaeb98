"""The widget's place in a notebook's saved output: a static image after the live view.

Displaying a widget writes two outputs: the widget view, then a static output
holding the layout (``image/svg+xml``, ``image/png``, ``text/plain``) under a
``display_id``, refreshed when a run ends.

Why a second output and not one more type in the view's bundle: nbconvert
``--execute`` saves the widget state, and nbconvert's HTML exporter then always
picks the widget view (it renders only with a widget manager from a CDN), so a
static type beside it never shows. The static output shows wherever the live
widget does not render (nbconvert HTML, static viewers, a notebook reopened
without a kernel); where it does render (JupyterLab, Notebook 7), a rule of the
widget's CSS hides it right after a live ``.unitopia`` view (its SVG's root has
the class ``unitopia-static``, which JupyterLab's ``<img src>`` of it spells out).

Why no ``text/html``: JupyterLab shows an untrusted output (a notebook executed
elsewhere, not yet trusted) in its first *safe* type by rank, and sanitised HTML
is safe and ranks first: the SVG's elements are stripped and their tooltip text
left as a wall, and ``data:`` images are dropped. Without it, a trusted notebook
shows the SVG (styles and all; it ranks before PNG), an untrusted one the PNG,
and nbconvert's HTML the SVG as an ``<img>`` (no tooltips there). The view's own
``text/plain`` (what an untrusted notebook shows for the view) names the chart
and no run state, which it could not keep true.

Why a large chart's SVG holds its PNG: a browser draws an SVG image element by element
even when the image is hidden, and 20,000 units held the page's main thread for
28 s after each run (and grew the notebook file by the SVG's size). Past ``SVG_BYTES``
the ``image/svg+xml`` is the PNG inside an ``<svg>`` root (one element to draw, the
same class for the CSS rule); the vector chart is what ``w.save("x.svg")`` writes.
"""
from __future__ import annotations

import base64
import re
import uuid
import warnings
from html import unescape
from xml.sax.saxutils import escape

from ..io import svgsafe
from ..output.export import svg_size

PLAIN = "UnitoPia chart: {rows} rows in {layers} layer(s), {state}"
VIEW_PLAIN = "UnitoPia chart: {rows} rows in {layers} layer(s) (the live widget; its image follows)"
MARK = '<svg class="unitopia-static" '   # the static image's root, found by the widget's CSS
SVG_BYTES = 1_000_000   # a static SVG larger than this is replaced by one holding its PNG
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

    def view_plain(self) -> str:
        """The live view's ``text/plain``: what the chart is, no state that could go stale."""
        chart = self.widget._chart
        return VIEW_PLAIN.format(rows=len(chart.df), layers=len(chart.layers))

    def svg(self) -> str | None:
        """The current layout as exported (legend, title, caption), ids prefixed so that
        several charts inline in one page keep their own definitions; None without one."""
        try:
            svg = self.widget._chart.to_svg()
        except RuntimeError:   # no layout yet, or one that no longer matches the layers
            return None
        prefix = "c" + self.display_id[len("unitopia-"):][:8]
        return MARK + prefix_ids(svg, prefix)[len("<svg "):]

    def bundle(self) -> dict:
        """The static output's MIME bundle. A layout whose PNG cannot be drawn has none:
        its text says why (an untrusted notebook shows it), and no older image stays."""
        plain = self.plain()
        svg = self.svg()
        if svg is None:
            return {"text/plain": plain, "image/svg+xml": _note(plain, self.widget._chart.canvas[0])}
        try:
            png = base64.b64encode(self.widget._chart.to_png(1.0)).decode()
        except Exception as exc:   # no PNG: say why, and show no older one
            why = f"its PNG could not be drawn: {type(exc).__name__}: {str(exc)[:200]}"
            warnings.warn(f"the static image: {why}", RuntimeWarning, stacklevel=2)
            return {"text/plain": f"{plain}; {why}", "image/svg+xml": svg}
        if len(svg) > SVG_BYTES:
            svg = _picture(png, *svg_size(svg))
        return {"text/plain": plain, "image/svg+xml": svg, "image/png": png}

    def show(self) -> None:
        from IPython.display import display
        display(self.bundle(), raw=True, display_id=self.display_id)
        self.shown = True

    def update(self) -> None:
        """Refresh every static output of the widget (no-op when it was never displayed)."""
        if self.shown:
            from IPython.display import update_display
            update_display(self.bundle(), raw=True, display_id=self.display_id)


def _note(text: str, width: float) -> str:
    """A one-line SVG image of ``text``, ``width`` px wide (the static image's place
    before a layout)."""
    return (f'{MARK}xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="32" '
            f'viewBox="0 0 {width:.0f} 32"><text x="8" y="21" font-family="sans-serif" '
            f'font-size="13">{escape(text)}</text></svg>')


def _picture(png: str, width: float, height: float) -> str:
    """An SVG image ``width`` x ``height`` px holding only the base64 ``png``."""
    return (f'{MARK}xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
            f'viewBox="0 0 {width:.0f} {height:.0f}"><image width="{width:.0f}" '
            f'height="{height:.0f}" href="data:image/png;base64,{png}"/></svg>')
