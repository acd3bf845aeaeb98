"""SVG and PNG export of a laid-out chart (DESIGN.md section 2, "SVG export").

Structure: a root ``<svg width=W height=H viewBox="0 0 W H">``; the background,
if any, as ``<image class="background">``; a comment crediting the icons'
licence when Font Awesome icons are drawn; one definition per (layer, mark of
the layer, colour) in ``<defs>``, each mark keeping its own vector design; one
``<g class="unit" data-row data-layer transform>`` per unit holding a ``<title>`` with the row's values and a ``<use>`` of its
definition. The unit transform maps the mark's box onto its placement:
``translate(x y) rotate(angle) scale(sx sy) translate(-box_w/2 -box_h/2)``. A partial
mark (the table's ``drawn`` below 1, ``per=`` with ``partial=True``) clips its ``<use>`` to
that share of its box's width, from the left.
"""
from __future__ import annotations

import io
import re
from xml.sax.saxutils import escape, quoteattr

import numpy as np
from PIL import Image

from ..io.svgsafe import SVG_NS
from ..io.svgworker import RenderTimeout, svg_to_png

EXPORT_SECONDS = 300.0   # one PNG export (a page or an atlas of sprites) at most

_XML_ILLEGAL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")
ICON_CREDIT = ("<!-- Icons: Font Awesome Free by Fonticons, Inc., CC BY 4.0, "
               "https://fontawesome.com/license/free -->")


def _n(v: float) -> str:
    s = f"{float(v):.3f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def to_svg(canvas, table, layers, colors, titles, background: str | None = None,
           page=None, under: str = "") -> str:
    """The chart as SVG text.

    ``table``: the placements DataFrame (one row per unit, layer order; its ``mark``
    column indexes each layer's marks);
    ``colors``: CSS colour per unit; ``titles``: tooltip text per unit;
    ``background``: a PNG data URL or None; ``page``: a ``page.Page`` (the viewBox
    around the canvas and the legend, title and caption drawn over it) or None;
    ``under``: SVG drawn between the background and the units (container outlines).
    """
    w, h = canvas
    vx, vy, vw, vh = page.view if page is not None else (0, 0, w, h)
    out = [f'<svg xmlns="{SVG_NS}" xmlns:xlink="http://www.w3.org/1999/xlink" '
           f'width="{_n(vw)}" height="{_n(vh)}" viewBox="{_n(vx)} {_n(vy)} {_n(vw)} {_n(vh)}">']
    if background:
        out.append(f'<image class="background" x="0" y="0" width="{_n(w)}" height="{_n(h)}" '
                   f'preserveAspectRatio="none" href={quoteattr(background)}/>')
    if under:
        out.append(under)
    by_name = {layer.name: (i, layer) for i, layer in enumerate(layers)}
    defs, ids = [], {}
    keys = list(zip(table["layer"], table["mark"], colors))
    for key in keys:
        if key not in ids:
            i, layer = by_name[key[0]]
            def_id = f"u{i}m{len(ids)}"
            ids[key] = def_id
            defs.append(layer.marks[key[1]].svg_fragment(def_id, key[2]))
    if any(by_name[name][1].marks[k].kind == "icon" for name, k, _ in ids):
        out.append(ICON_CREDIT)   # the artwork's licence asks for attribution
    cols = table[["x", "y", "angle", "sx", "sy"]].to_numpy(dtype=float)
    clips = table["drawn"].to_numpy(dtype=float) if "drawn" in table else np.ones(len(table))
    boxes = [by_name[name][1].marks[key[1]].box_size for name, key in zip(table["layer"], keys)]
    cuts = {}   # (box w, box h, clip) -> id of the clipPath that keeps that share of the width
    for (bw, bh), c in zip(boxes, clips):
        if c < 1 and (bw, bh, c) not in cuts:
            cuts[(bw, bh, c)] = f"c{len(cuts)}"
            defs.append(f'<clipPath id="c{len(cuts) - 1}"><rect x="0" y="0" width="{bw * c:.6g}" '
                        f'height="{bh:.6g}"/></clipPath>')
    out.append("<defs>" + "".join(defs) + "</defs>")
    for k, (row, name) in enumerate(zip(table["row"], table["layer"])):
        x, y, a, sx, sy = cols[k]
        bw, bh = boxes[k]
        transform = (f"translate({_n(x)} {_n(y)}) rotate({_n(a)}) scale({sx:.6g} {sy:.6g}) "
                     f"translate({_n(-bw / 2)} {_n(-bh / 2)})")
        cut = f' clip-path="url(#{cuts[(bw, bh, clips[k])]})"' if clips[k] < 1 else ""
        out.append(f'<g class="unit" data-row={quoteattr(str(row))} data-layer={quoteattr(name)} '
                   f'transform="{transform}"><title>{escape(titles[k])}</title>'
                   f'<use href="#{ids[keys[k]]}"{cut}/></g>')
    if page is not None and page.overlay:
        out.append(page.overlay)
    out.append("</svg>")
    return _XML_ILLEGAL.sub("\ufffd", "\n".join(out))   # control characters in the data: not XML


def to_png(svg: str, canvas, scale: float = 1.0) -> bytes:
    """PNG bytes of ``svg`` rendered at ``scale`` x ``canvas`` (the SVG's width, height) by
    resvg in its worker process (``io/svgworker.py``), so Ctrl-C stops a long export; one
    past ``EXPORT_SECONDS`` is refused."""
    w, h = canvas
    try:
        return svg_to_png(EXPORT_SECONDS, svg_string=svg, width=max(1, int(round(w * scale))),
                          height=max(1, int(round(h * scale))))
    except RenderTimeout:
        raise ValueError(f"the export could not be drawn within {EXPORT_SECONDS:g} s at "
                         f"{w * scale:.0f} x {h * scale:.0f} px, so resvg was stopped; export "
                         f"at a smaller scale, or as SVG") from None


def png_array(svg: str, canvas, scale: float = 1.0) -> np.ndarray:
    """``(H, W, 4)`` uint8 RGBA of ``svg`` rendered at ``scale``."""
    return np.array(Image.open(io.BytesIO(to_png(svg, canvas, scale))).convert("RGBA"))


def svg_size(svg: str) -> tuple[float, float]:
    """(width, height) of the root of an exported SVG."""
    m = re.match(r'<svg[^>]*? width="([0-9.]+)" height="([0-9.]+)"', svg)
    return float(m.group(1)), float(m.group(2))
