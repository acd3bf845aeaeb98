"""SVG safety: parse untrusted SVG into a clean tree, serialise it, render it.

A sanitised tree has local tag names (no namespace), SVG attributes, plain
``href`` (never ``xlink:href``) pointing only at ``#id`` or ``data:image/...``,
no scripts, event handlers, foreign content or external URLs. Only sanitised
text is ever given to the renderer, which sees an empty resources directory.
"""
from __future__ import annotations

import base64
import io
import re
import tempfile
import xml.etree.ElementTree as ET

import numpy as np
from defusedxml import DefusedXmlException
from defusedxml.ElementTree import DefusedXMLParser
from PIL import Image, ImageColor

from . import rendercache
from .images import MAX_PIXELS, parse_data_url, probe_size
from .svgcost import cap_filters
from .svgworker import RENDER_SECONDS, RenderTimeout, svg_to_png

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
XML_NS = "http://www.w3.org/XML/1998/namespace"
MAX_SVG_BYTES = 5_000_000
MAX_SVG_ELEMENTS = 50_000
MAX_SVG_DEPTH = 200
_DROPPED = {"script", "foreignobject", "iframe", "embed", "object", "handler", "listener"}
_ANIMATIONS = {"animate", "set", "animatetransform", "animatemotion", "animatecolor"}
_XML_KEPT = {"space", "lang"}
_URL = re.compile(r"""url\(\s*(['"]?)(.*?)\1\s*\)""", re.I | re.S)
_IMPORT = re.compile(r"@import[^;]*(;|$)", re.I)
_URL_FUNCS = re.compile(r"(?<![\w-])(?:-webkit-)?(?:image-set|image|cross-fade|src|element)\s*\("
                        r"[^()]*(?:\([^()]*\)[^()]*)*\)?", re.I)
_ESCAPED = re.compile(r"[^;{}]*\\[^;{}]*")


class _Builder(ET.TreeBuilder):
    """A tree builder that refuses too many or too deeply nested elements."""

    def __init__(self):
        super().__init__()
        self.count = 0
        self.depth = 0

    def start(self, tag, attrs):
        self.count += 1
        self.depth += 1
        if self.count > MAX_SVG_ELEMENTS:
            raise ValueError(f"SVG has more than the limit of {MAX_SVG_ELEMENTS:,} elements")
        if self.depth > MAX_SVG_DEPTH:
            raise ValueError(f"SVG nests elements deeper than the limit of {MAX_SVG_DEPTH} levels")
        return super().start(tag, attrs)

    def end(self, tag):
        self.depth -= 1
        return super().end(tag)


def _split(name: str) -> tuple[str | None, str]:
    if name.startswith("{"):
        ns, local = name[1:].split("}", 1)
        return ns, local
    return None, name


def _clean_data_image(url: str, nested: int) -> str | None:
    """The data:image URL itself if safe (nested SVG is sanitised), else None."""
    try:
        mime, payload = parse_data_url(url)
    except ValueError:
        return None
    if mime == "image/svg+xml":
        if nested >= 1:
            return None
        try:
            clean = sanitize_svg(payload, _nested=nested + 1)
        except ValueError:
            return None
        return "data:image/svg+xml;base64," + base64.b64encode(clean.encode()).decode()
    size = probe_size(payload)
    if size is None or size[0] * size[1] > MAX_PIXELS:
        return None
    return url.strip()


def _clean_url(url: str, nested: int) -> str | None:
    """``url`` if it is an in-document ``#id`` or a safe data:image URL, else None."""
    url = url.strip()
    if re.fullmatch(r"#[^\s#'\"()<>]+", url):
        return url
    if url[:11].lower() == "data:image/":
        return _clean_data_image(url, nested)
    return None


def clean_css(css: str, nested: int = 0) -> str:
    """CSS without ``@import``, escapes, or ``url()`` other than ``#id``/data:image.

    Declarations or selectors containing a backslash escape are removed whole,
    and URL-taking functions other than ``url()`` become ``none``.
    """
    css = _IMPORT.sub("", _ESCAPED.sub("", css))
    css = _URL_FUNCS.sub("none", css)

    def repl(m: re.Match) -> str:
        url = _clean_url(m.group(2), nested)
        if url is None:
            return "none"
        return f"url({url})" if url.startswith("#") else f'url("{url}")'
    return _URL.sub(repl, css)


def _clean_element(el: ET.Element, nested: int) -> None:
    """Rewrite one element's tag and attributes in place (children untouched)."""
    el.tag = _split(el.tag)[1]
    attrs = {}
    for name, value in el.attrib.items():
        ns, local = _split(name)
        if ns not in (None, XLINK_NS, XML_NS) or local.lower().startswith("on"):
            continue
        if ns == XML_NS:
            if local in _XML_KEPT:
                attrs[name] = value
            continue
        if local == "href":
            url = None if el.tag == "a" else _clean_url(value, nested)
            if url is not None:
                attrs["href"] = url
            continue
        if ns == XLINK_NS:
            continue
        if local == "style" or "url(" in value.lower() or "(" in value and _URL_FUNCS.search(value):
            value = clean_css(value, nested)
        attrs[local] = value
    el.attrib.clear()
    el.attrib.update(attrs)
    if el.tag == "style" and el.text:
        el.text = clean_css(el.text, nested)


def _unwanted(el: ET.Element) -> bool:
    ns, local = _split(el.tag) if isinstance(el.tag, str) else ("", "")
    if ns not in (None, SVG_NS) or local.lower() in _DROPPED:
        return True
    if local.lower() in _ANIMATIONS:
        target = _split(el.get("attributeName", ""))[1].strip().lower()
        return target == "href" or target.startswith("on") or ":" in target
    return False


def parse_svg(text: str | bytes, _nested: int = 0) -> ET.Element:
    """Parse untrusted SVG text or bytes into a sanitised tree (see module doc).

    Raises ValueError for entity declarations, malformed XML, a root that is
    not ``svg``, or input over :data:`MAX_SVG_BYTES` / :data:`MAX_SVG_ELEMENTS`.
    Costly filter primitives are capped, with a warning (``svgcost.cap_filters``).
    """
    if isinstance(text, (bytes, bytearray, memoryview)):
        data = bytes(text)
        size = len(data)
    elif isinstance(text, str):
        data = text.lstrip("\ufeff")
        size = len(data) if len(data) * 4 <= MAX_SVG_BYTES else len(data.encode("utf-8", "replace"))
    else:
        raise ValueError(f"expected SVG text, got {type(text).__name__}")
    if size > MAX_SVG_BYTES:
        raise ValueError(f"SVG is {size:,} bytes, over the limit of {MAX_SVG_BYTES:,} bytes (5 MB)")
    builder = _Builder()
    parser = DefusedXMLParser(target=builder, forbid_dtd=False, forbid_entities=True,
                              forbid_external=True)
    try:
        parser.feed(data)
        root = parser.close()
    except DefusedXmlException as exc:
        raise ValueError(f"SVG refused: it declares an XML entity or external reference "
                         f"({type(exc).__name__}); entity declarations are not allowed") from None
    except ET.ParseError as exc:
        raise ValueError(f"SVG is not well-formed XML: {exc}") from None
    except (UnicodeError, RecursionError, OverflowError) as exc:
        raise ValueError(f"SVG could not be parsed: {exc}") from None
    if _split(root.tag) not in ((None, "svg"), (SVG_NS, "svg")):
        raise ValueError(f"not an SVG document: the root element is "
                         f"<{_split(root.tag)[1]}>, not <svg>")
    _clean_element(root, _nested)
    stack = [root]
    while stack:
        parent = stack.pop()
        for child in list(parent):
            if _unwanted(child):
                parent.remove(child)
                continue
            _clean_element(child, _nested)
            stack.append(child)
    cap_filters(root)
    return root


def _shallow(root: ET.Element, **attrs: str) -> ET.Element:
    """A new root with ``root``'s attributes updated by ``attrs``, sharing its children."""
    out = ET.Element(root.tag, {k: v for k, v in root.attrib.items() if k != "xmlns"})
    out.attrib.update(attrs)
    out.text = root.text
    out.extend(list(root))
    return out


def serialize(root: ET.Element) -> str:
    """Standalone SVG text of a sanitised tree (the tree is not modified)."""
    return ET.tostring(_shallow(root, xmlns=SVG_NS), encoding="unicode")


def sanitize_svg(text: str | bytes, _nested: int = 0) -> str:
    """Sanitised, well-formed, standalone SVG text (see :func:`parse_svg`)."""
    return serialize(parse_svg(text, _nested))


OPAQUE_CSS = "* { opacity: 1 !important; fill-opacity: 1 !important; stroke-opacity: 1 !important }"


def render_svg(root: ET.Element, width: int, height: int, opaque: bool = False,
               keep: bool = False) -> np.ndarray:
    """uint8 ``(height, width, 4)`` straight RGBA of a sanitised tree.

    The root's own ``width``/``height`` are replaced by the pixel size, so its
    viewBox (or user space) is stretched over exactly ``width x height`` pixels.
    ``opaque`` renders every element at full opacity: the footprint a mark
    occupies, however translucent its paint. resvg runs in a worker process
    (``svgworker``): Ctrl-C stops it, and a render past ``RENDER_SECONDS`` is refused.
    ``keep``: the render is kept on disk for other processes, and read from there when
    kept (``rendercache``).
    """
    if width < 1 or height < 1 or width * height > MAX_PIXELS:
        raise ValueError(f"render size {width} x {height} is out of range")
    text = serialize(_shallow(root, width=str(int(width)), height=str(int(height)),
                              preserveAspectRatio="none"))
    style = OPAQUE_CSS if opaque else None
    file = rendercache.name(text, style) if keep else None
    png = None if file is None else rendercache.load(file)
    if png is None:
        png = _render(root, text, width, height, style)
        if file is not None:
            rendercache.store(file, png)
    with Image.open(io.BytesIO(png)) as img:
        rgba = np.asarray(img.convert("RGBA"))
    if rgba.shape[:2] != (height, width):
        out = np.zeros((height, width, 4), np.uint8)
        h, w = min(height, rgba.shape[0]), min(width, rgba.shape[1])
        out[:h, :w] = rgba[:h, :w]
        rgba = out
    return rgba


def _render(root: ET.Element, text: str, width: int, height: int, style: str | None) -> bytes:
    """resvg's PNG bytes of ``text`` (the serialised ``root`` at ``width x height``) with the
    style sheet ``style``."""
    with tempfile.TemporaryDirectory(prefix="unitopia-svg-") as empty:
        try:
            return bytes(svg_to_png(RENDER_SECONDS, svg_string=text, resources_dir=empty,
                                    style_sheet=style))
        except RenderTimeout:
            raise ValueError(f"SVG could not be drawn at {width} x {height} px within "
                             f"{RENDER_SECONDS:g} s, so resvg was stopped ({_costliest(root)}); "
                             f"simplify the mark") from None
        except (KeyboardInterrupt, SystemExit):
            raise
        except BaseException as exc:  # resvg panics surface as BaseException
            raise ValueError(f"SVG could not be rendered: {exc}") from None


def _costliest(root: ET.Element) -> str:
    """The elements that likely made a render slow: its filter primitives, else a count."""
    kinds = sorted({el.tag for el in root.iter() if isinstance(el.tag, str)
                    and el.tag.lower().startswith("fe")})
    if kinds:
        return "its filter primitives: " + ", ".join(f"<{k}>" for k in kinds)
    return f"{sum(1 for _ in root.iter()):,} elements"


# --- Rewriting a sanitised tree for embedding: scoping and recolouring -------

PAINT_PROPERTIES = ("fill", "stroke", "stop-color", "flood-color", "lighting-color", "color")
_SHAPES = {"path", "rect", "circle", "ellipse", "polygon", "polyline", "line", "text", "use"}
_NON_PAINTING = {"clippath", "mask", "pattern", "marker", "symbol", "defs", "lineargradient",
                 "radialgradient", "filter", "style", "title", "desc", "metadata"}
_DECL = re.compile(r"(?P<prop>[A-Za-z-]+)(?P<sep>\s*:\s*)(?P<value>[^;{}]*)")
_NAME = r"-?[A-Za-z_][\w-]*"


_ENTERED = ("@media", "@supports", "@container", "@layer")


def _blocks(css: str):
    """Split CSS into ``(head, body)`` pairs at depth 0: ``body`` is the text inside a
    rule's braces, or None for text ending in ``;`` (a declaration or a statement)."""
    pos = 0
    while pos < len(css):
        brace, semi = css.find("{", pos), css.find(";", pos)
        if brace < 0 or 0 <= semi < brace:
            stop = len(css) if semi < 0 else semi + 1
            yield css[pos:stop], None
            pos = stop
            continue
        depth, end = 1, brace + 1
        while end < len(css) and depth:
            depth += {"{": 1, "}": -1}.get(css[end], 0)
            end += 1
        yield css[pos:brace].strip(), css[brace + 1:end - 1]
        pos = end


def _css_blocks(css: str, selector_fn, decl_fn, nested: bool = False) -> str:
    """Rewrite CSS rule by rule: selectors through ``selector_fn``, declarations through
    ``decl_fn``; rules nested in a rule (CSS nesting) have their names renamed by
    ``selector_fn(s, nested=True)`` and stay relative to the scoped rule around them.

    Only the at-rules that hold rules and style nothing themselves (``@media``,
    ``@supports``, ``@container``, block ``@layer``) are entered; every other at-rule
    (``@scope``, ``@font-face``, ``@keyframes``, ``@layer a, b;``, ``@charset``, ...) is
    dropped, so no rule of a mark's CSS can reach outside the element it is scoped to.
    """
    css = re.sub(r"/\*.*?\*/", "", css, flags=re.S)
    out = []
    for head, body in _blocks(css):
        head = head.strip()
        if body is None:
            if nested and not head.startswith("@") and head.count('"') % 2 == 0 \
                    and head.count("'") % 2 == 0:
                out.append(decl_fn(head))
        elif head.startswith("@"):
            if head.lower().startswith(_ENTERED):
                out.append(f"{head}{{{_css_blocks(body, selector_fn, decl_fn, nested)}}}")
        elif head:
            selectors = ",".join(selector_fn(s.strip(), nested=nested) for s in head.split(",")
                                 if s.strip())
            out.append(f"{selectors}{{{_css_blocks(body, selector_fn, decl_fn, True)}}}")
    return ("" if nested else "\n").join(out)


def _map_declarations(body: str, fn) -> str:
    """Apply ``fn(property, value) -> value`` to each ``property: value`` declaration."""
    return _DECL.sub(lambda m: m["prop"] + m["sep"] + fn(m["prop"].lower(), m["value"]), body)


def _attribute_pass(root: ET.Element, attr_fn, decl_fn, selector_fn) -> None:
    """Visit every attribute (``attr_fn(name, value) -> value``), style attribute and <style>."""
    for el in root.iter():
        for name, value in list(el.attrib.items()):
            if name == "style":
                el.set(name, _map_declarations(value, decl_fn))
            else:
                el.set(name, attr_fn(name, value))
        if el.tag == "style" and el.text:
            el.text = _css_blocks(el.text, selector_fn, lambda b: _map_declarations(b, decl_fn))


def rename_selector(selector: str, rename, kinds: str = ".#") -> str:
    """``selector`` with each ``.class`` and ``#id`` name (those of ``kinds``) passed
    through ``rename``; attribute selectors ``[...]`` are left as they are."""
    parts = re.split(r"(\[[^\]]*\])", selector)
    for i in range(0, len(parts), 2):
        parts[i] = re.sub(rf"([{re.escape(kinds)}])({_NAME})",
                          lambda m: f"{m[1]}{rename(m[2])}", parts[i])
    return "".join(parts)


def rename_ids(css: str, rename) -> str:
    """``css`` with every ``#id`` in its selectors passed through ``rename`` (declarations,
    where ``#`` starts a colour, unchanged); used where a document's ids are renamed."""
    def selector_fn(selector, nested=False):
        return rename_selector(selector, rename, "#")
    return _css_blocks(css, selector_fn, lambda body: body)


def scope(root: ET.Element, prefix: str) -> None:
    """Prefix ids and class names with ``prefix-`` and confine CSS rules to ``#prefix``.

    Rewrites references (``href="#id"``, ``url(#id)``) to match, so several
    marks sharing class names or ids can live in one document.
    """
    rename_urls = lambda v: re.sub(r"url\(\s*(['\"]?)#", lambda m: f"url({m[1]}#{prefix}-", v)

    def attr_fn(name, value):
        if name in ("id", "class"):
            return " ".join(f"{prefix}-{token}" for token in value.split())
        if name == "href" and value.startswith("#"):
            return f"#{prefix}-{value[1:]}"
        return rename_urls(value)

    def selector_fn(selector, nested=False):
        renamed = rename_selector(selector, lambda name: f"{prefix}-{name}")
        return renamed if nested else f"#{prefix} {renamed}"

    _attribute_pass(root, attr_fn, lambda prop, value: rename_urls(value), selector_fn)


def parse_color(value: str) -> tuple[int, int, int] | None:
    """(r, g, b) of a CSS colour value, or None for none/url()/currentColor/unparseable."""
    if not isinstance(value, str):
        return None
    value = re.sub(r"\s*!important\s*$", "", value.strip(), flags=re.I)
    if not value or value.lower() in ("none", "currentcolor", "inherit", "transparent"):
        return None
    try:
        return tuple(ImageColor.getrgb(value)[:3])
    except ValueError:
        return None


def _paint_pass(root: ET.Element, fn) -> None:
    """Apply ``fn(rgb, value) -> value`` to every paint colour in ``root``."""
    def on_value(prop, value):
        rgb = parse_color(value) if prop in PAINT_PROPERTIES else None
        return value if rgb is None else fn(rgb, value)
    _attribute_pass(root, on_value, on_value, lambda s, nested=False: s)


def paint_colors(root: ET.Element) -> list[tuple[int, int, int]]:
    """The distinct paint colours used in ``root``, in order of appearance."""
    found: list[tuple[int, int, int]] = []
    _paint_pass(root, lambda rgb, value: found.append(rgb) or value)
    return list(dict.fromkeys(found))


def uses_default_fill(root: ET.Element) -> bool:
    """True if some painting element inherits the initial fill (black) from no one.

    Approximation: any ``<style>`` that mentions ``fill`` counts as setting it.
    """
    if any("fill" in (el.text or "") for el in root.iter("style")):
        return False
    stack = [(root, False)]
    while stack:
        el, has_fill = stack.pop()
        if el.tag.lower() in _NON_PAINTING:
            continue
        has_fill = has_fill or "fill" in el.attrib or "fill" in el.get("style", "")
        if el.tag in _SHAPES and not has_fill:
            return True
        stack.extend((child, has_fill) for child in el)
    return False


def uses_current_color(root: ET.Element) -> bool:
    """True if some attribute or <style> rule of ``root`` paints with ``currentColor``."""
    return any("currentcolor" in v.lower() for el in root.iter()
               for v in [*el.attrib.values(), (el.text or "") if el.tag == "style" else ""])


def recolor(root: ET.Element, color: str) -> None:
    """Recolour an icon in place to ``color``, keeping its shading.

    One paint colour: it is replaced. Several, some of them neither near-white
    nor near-black: a tint. The median luminance of those middle colours
    becomes ``color`` itself; darker paints (gradient stops too) become
    ``color`` darkened in proportion, lighter ones ``color`` lightened towards
    white, so every distinct luminance stays distinct and in order, black stays
    black and white stays white. If all are near-black or near-white, the
    near-black ones are replaced and the white details stay.
    """
    target = parse_color(color)
    if target is None:
        raise ValueError(f"not a CSS colour: {color!r}")
    colors = paint_colors(root)
    near_white = {c for c in colors if min(c) >= 230}
    near_black = {c for c in colors if max(c) <= 40}
    middle = set(colors) - near_white - near_black
    hex_color = "#%02x%02x%02x" % target
    if len(colors) == 1 or not middle:
        chosen = set(colors) if len(colors) == 1 else near_black or set(colors)
        _paint_pass(root, lambda rgb, value: hex_color if rgb in chosen else value)
        return
    base = float(np.median([luma(c) for c in middle]))
    _paint_pass(root, lambda rgb, value: "#%02x%02x%02x" % shade(target, luma(rgb), base))


def luma(rgb) -> float:
    """Luminance of an sRGB colour, 0 to 255 (Rec. 709 weights on the coded values)."""
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]


def shade(target, lum: float, base: float) -> tuple[int, int, int]:
    """``target`` (r, g, b) as a paint of luminance ``lum`` in a mark whose middle luminance
    is ``base`` (0 to 255, ``0 < base < 255``): darkened towards black below ``base``,
    lightened towards white above, white at 255."""
    t = np.asarray(target, dtype=float)
    out = t * lum / base if lum <= base else t + (255.0 - t) * (lum - base) / (255.0 - base)
    return tuple(int(round(v)) for v in np.clip(out, 0, 255))
