"""Containers: the regions marks are packed into.

Coordinates are canvas pixels, x right, y down; a canvas size is
``(width, height)``. A container is immutable: :meth:`Container.cut` returns a
new one. Vector kinds (``canvas``, ``rect``, ``ellipse``, ``polygon``, ``path``)
keep their geometry; image kinds keep a boolean mask ``(h, w)`` stretched over
a box (the whole canvas unless given). Polygons and paths fill even-odd, so
nested subpaths are holes. Rasterisation lives in :mod:`.regions`.
"""
from __future__ import annotations

import copy
import io
import math
import warnings

import numpy as np
from PIL import Image

from . import regions
from .bounds import MAX_CONTAINER_POINTS, MAX_CUTS, MAX_PATH_CHARS, check_length
from ..io.images import check_pixels, image_data_url, load_image
from .validate import (check_box, check_canvas_size, check_coord, check_finite, check_points,
                       check_positive)

KINDS = ("canvas", "rect", "ellipse", "polygon", "path", "image")
MAX_INSIDE_SHARE, MIN_INSIDE_SHARE = 0.9, 0.001  # image containers outside these warn
_FIELDS = {"canvas": (), "rect": ("x", "y", "w", "h"), "ellipse": ("cx", "cy", "rx", "ry"),
           "polygon": ("points",), "path": ("d",), "image": ("image",)}


def _num(v: float) -> str:
    """A number for SVG path data: at most 3 decimals, no trailing zeros."""
    s = f"{v:.3f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


class Container:
    """A region of the canvas. Build one with the class methods, never directly."""

    __hash__ = None

    def __init__(self, kind: str, params: dict, *, rings=None, mask=None, cuts=()):
        self._kind = kind
        self._params = params          # the kind's JSON fields (without "cuts")
        self._rings = rings            # polygon / path: list of (k, 2) float64
        self._mask = mask              # image: bool (h, w)
        self._cuts = tuple(cuts)       # ((k, 2) float64 points, width px)
        self._cache: dict = {}

    kind = property(lambda self: self._kind, doc="One of :data:`KINDS`.")

    # ---- constructors -------------------------------------------------------------
    @classmethod
    def canvas(cls) -> "Container":
        """The whole canvas."""
        return cls("canvas", {})

    @classmethod
    def rect(cls, x, y, w, h) -> "Container":
        """The rectangle with top-left corner (x, y) and size w x h (canvas px)."""
        o = "Container.rect"
        return cls("rect", {"x": check_coord(o, "x", x), "y": check_coord(o, "y", y),
                            "w": check_coord(o, "w", check_positive(o, "w", w)),
                            "h": check_coord(o, "h", check_positive(o, "h", h))})

    @classmethod
    def ellipse(cls, cx, cy, rx, ry) -> "Container":
        """The axis-aligned ellipse with centre (cx, cy) and radii rx, ry (canvas px)."""
        o = "Container.ellipse"
        return cls("ellipse", {"cx": check_coord(o, "cx", cx), "cy": check_coord(o, "cy", cy),
                               "rx": check_coord(o, "rx", check_positive(o, "rx", rx)),
                               "ry": check_coord(o, "ry", check_positive(o, "ry", ry))})

    @classmethod
    def polygon(cls, points) -> "Container":
        """The polygon through ``points`` (k, 2), k >= 3, closed, filled even-odd."""
        check_length("Container.polygon: points", points, MAX_CONTAINER_POINTS, "vertices")
        pts = check_points("Container.polygon", "points", points, 3)
        _check_area("Container.polygon", "points", [pts])
        return cls("polygon", {"points": pts.tolist()}, rings=[pts])

    @classmethod
    def path(cls, d: str) -> "Container":
        """The even-odd fill of SVG path data ``d`` (canvas px): several subpaths,
        each closed; holes allowed; curves flattened to within 0.01 px."""
        o = "Container.path"
        if not isinstance(d, str):
            raise TypeError(f"{o}: d must be a string of SVG path data, got {type(d).__name__}")
        check_length(f"{o}: d", d, MAX_PATH_CHARS, "characters")
        if not d.strip():
            raise ValueError(f"{o}: d is empty; expected SVG path data such as 'M 0 0 H 100 V 80 Z'")
        try:
            rings = regions.flatten_path(d)
        except ValueError as exc:
            raise ValueError(f"{o}: d is not valid SVG path data ({exc}); got {d[:60]!r}") from None
        rings = [r for r in rings if len(r) >= 2]
        if not rings:
            raise ValueError(f"{o}: d draws nothing; got {d[:60]!r}")
        for ring in rings:
            check_points(o, "d", ring, 1)
        _check_area(o, "d", rings)
        return cls("path", {"d": d}, rings=rings)

    @classmethod
    def image(cls, source, threshold: float = 0.5, box=None, invert: bool = False) -> "Container":
        """The inside pixels of an image stretched over ``box = (x, y, w, h)`` (canvas px)
        or, if None, the whole canvas.

        ``source``: a path, data URL, bytes, PIL image or array (see
        :func:`.images.load_image`); a 2-D boolean array is the mask itself (True
        inside). The image is read as a person sees it: if transparency is its
        background (at least half the border pixels have alpha < 50%), inside is
        the opaque figure, whatever its colour; otherwise the image is composited
        over white and inside is what is darker than ``threshold`` (luminance in
        (0, 1]), so faint alpha pixels, antialiased edges, 16-bit grey and JPEGs read
        as drawn. ``invert`` swaps inside and out. Warns when the inside covers more than
        90% or less than 0.1% of the image; check :meth:`inside_share` or show the
        container in a notebook to see what was read.
        """
        return cls._image("Container.image", source, threshold, box, invert)

    @classmethod
    def _image(cls, owner, source, threshold, box, invert, advice=None) -> "Container":
        """Shared body of the image constructors; ``owner`` names the caller in errors,
        ``advice`` ends the warning of an implausible inside share (default: name
        ``invert=`` and ``threshold=``)."""
        threshold = check_finite(owner, "threshold", threshold)
        if not 0 < threshold <= 1:
            raise ValueError(f"{owner}: threshold must be in (0, 1], got {threshold:g}")
        box = check_box(owner, box)
        if isinstance(source, np.ndarray) and source.dtype == np.bool_ and source.ndim == 2:
            check_pixels(source.shape[1], source.shape[0], what="mask array")
            mask = ~source if invert else source.copy()
            if not mask.any():
                raise ValueError(f"{owner}: no pixel is inside (the mask array is all "
                                 f"{'True' if invert else 'False'}); use invert={not invert}")
        else:
            rgba = np.asarray(load_image(source))
            mask = regions.mask_from_rgba(owner, rgba, threshold, bool(invert))
        share = float(mask.mean())
        if share > MAX_INSIDE_SHARE or share < MIN_INSIDE_SHARE:
            advice = advice or ("pass invert=True (inside and out swapped) or another "
                                f"threshold= (now {threshold:g}; pixels darker than it are inside)")
            warnings.warn(f"{owner}: the inside covers {share:.2%} of the image; if the shape "
                          f"was read wrong, {advice}", stacklevel=3)
        return cls("image", {"threshold": threshold, "box": None if box is None else list(box)},
                   mask=mask)

    @classmethod
    def from_ipycanvas(cls, canvas, threshold: float = 0.5) -> "Container":
        """An image container of what was drawn on an ``ipycanvas.Canvas`` (created with
        ``sync_image_data=True``), placed over its extent ``(0, 0, canvas.width, canvas.height)``."""
        o = "Container.from_ipycanvas"
        try:
            data = canvas.get_image_data()
        except RuntimeError:
            data = None
        if data is None or np.size(data) == 0:
            raise ValueError(f"{o}: the canvas has no image data; create it with "
                             "ipycanvas.Canvas(..., sync_image_data=True) and draw on it while it "
                             "is displayed")
        rgba = np.asarray(data)
        if rgba.dtype != np.uint8:
            rgba = np.clip(rgba, 0, 255).astype(np.uint8)
        if rgba.ndim == 3 and rgba.shape[2] == 4 and not rgba[..., 3].any():
            raise ValueError(f"{o}: nothing is drawn on the canvas (all {rgba.shape[0] * rgba.shape[1]} "
                             "pixels are transparent); draw the container's shape first")
        box = (0, 0, canvas.width, canvas.height)
        return cls._image(o, rgba, threshold, box, False)

    @classmethod
    def from_background(cls, image, point, tolerance: float = 0.15, box=None,
                        canvas_size=None) -> "Container":
        """Magic wand: the 4-connected pixels around ``point`` (canvas px) whose colour is
        within ``tolerance`` (RGB distance / sqrt(3), colours in [0, 1], over white) of
        the colour at ``point``.

        The image is stretched over ``box``, else over the canvas of ``canvas_size``;
        with neither, one image pixel is one canvas px from the origin.
        """
        o = "Container.from_background"
        tolerance = check_finite(o, "tolerance", tolerance)
        if not 0 <= tolerance <= 1:
            raise ValueError(f"{o}: tolerance must be in [0, 1], got {tolerance:g}")
        box = check_box(o, box)
        rgba = np.asarray(load_image(image))
        h, w = rgba.shape[:2]
        if box is None:
            cw, ch = check_canvas_size(o, canvas_size) if canvas_size is not None else (w, h)
            place = (0.0, 0.0, cw, ch)
        else:
            place = box
        px, py = (check_coord(o, "point x", v) for v in check_points(o, "point", [point], 1)[0])
        col = math.floor((px - place[0]) / place[2] * w)
        row = math.floor((py - place[1]) / place[3] * h)
        if not (0 <= col < w and 0 <= row < h):
            raise ValueError(f"{o}: point ({px:g}, {py:g}) is outside the image, which covers "
                             f"x {place[0]:g}..{place[0] + place[2]:g}, y {place[1]:g}..{place[1] + place[3]:g}")
        mask = regions.wand_mask(rgba, row, col, tolerance)
        return cls._image(o, mask, 0.5, box if box is not None or canvas_size is not None
                          else place, False,
                          advice=f"pick another point or tolerance= (now {tolerance:g})")

    # ---- editing and serialisation -----------------------------------------------
    def cut(self, points, width: float) -> "Container":
        """A new container with the round-capped stroke along ``points`` (k, 2), k >= 1,
        ``width`` canvas px wide, removed. Cuts accumulate."""
        o = "Container.cut"
        check_length(f"{o}: points", points, MAX_CONTAINER_POINTS)
        check_length(f"{o}: cuts", self._cuts + ((points, width),), MAX_CUTS)
        pts = check_points(o, "points", points, 1)
        width = check_coord(o, "width", check_positive(o, "width", width))
        return Container(self._kind, self._params, rings=self._rings, mask=self._mask,
                         cuts=self._cuts + ((pts, width),))

    def to_json(self) -> dict:
        """The protocol dict; image kinds embed the mask as a PNG data URL
        (inside opaque black, outside transparent white)."""
        d = {"kind": self._kind, **copy.deepcopy(self._params)}
        if self._kind == "image":
            if "url" not in self._cache:
                rgba = np.where(self._mask[..., None], np.uint8([0, 0, 0, 255]),
                                np.uint8([255, 255, 255, 0]))
                self._cache["url"] = image_data_url(Image.fromarray(rgba.astype(np.uint8), "RGBA"))
            d = {"kind": "image", "image": self._cache["url"], **copy.deepcopy(self._params)}
        d["cuts"] = [{"points": p.tolist(), "width": w} for p, w in self._cuts]
        return d

    @classmethod
    def from_json(cls, d: dict) -> "Container":
        """The container described by a protocol dict (see docs/protocol.md)."""
        o = "Container.from_json"
        if not isinstance(d, dict):
            raise ValueError(f"{o}: expected a dict such as {{'kind': 'rect', 'x': 0, 'y': 0, "
                             f"'w': 10, 'h': 10}}, got {type(d).__name__}")
        if d.get("kind") not in KINDS:
            got = d.get("kind")
            raise ValueError(f"{o}: unknown container kind {got!r}; valid kinds are "
                             + ", ".join(repr(k) for k in KINDS))
        kind = d["kind"]
        missing = [f for f in _FIELDS[kind] if f not in d]
        if missing:
            raise ValueError(f"{o}: a {kind!r} container needs {', '.join(_FIELDS[kind])}; "
                             f"missing {', '.join(missing)}")
        if kind == "canvas":
            c = cls.canvas()
        elif kind == "polygon":
            c = cls.polygon(d["points"])
        elif kind == "path":
            c = cls.path(d["d"])
        elif kind == "image":
            c = cls._image(o, d["image"], d.get("threshold", 0.5), d.get("box"),
                           bool(d.get("invert", False)))
        else:
            c = getattr(cls, kind)(*(d[f] for f in _FIELDS[kind]))
        cuts = d.get("cuts") or []
        if not isinstance(cuts, list):
            raise ValueError(f"{o}: cuts must be a list of {{'points', 'width'}}, got {cuts!r:.60}")
        check_length(f"{o}: cuts", cuts, MAX_CUTS)
        for cut in cuts:
            if not isinstance(cut, dict) or "points" not in cut or "width" not in cut:
                raise ValueError(f"{o}: each cut needs 'points' and 'width', got {cut!r:.60}")
            c = c.cut(cut["points"], cut["width"])
        return c

    def __eq__(self, other):
        if not isinstance(other, Container):
            return NotImplemented
        return self.to_json() == other.to_json()

    def __repr__(self):
        if self._kind == "image":
            h, w = self._mask.shape
            args = f"<{w}x{h} mask>, box={self._params['box']}"
        elif self._kind in ("polygon", "path"):
            args = f"<{sum(len(r) for r in self._rings)} vertices>"
        else:
            args = ", ".join(f"{self._params[f]:g}" for f in _FIELDS[self._kind])
        cuts = f".cut(...) x {len(self._cuts)}" if self._cuts else ""
        return f"Container.{self._kind}({args}){cuts}"

    def inside_share(self, canvas_size=None) -> float:
        """Share in [0, 1] of the canvas of ``canvas_size`` inside the region; for image
        kinds without ``canvas_size``, the share of the image's pixels read as inside."""
        if canvas_size is None:
            if self._kind != "image":
                raise ValueError(f"Container.inside_share: a {self._kind!r} container needs "
                                 "canvas_size=(width, height)")
            return float(self._mask.mean())
        w, h = check_canvas_size("Container.inside_share", canvas_size)
        return self.area((w, h)) / (w * h)

    def preview(self, canvas_size=None, rho: float | None = None) -> Image.Image:
        """A PIL picture of what is inside (black) and outside (white): image kinds at
        the mask's own size by default, other kinds on the canvas of ``canvas_size``
        at ``rho`` raster px per canvas px (default: at most 400 px wide)."""
        if canvas_size is None and self._kind == "image" and not self._cuts:
            inside = self._mask
        else:
            if canvas_size is None:
                raise ValueError(f"Container.preview: a {self._kind!r} container needs "
                                 "canvas_size=(width, height)")
            size = check_canvas_size("Container.preview", canvas_size)
            rho = min(1.0, 400 / size[0]) if rho is None else rho
            inside = self.coverage(size, rho) >= 0.5
        return Image.fromarray(np.where(inside, 0, 255).astype(np.uint8), "L")

    def _repr_png_(self) -> bytes | None:
        """The :meth:`preview` of image kinds as PNG bytes, for notebooks."""
        if self._kind != "image":
            return None
        buf = io.BytesIO()
        self.preview().save(buf, format="PNG")
        return buf.getvalue()

    # ---- geometry ------------------------------------------------------------------
    def coverage(self, canvas_size, rho: float) -> np.ndarray:
        """float32 (H, W), H = ceil(height * rho), W = ceil(width * rho): the share of each
        raster pixel inside the region; pixel (i, j) covers canvas [j/rho, (j+1)/rho] x
        [i/rho, (i+1)/rho]. Exact in x, 1/16-px rows in y (exact for masks). Cached and
        read-only: copy it before writing."""
        key = ("coverage", check_canvas_size("Container.coverage", canvas_size),
               check_positive("Container.coverage", "rho", rho))
        if key not in self._cache:
            rows, line, x0, x1, shape = self._spans(key[1], key[2])
            cov = regions.coverage(rows, line, x0, x1, key[2], shape)
            cov.flags.writeable = False
            self._cache[key] = cov
        return self._cache[key]

    def area(self, canvas_size) -> float:
        """Area of the region inside the canvas, canvas px^2."""
        size = check_canvas_size("Container.area", canvas_size)
        exact = self._analytic(size)
        if exact is not None:
            return exact[0]
        rows, line, x0, x1, _ = self._spans(size, 1.0)
        return float(np.sum((x1 - x0) * (rows.hi - rows.lo)[line]))

    def centroid(self, canvas_size) -> tuple[float, float]:
        """Centre of mass (x, y) of the region inside the canvas, canvas px."""
        size = check_canvas_size("Container.centroid", canvas_size)
        exact = self._analytic(size)
        if exact is not None:
            return exact[1]
        rows, line, x0, x1, _ = self._spans(size, 1.0)
        weight = (x1 - x0) * (rows.hi - rows.lo)[line]
        total = weight.sum()
        if total <= 0:
            raise ValueError(f"Container.centroid: {self!r} does not overlap the "
                             f"{size[0]:g} x {size[1]:g} canvas")
        cx = np.sum((x0 + x1) / 2 * weight) / total
        return float(cx), float(np.sum(rows.y[line] * weight) / total)

    def bbox(self, canvas_size) -> tuple[float, float, float, float]:
        """(x, y, w, h) of the inside region within the canvas, canvas px."""
        size = check_canvas_size("Container.bbox", canvas_size)
        rows, line, x0, x1, _ = self._spans(size, 1.0)
        if len(line) == 0:
            raise ValueError(f"Container.bbox: {self!r} does not overlap the "
                             f"{size[0]:g} x {size[1]:g} canvas")
        gx0, gy0, gx1, gy1 = self._extent(size)
        within = gx0 >= 0 and gy0 >= 0 and gx1 <= size[0] and gy1 <= size[1]
        if within and not self._cuts and self._kind != "image":   # the geometry is exact
            return float(gx0), float(gy0), float(gx1 - gx0), float(gy1 - gy0)
        left, right = max(x0.min(), gx0, 0.0), min(x1.max(), gx1, size[0])
        top, bottom = max(rows.lo[line].min(), gy0, 0.0), min(rows.hi[line].max(), gy1, size[1])
        return float(left), float(top), float(right - left), float(bottom - top)

    def svg_path(self, canvas_size) -> str | None:
        """SVG path data outlining the region (fill it even-odd), or None for image
        kinds and for containers with cuts, whose outline is not kept as vectors."""
        if self._kind == "image" or self._cuts:
            return None
        p, n = self._params, _num
        if self._kind == "canvas":
            w, h = check_canvas_size("Container.svg_path", canvas_size)
            return f"M0 0H{n(w)}V{n(h)}H0Z"
        if self._kind == "rect":
            return f"M{n(p['x'])} {n(p['y'])}h{n(p['w'])}v{n(p['h'])}h{n(-p['w'])}Z"
        if self._kind == "ellipse":
            cx, cy, rx, ry = (p[f] for f in _FIELDS["ellipse"])
            arc = f"A{n(rx)} {n(ry)} 0 1 0"
            return f"M{n(cx - rx)} {n(cy)}{arc} {n(cx + rx)} {n(cy)}{arc} {n(cx - rx)} {n(cy)}Z"
        if self._kind == "path":
            return p["d"]
        return "M" + "L".join(f"{n(x)} {n(y)}" for x, y in self._rings[0]) + "Z"

    # ---- internals -----------------------------------------------------------------
    def _extent(self, size) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1) bounding the uncut geometry, canvas px."""
        p = self._params
        if self._kind == "rect":
            return p["x"], p["y"], p["x"] + p["w"], p["y"] + p["h"]
        if self._kind == "ellipse":
            return p["cx"] - p["rx"], p["cy"] - p["ry"], p["cx"] + p["rx"], p["cy"] + p["ry"]
        if self._kind in ("polygon", "path"):
            pts = np.concatenate(self._rings)
            return (*pts.min(axis=0), *pts.max(axis=0))
        if self._kind == "image" and p["box"] is not None:
            x, y, w, h = p["box"]
            return x, y, x + w, y + h
        return 0.0, 0.0, size[0], size[1]

    def _analytic(self, size):
        """(area, centroid) in closed form when there are no cuts and the kind allows it."""
        if self._cuts or self._kind == "image":
            return None
        x0, y0, x1, y1 = self._extent(size)
        if self._kind in ("rect", "canvas"):
            x0, y0 = max(x0, 0.0), max(y0, 0.0)
            x1, y1 = min(x1, size[0]), min(y1, size[1])
            if x1 <= x0 or y1 <= y0:
                return None
            return (x1 - x0) * (y1 - y0), ((x0 + x1) / 2, (y0 + y1) / 2)
        if x0 < 0 or y0 < 0 or x1 > size[0] or y1 > size[1]:
            return None
        if self._kind == "ellipse":
            p = self._params
            return math.pi * p["rx"] * p["ry"], (p["cx"], p["cy"])
        if "evenodd" not in self._cache:
            self._cache["evenodd"] = regions.evenodd_area(self._rings)
        rows, line, sx0, sx1, _ = self._spans(size, 1.0)
        weight = (sx1 - sx0) * (rows.hi - rows.lo)[line]
        centroid = (float(np.sum((sx0 + sx1) / 2 * weight) / weight.sum()),
                    float(np.sum(rows.y[line] * weight) / weight.sum())) if weight.sum() > 0 else None
        return (self._cache["evenodd"], centroid) if centroid else None

    def _spans(self, size, rho):
        """Sample rows and inside spans of the region on the raster of ``size`` at ``rho``:
        (Rows, line (n,), x0 (n,), x1 (n,), (H, W))."""
        key = ("spans", size, rho)
        if key in self._cache:
            return self._cache[key]
        shape = (math.ceil(size[1] * rho), math.ceil(size[0] * rho))
        if self._kind == "image" and not self._cuts:
            box = self._extent(size)
            rows = regions.band_rows(shape[0], rho, box[1], box[3] - box[1], self._mask.shape[0])
        else:
            rows = regions.subrows(shape[0], rho)
        region = self._events(size, rows.y)
        cut_events = [regions.stroke_events(p, w, rows.y) for p, w in self._cuts]
        cuts = tuple(np.concatenate([e[i] for e in cut_events]) if cut_events else np.zeros(0)
                     for i in range(3))
        line, x0, x1 = regions.spans(region, cuts, 0.0, shape[1] / rho)
        self._cache[key] = (rows, line, x0, x1, shape)
        return self._cache[key]

    def _events(self, size, ys):
        """Even-odd toggles (line, x) of the uncut region on sample lines ``ys``."""
        p = self._params
        if self._kind == "canvas":
            return regions.rect_events(0.0, 0.0, size[0], size[1], ys)
        if self._kind == "rect":
            return regions.rect_events(p["x"], p["y"], p["w"], p["h"], ys)
        if self._kind == "ellipse":
            return regions.ellipse_events(p["cx"], p["cy"], p["rx"], p["ry"], ys)
        if self._kind == "image":
            x0, y0, x1, y1 = self._extent(size)
            return regions.mask_events(self._mask, (x0, y0, x1 - x0, y1 - y0), ys)
        return regions.crossings(regions.ring_edges(self._rings), ys)


def _check_area(owner: str, name: str, rings) -> None:
    """ValueError if the even-odd fill of ``rings`` has (numerically) zero area."""
    pts = np.concatenate(rings)
    span = float(np.ptp(pts, axis=0).max())
    if regions.evenodd_area(rings) <= 1e-12 * max(span, 1e-300) ** 2:
        raise ValueError(f"{owner}: the shape of {name} has zero area (points collinear, repeated "
                         "or retracing); a container needs a region with area > 0")
