"""Marks: the pictures that units are drawn with.

A mark has a *box*, the tight bounding box of its visible content, of size
``box_size = (w, h)`` in the mark's own user units (SVG user units for vector
marks, pixels for raster marks). Silhouettes are float32 ``(h, w)`` alpha
images of exactly that box; fragments draw it over ``(0, 0)-(w, h)``.
Kinds: ``shape`` (built-in path), ``svg`` (sanitised icon), ``icon`` (a Font
Awesome icon by name, see ``icons``), ``image`` (raster with alpha) and
``sketch`` (round-capped polylines).
"""
from __future__ import annotations

import base64
import copy
import difflib
import functools
import json
import math
import os
import re
import xml.etree.ElementTree as ET

import numpy as np
from PIL import Image
from scipy import ndimage

from . import icons
from ..io import images, svgsafe
from .bounds import sketch_strokes
from .validate import short

DEFAULT_COLOR = "#4e79a7"
FOOTPRINTS = ("silhouette", "ink")   # what a mark collides with: ink with holes filled, or ink
FILL_FRACTION_SIDE = 512
_BOX_SEARCH_SIDE = 1024
MAX_ASPECT = 1e6   # a mark's width / height (and height / width) at most: float32 rendering
_ROOT_ONLY = {"width", "height", "viewBox", "x", "y", "preserveAspectRatio", "version",
              "baseProfile", "xmlns"}
_UNITS = {"": 1.0, "px": 1.0, "pt": 4 / 3, "pc": 16.0, "mm": 96 / 25.4, "cm": 96 / 2.54, "in": 96.0}
_RASTER_SUFFIXES = (".png", ".jpg", ".jpeg")


def _polygon(n: int, inner: float | None = None) -> str:
    """Path data of a regular n-gon (or n-pointed star) of radius 50, pointing up."""
    steps = 2 * n if inner else n
    pts = []
    for k in range(steps):
        r = inner * 50 if inner and k % 2 else 50
        a = math.radians(-90 + 360 * k / steps)
        pts.append(f"{50 + r * math.cos(a):.4f} {50 + r * math.sin(a):.4f}")
    return "M" + " L".join(pts) + " Z"


SHAPES = {
    "circle": "M0 50 A50 50 0 1 0 100 50 A50 50 0 1 0 0 50 Z",
    "square": "M0 0 H100 V100 H0 Z",
    "triangle": _polygon(3),
    "star": _polygon(5, inner=0.381966),
    "drop": "M50 0 C50 0 85 40 85 65 A35 35 0 0 1 15 65 C15 40 50 0 50 0 Z",
    "heart": ("M50 90 C20 70 0 50 0 28 C0 12 12 0 27 0 C38 0 46 6 50 15 "
              "C54 6 62 0 73 0 C88 0 100 12 100 28 C100 50 80 70 50 90 Z"),
    "hexagon": _polygon(6),
    "pentagon": _polygon(5),
    "diamond": "M50 0 L100 50 L50 100 L0 50 Z",
    "cross": "M35 0 H65 V35 H100 V65 H65 V100 H35 V65 H0 V35 H35 Z",
}


@functools.lru_cache(maxsize=None)
def _shape_box(name: str) -> tuple[float, float, float, float]:
    from svgpathtools import parse_path
    x0, x1, y0, y1 = (float(v) for v in parse_path(SHAPES[name]).bbox())
    return (x0, y0, x1 - x0, y1 - y0)


def _num(v: float) -> str:
    return format(float(v), ".10g")


def _pixel_size(aspect: float, max_side: int) -> tuple[int, int]:
    """(w, h) pixels with the long side ``max_side`` and the given w / h."""
    if aspect >= 1:
        return max_side, max(1, round(max_side / aspect))
    return max(1, round(max_side * aspect)), max_side


def _length(value: str | None) -> float:
    """An SVG length in px; 100 for a missing, relative or invalid one."""
    m = re.fullmatch(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?)\s*(px|pt|pc|mm|cm|in)?\s*",
                     value or "", re.I)
    px = float(m[1]) * _UNITS[(m[2] or "").lower()] if m else 0.0
    return px if math.isfinite(px) and px > 0 else 100.0


def _view(root: ET.Element) -> tuple[float, float, float, float]:
    """The root's viewBox ``(x, y, w, h)``, or ``(0, 0, width, height)`` in px."""
    vb = root.get("viewBox")
    if vb is None:
        return (0.0, 0.0, _length(root.get("width")), _length(root.get("height")))
    try:
        x, y, w, h = (float(v) for v in re.split(r"[\s,]+", vb.strip()))
    except ValueError:
        raise ValueError(f"SVG has an invalid viewBox {vb[:60]!r}") from None
    if not all(map(math.isfinite, (x, y, w, h))) or w <= 0 or h <= 0:
        raise ValueError(f"SVG has an invalid viewBox {vb[:60]!r}")
    return (x, y, w, h)


def _check_drawable(root: ET.Element, box, what: str) -> None:
    """A ValueError naming ``what`` unless the mark drawn in ``box`` has ink: an aspect
    within ``MAX_ASPECT`` and numbers resvg's 32-bit floats hold."""
    w, h = box[2], box[3]
    if not (w > 0 and h > 0 and 1 / MAX_ASPECT <= w / h <= MAX_ASPECT):
        raise ValueError(f"{what}: a mark {w:g} x {h:g} is more than {MAX_ASPECT:g} times wider "
                         f"than tall (or taller than wide); draw it less elongated")
    pw, ph = _pixel_size(w / h, 64)
    if not svgsafe.render_svg(_document(root, box), pw, ph)[..., 3].any():
        raise ValueError(f"{what}: draws nothing (numbers this large are past what the renderer "
                         f"holds); keep the points and the width under 1e30 and the width "
                         f"near the strokes' size")


def _embed(root: ET.Element, region, def_id: str, color: str | None) -> ET.Element:
    """``<g id=def_id>`` showing ``region = (x, y, w, h)`` of ``root`` over (0, 0)-(w, h)."""
    x, y, w, h = region
    attrs = {k: v for k, v in root.attrib.items() if k not in _ROOT_ONLY}
    wrapper = ET.Element("svg", attrs)
    wrapper.extend(copy.deepcopy(list(root)))
    wrapper.attrib.update(x="0", y="0", width=_num(w), height=_num(h),
                          viewBox=f"{_num(x)} {_num(y)} {_num(w)} {_num(h)}",
                          preserveAspectRatio="none")
    if "fill" not in attrs and svgsafe.uses_default_fill(root):
        wrapper.set("fill", "#000000")
    if "color" not in attrs and svgsafe.uses_current_color(root):
        wrapper.set("color", "#000000")
    svgsafe.scope(wrapper, def_id)
    if color is not None:
        svgsafe.recolor(wrapper, color)
    group = ET.Element("g", id=def_id)
    group.append(wrapper)
    return group


def _document(root: ET.Element, region, color: str | None = None) -> ET.Element:
    """A standalone ``<svg viewBox="0 0 w h">`` of ``region`` of ``root``."""
    doc = ET.Element("svg", viewBox=f"0 0 {_num(region[2])} {_num(region[3])}")
    doc.append(_embed(root, region, "m", color))
    return doc


def _edge_coverage(line: np.ndarray) -> float:
    """Share of the outermost pixel line that the content covers, in (0, 1].

    Only a straight edge (uniform partial alpha along the line) gives a
    sub-pixel answer; a curved one counts as fully covered, keeping the box loose.
    """
    values = line[line > 0]
    if len(values) >= 3 and int(values.max()) - int(np.median(values)) <= 2:
        return float(values.max()) / 255.0
    return 1.0


def _content_box(root: ET.Element) -> tuple[float, float, float, float]:
    """Tight box ``(x, y, w, h)``, in root user units, of the visible pixels.

    A coarse render of the whole view finds the content; a second render of
    that area refines the box to 1/1024 of its size (sub-pixel for straight edges).
    """
    view = region = _view(root)
    for _ in range(2):
        pw, ph = _pixel_size(region[2] / region[3], _BOX_SEARCH_SIDE)
        alpha = svgsafe.render_svg(_document(root, region), pw, ph)[..., 3]
        cols, rows = np.flatnonzero(alpha.any(axis=0)), np.flatnonzero(alpha.any(axis=1))
        if len(cols) == 0:
            raise ValueError("SVG mark is empty: nothing is visible after sanitising")
        sx, sy = region[2] / pw, region[3] / ph
        cx = (_edge_coverage(alpha[:, cols[0]]), _edge_coverage(alpha[:, cols[-1]])) \
            if len(cols) > 1 else (1.0, 1.0)
        cy = (_edge_coverage(alpha[rows[0]]), _edge_coverage(alpha[rows[-1]])) \
            if len(rows) > 1 else (1.0, 1.0)
        x0, x1 = region[0] + (cols[0] + 1 - cx[0]) * sx, region[0] + (cols[-1] + cx[1]) * sx
        y0, y1 = region[1] + (rows[0] + 1 - cy[0]) * sy, region[1] + (rows[-1] + cy[1]) * sy
        box = (float(x0), float(y0), float(x1 - x0), float(y1 - y0))
        left, top = max(view[0], x0 - sx), max(view[1], y0 - sy)
        right = min(view[0] + view[2], x1 + sx)
        bottom = min(view[1] + view[3], y1 + sy)
        region = (left, top, right - left, bottom - top)
    return box


def _check_def_id(def_id: str) -> None:
    if not isinstance(def_id, str) or not re.fullmatch(r"[A-Za-z_][\w-]*", def_id):
        raise ValueError(f"def_id must be an XML/CSS name such as 'mark-0', got {def_id!r}")


def _spec_error(spec) -> ValueError:
    text = repr(spec)
    text = text if len(text) <= 80 else text[:77] + "..."
    hint = ""
    if isinstance(spec, str):
        close = difflib.get_close_matches(spec.lower(), SHAPES, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
    return ValueError(
        f"unknown mark spec {text}{hint}: expected a Mark, a shape name "
        f"({', '.join(SHAPES)}), an icon name such as 'fa:apple-whole', SVG text, a path "
        "ending in .svg, .png, .jpg or .jpeg, a numpy array, a PIL image, or a mark dict "
        "with kind shape, svg, icon, image or sketch")


class Mark:
    """An immutable mark. Build one with :meth:`shape`, :meth:`svg`, :meth:`image`,
    :meth:`sketch`, :meth:`from_spec` or :meth:`from_json`."""

    __slots__ = ("kind", "_json", "_root", "_box", "_image", "_cache", "_hash", "solid")

    def __init__(self, kind: str, json_dict: dict, *, root=None, box=None, image=None,
                 solid: bool = False):
        for name, value in (("kind", kind), ("_json", json_dict), ("_root", root),
                            ("_box", box), ("_image", image), ("_cache", {}), ("_hash", None),
                            ("solid", solid)):
            object.__setattr__(self, name, value)

    def as_footprint(self, footprint: str) -> "Mark":
        """This mark as layout sees it under a layer's ``footprint`` (one of
        :data:`FOOTPRINTS`): ``"silhouette"`` fills the holes its ink encloses (a ring
        keeps other marks out of its middle), ``"ink"`` collides with the ink alone.
        Both draw the same ink; only :meth:`silhouette` differs."""
        check_footprint("footprint", footprint)
        solid = footprint == "silhouette"
        if solid == self.solid:
            return self
        return Mark(self.kind, self._json, root=self._root, box=self._box, image=self._image,
                    solid=solid)

    def __setattr__(self, name, value):
        raise AttributeError("Mark is immutable")

    # --- constructors -------------------------------------------------------
    @classmethod
    def shape(cls, name: str) -> "Mark":
        """A built-in shape; ``name`` is one of :data:`SHAPES`."""
        if not isinstance(name, str) or name not in SHAPES:
            raise _spec_error(name)
        box = _shape_box(name)
        root = ET.Element("svg", viewBox=" ".join(map(_num, box)))
        ET.SubElement(root, "path", d=SHAPES[name], fill=DEFAULT_COLOR)
        return cls("shape", {"kind": "shape", "name": name}, root=root, box=box)

    @classmethod
    def svg(cls, source: str | bytes | os.PathLike) -> "Mark":
        """An SVG icon from SVG text (starting with ``<``), SVG bytes, or a file path."""
        if isinstance(source, str) and source.lstrip("\ufeff \t\r\n").startswith("<"):
            text = source
        elif isinstance(source, (bytes, bytearray)):
            text = bytes(source)
        elif isinstance(source, (str, os.PathLike)):
            path = os.fspath(source)
            try:
                with open(path, "rb") as fp:
                    size = os.fstat(fp.fileno()).st_size
                    if size > svgsafe.MAX_SVG_BYTES:
                        raise ValueError(f"SVG file {short(path)} is {size:,} bytes, over the "
                                         f"limit of {svgsafe.MAX_SVG_BYTES:,} bytes (5 MB)")
                    text = fp.read(svgsafe.MAX_SVG_BYTES + 1)
            except OSError as exc:
                raise ValueError(f"cannot read SVG file {short(path)}: {exc.strerror or exc}") from None
        else:
            raise ValueError(f"expected SVG text or a path, got {type(source).__name__}")
        root = svgsafe.parse_svg(text)
        box = _content_box(root)
        return cls("svg", {"kind": "svg", "svg": svgsafe.serialize(root)}, root=root, box=box)

    @classmethod
    def icon(cls, name: str) -> "Mark":
        """A Font Awesome Free icon by name, ``"fa:apple-whole"`` (see ``icons``)."""
        if not icons.is_icon_name(name):
            raise _spec_error(name)
        return _icon(name)

    @classmethod
    def image(cls, source, key: str | None = "auto", tolerance: float = 0.1) -> "Mark":
        """A raster mark from a PNG/JPEG path, bytes, data URL, array or PIL image.

        Alpha is used when some pixel is not opaque; otherwise ``key="auto"``
        removes a uniform border-coloured background (within ``tolerance``,
        in [0, 1]); ``key`` may also be a CSS colour; ``key=None`` keeps all.
        """
        if not 0 <= tolerance <= 1:
            raise ValueError(f"tolerance must be in [0, 1], got {tolerance!r}")
        img = images.load_image(source)
        if not images.has_transparency(img) and key is not None:
            img = images.key_background(img, key, tolerance)
        img = images.crop_to_alpha(img)
        return cls("image", {"kind": "image", "image": images.image_data_url(img)},
                   box=(0.0, 0.0, float(img.width), float(img.height)), image=img)

    @classmethod
    def sketch(cls, strokes, width: float = 3.0, color: str = "#222") -> "Mark":
        """Hand-drawn strokes: a list of ``(k, 2)`` polylines (any units, y down),
        drawn with round caps and joins of stroke ``width`` in the same units."""
        width = float(width)
        if not math.isfinite(width) or width <= 0:
            raise ValueError(f"sketch width must be a positive number, got {width!r}")
        if svgsafe.parse_color(color) is None:
            raise ValueError(f"sketch color must be a CSS colour, got {color!r}")
        strokes = sketch_strokes(strokes)
        try:
            lines = [np.asarray(s, dtype=np.float64).reshape(-1, 2) for s in strokes]
        except (TypeError, ValueError):
            raise ValueError("sketch strokes must be a list of (k, 2) point lists") from None
        lines = [line for line in lines if len(line)]
        if not lines or not all(np.isfinite(line).all() for line in lines):
            raise ValueError("sketch needs at least one stroke of finite (x, y) points")
        pts = np.concatenate(lines)
        lo, hi = pts.min(axis=0) - width / 2, pts.max(axis=0) + width / 2
        box = tuple(float(v) for v in (lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1]))
        root = ET.Element("svg", viewBox=" ".join(map(_num, box)))
        group = ET.SubElement(root, "g", {"fill": "none", "stroke": color,
                                          "stroke-width": _num(width), "stroke-linecap": "round",
                                          "stroke-linejoin": "round"})
        for line in lines:
            if len(line) == 1:
                ET.SubElement(group, "circle", cx=_num(line[0, 0]), cy=_num(line[0, 1]),
                              r=_num(width / 2), fill=color, stroke="none")
            else:
                d = "M" + " L".join(f"{_num(x)} {_num(y)}" for x, y in line)
                ET.SubElement(group, "path", d=d)
        span = pts.max(axis=0) - pts.min(axis=0)
        _check_drawable(root, box, f"sketch (width {width:g}, points spanning "
                                   f"{span[0]:g} x {span[1]:g})")
        spec = {"kind": "sketch", "strokes": [line.tolist() for line in lines],
                "width": width, "color": color}
        return cls("sketch", spec, root=root, box=box)

    @classmethod
    def from_spec(cls, spec) -> "Mark":
        """A Mark from anything users pass as ``mark=`` (see module doc)."""
        if isinstance(spec, Mark):
            return spec
        if isinstance(spec, dict):
            return cls.from_json(spec)
        if isinstance(spec, (np.ndarray, Image.Image)):
            return cls.image(spec)
        if isinstance(spec, str) and spec in SHAPES:
            return cls.shape(spec)
        if icons.is_icon_name(spec):
            return cls.icon(spec)
        if isinstance(spec, str) and spec.lstrip("\ufeff \t\r\n").startswith("<"):
            return cls.svg(spec)
        if isinstance(spec, (str, os.PathLike)):
            suffix = os.path.splitext(os.fspath(spec))[1].lower()
            if suffix == ".svg":
                return cls.svg(spec)
            if suffix in _RASTER_SUFFIXES:
                return cls.image(spec)
        raise _spec_error(spec)

    @classmethod
    def from_json(cls, d: dict) -> "Mark":
        """Inverse of :meth:`to_json`."""
        kind = d.get("kind") if isinstance(d, dict) else None
        try:
            if kind == "shape":
                return cls.shape(d["name"])
            if kind == "svg":
                return cls.svg(d["svg"])
            if kind == "icon":
                return cls.icon(d["name"])
            if kind == "image":
                return cls.image(images.decode_data_url(d["image"]), key=None)
            if kind == "sketch":
                return cls.sketch(d["strokes"], d.get("width", 3.0), d.get("color", "#222"))
        except KeyError as exc:
            raise ValueError(f"mark dict of kind {kind!r} lacks the key {exc}") from None
        raise _spec_error(d)

    # --- geometry -----------------------------------------------------------
    @property
    def box_size(self) -> tuple[float, float]:
        """(w, h) of the box in the fragment's user units."""
        return (float(self._box[2]), float(self._box[3]))

    @property
    def aspect(self) -> float:
        """Box width / box height."""
        return self._box[2] / self._box[3]

    @property
    def fill_fraction(self) -> float:
        """Silhouette area / box area in (0, 1], on a 512-px silhouette."""
        if "fill" not in self._cache:
            self._cache["fill"] = float(self.silhouette(FILL_FRACTION_SIDE).mean())
        return self._cache["fill"]

    def silhouette(self, max_side: int) -> np.ndarray:
        """float32 ``(h, w)`` footprint in [0, 1] of the box, long side ``max_side`` px.

        The footprint is where the mark has ink, whatever its opacity: SVG marks
        render with every opacity at 1, raster alpha counts double (so a
        half-transparent pixel is occupied), and edges stay anti-aliased.

        A :attr:`solid` mark (see :meth:`as_footprint`) also covers every hole its
        ink encloses, at full alpha.

        The render is cached per ``max_side`` (for every equal mark in the
        process: a new chart with the same marks renders nothing); each call
        returns a fresh copy.
        """
        max_side = int(max_side)
        if not 1 <= max_side <= 8192:
            raise ValueError(f"max_side must be in [1, 8192], got {max_side}")
        if max_side not in self._cache:
            self._cache[max_side] = _silhouette(self, max_side)
        return self._cache[max_side].copy()

    def _render(self, max_side: int) -> np.ndarray:
        size = _pixel_size(self.aspect, max_side)
        if self._image is not None:
            alpha = np.minimum(2.0 * images.resize_alpha(self._image, size), 1.0)
        else:
            rgba = svgsafe.render_svg(_document(self._root, self._box), *size, opaque=True,
                                      keep=True)   # for other processes too
            alpha = rgba[..., 3].astype(np.float32) / 255.0
        if self.solid:
            ink = alpha >= 0.5
            alpha = np.where(ndimage.binary_fill_holes(ink) & ~ink, np.float32(1), alpha)
        return alpha

    # --- output -------------------------------------------------------------
    def svg_fragment(self, def_id: str, color: str | None = None) -> str:
        """``<g id="{def_id}">`` drawing the mark over (0, 0)-(box_w, box_h),
        ids and classes prefixed with ``def_id``, recoloured or tinted to ``color``."""
        _check_def_id(def_id)
        if color is not None and svgsafe.parse_color(color) is None:
            raise ValueError(f"not a CSS colour: {color!r}")
        if self._image is not None:
            img = self._image if color is None else images.tint(self._image, color)
            group = ET.Element("g", id=def_id)
            ET.SubElement(group, "image", x="0", y="0", width=str(img.width),
                          height=str(img.height), preserveAspectRatio="none",
                          href=images.image_data_url(img))
        else:
            group = _embed(self._root, self._box, def_id, color)
        return ET.tostring(group, encoding="unicode")

    def to_svg(self, color: str | None = None, max_side: int = 512) -> str:
        """A standalone SVG document of the box, ``max_side`` px on its long side."""
        w, h = _pixel_size(self.aspect, max_side)
        bw, bh = self.box_size
        return (f'<svg xmlns="{svgsafe.SVG_NS}" width="{w}" height="{h}" '
                f'viewBox="0 0 {_num(bw)} {_num(bh)}" preserveAspectRatio="none">'
                f'{self.svg_fragment("mark", color)}</svg>')

    def data_url(self) -> str:
        """``data:image/svg+xml;base64,...`` (vector) or ``data:image/png;base64,...`` (raster)."""
        if self._image is not None:
            return self._json["image"]
        return "data:image/svg+xml;base64," + base64.b64encode(self.to_svg().encode()).decode()

    def to_json(self) -> dict:
        """The protocol dict (see docs/protocol.md)."""
        return copy.deepcopy(self._json)

    def __eq__(self, other):
        return isinstance(other, Mark) and self._json == other._json and self.solid == other.solid

    def __hash__(self):
        if self._hash is None:
            object.__setattr__(self, "_hash", hash((json.dumps(self._json, sort_keys=True),
                                                    self.solid)))
        return self._hash

    def __repr__(self):
        name = f" {self._json['name']!r}" if self.kind in ("shape", "icon") else ""
        return f"<Mark {self.kind}{name} aspect={self.aspect:.3g}>"


def check_footprint(name: str, value) -> str:
    """``value`` if it is one of :data:`FOOTPRINTS`, else a ValueError naming ``name``."""
    if not isinstance(value, str) or value not in FOOTPRINTS:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, FOOTPRINTS))} "
                         f"(\"silhouette\": holes the ink encloses are filled; \"ink\": marks may "
                         f"nest in each other's holes), got {value!r}")
    return value


@functools.lru_cache(maxsize=128)
def _silhouette(mark: Mark, max_side: int) -> np.ndarray:
    """``Mark.silhouette``'s render, shared by equal marks (marks are immutable)."""
    return mark._render(max_side)


@functools.lru_cache(maxsize=256)
def _icon(name: str) -> Mark:
    """The icon mark of ``name``, parsed and measured once per name (marks are immutable)."""
    root = svgsafe.parse_svg(icons.read_svg(name))
    return Mark("icon", {"kind": "icon", "name": name}, root=root, box=_content_box(root))
