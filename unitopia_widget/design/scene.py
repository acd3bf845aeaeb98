"""The design model: layers of marks, containers, emitters and forces.

A ``Scene`` is the whole design except the data: canvas, background, seed
and ordered ``Layer``s. It serialises to the versioned design JSON of
``docs/protocol.md``, the one format used by ``save``/``load`` and by the
widget's ``design`` traitlet.
"""
from __future__ import annotations

from numbers import Real

import numpy as np

from .bounds import (MAX_BLOCKS, MAX_COLUMN_NAME, MAX_FORCES, MAX_ROW_LABELS,
                     check_length)
from .containers import Container
from .emitters import CurveEmitter, GridEmitter, emitter_from_json
from .encodings import MARGINS_OF
from .forces import DirectionalForce, PointForce, force_from_json
from .marks import Mark, check_footprint
from .positions import check_arrange, check_scale
from .tally import check_count, check_partial, check_per, check_rounding
from .validate import check_choice, check_finite, closest, short

SCHEMA, VERSION = "unitopia-design", 5
CHANNELS = ("size", "width", "height", "color", "shape", "margin", "order", "x", "y")
MAX_MARKS = 100   # marks in one layer: each renders its own sprite pyramid
_MARK_KINDS = ("shape", "svg", "icon", "image", "sketch")
BOUNDARIES = ("closed", "open")
MAX_NAME = 200   # characters in a layer name
ORIENTATIONS = (None, "to_center", "along_emitter", "random")   # or ("random", lo, hi) degrees
RANGES = ("size_range", "width_range", "height_range")   # (min_px, max_px) of a linear scale
TALLY = ("count", "per", "rounding", "partial")   # units per row, one mark for k: design/tally.py
TALLY_DEFAULTS = {"count": None, "per": None, "rounding": "largest-remainder", "partial": False}
LAYER_FIELDS = ("mark", "container", "emitter", "forces", "boundary", "fill", "orientation",
                "rotate", "blocks", "iterations", "footprint", "margin_of", "name", "x_scale",
                "y_scale", "arrange") + CHANNELS + RANGES + TALLY


class Layer:
    """One sub-unit visualization: which rows, drawn how, laid out where.

    Change it with ``set(**fields)``; the owning chart is told, so the widget
    redraws. ``encodings`` maps channel -> column name or literal.

    ``mark`` is one spec, a list of specs (a group drawn with several marks:
    row i of the layer draws mark i mod k, or, with ``shape=<column>``, the
    sorted categories take the marks in turn) or ``{category: spec}`` (with
    ``shape=``). ``marks`` holds the Marks, ``mark_keys`` the dict's categories
    (None for a list).

    ``footprint``: what a mark collides with; ``"silhouette"`` (default) its ink
    with enclosed holes filled, so a ring keeps other marks out of its middle;
    ``"ink"`` its ink alone, for marks meant to nest. The export draws the ink.

    ``margin_of``: what the ``margin`` fraction is of; ``"median"`` (default) each mark's
    size up to its layer's median mark's, so marks larger than the median keep the median
    mark's gap (tied and small marks their own); ``"own"`` each mark's own size however
    large, so a large mark keeps a wide moat (version 3's rule).

    ``size_range``, ``width_range``, ``height_range``: None (data-true: area or extent
    proportional to the value) or ``(min_px, max_px)``: the bound column's values map
    linearly onto mark extents from ``min_px`` to ``max_px`` (not area-true); the global
    scale then fits them to the container as it does any sizes, keeping their ratio.

    ``count``: None (one unit per row) or a column: each row stands for that many units.
    ``per``: None (one mark per unit) or k: one mark for k units of one category;
    ``rounding`` and ``partial`` say how a group's remainder is drawn (``design/tally.py``).
    """

    def __init__(self, name: str, mark=None, rows=None, container=None, emitter=None,
                 forces=(), boundary="closed", fill=None, orientation=None, rotate=False,
                 blocks=(), iterations=600, footprint="silhouette", margin_of="median",
                 on_change=None, **encodings):
        self._on_change = None
        self.name, self.rows = layer_name(name), _rows(rows)
        self.marks, self.mark_keys = _mark_set("circle" if mark is None else mark)
        self.encodings = {c: None for c in CHANNELS}
        self.encodings["margin"] = 0.0
        self.container = self.emitter = None
        self.forces, self.blocks = [], []
        self.boundary, self.fill, self.orientation = "closed", None, None
        self.rotate, self.iterations, self.footprint = False, 600, "silhouette"
        self.margin_of = "median"
        self.size_range = self.width_range = self.height_range = None
        self.x_scale = self.y_scale = "linear"   # position channels: see design/positions.py
        self.arrange = "free"
        for key, value in TALLY_DEFAULTS.items():
            setattr(self, key, value)
        self.set(container=container, emitter=emitter, forces=forces, boundary=boundary,
                 fill=fill, orientation=orientation, rotate=rotate, blocks=blocks,
                 iterations=iterations, footprint=footprint, margin_of=margin_of, **encodings)
        self._on_change = on_change

    def set(self, **fields) -> "Layer":
        """Change fields (any of ``LAYER_FIELDS``); checks every value first, then applies."""
        for key in fields:
            if key not in LAYER_FIELDS:
                raise TypeError(f"Layer.set: unknown field {key!r}{closest(key, LAYER_FIELDS)}; "
                                f"valid fields: {', '.join(LAYER_FIELDS)}")
        checked = {k: _CHECKS[k](v) for k, v in fields.items()}
        old = {k: self.encodings[k] if k in CHANNELS else getattr(self, k) for k in checked
               if k != "mark"}
        if "mark" in checked:
            old["mark"] = (self.marks, self.mark_keys)
        self._apply(checked)
        if self._on_change is not None:
            try:   # the owner checks the whole chart (columns, block cycles, unique names)
                self._on_change(self, set(checked))
            except Exception:
                self._apply(old)   # a refused change leaves the layer as it was
                raise
        return self

    def _apply(self, values: dict) -> None:
        for key, value in values.items():
            if key == "mark":
                self.marks, self.mark_keys = value
            elif key in CHANNELS:
                self.encodings[key] = value
            else:
                setattr(self, key, value)

    @property
    def mark(self) -> Mark:
        """The layer's first mark (its only one unless it draws a group of marks)."""
        return self.marks[0]

    @property
    def region(self) -> Container:
        """The container marks are laid out in: the whole canvas when none is set."""
        return self.container if self.container is not None else Container.canvas()

    def to_json(self) -> dict:
        """The layer as the design JSON holds it (``docs/protocol.md``)."""
        return {
            "name": self.name, "rows": self.rows, "marks": [m.to_json() for m in self.marks],
            "mark_keys": None if self.mark_keys is None else list(self.mark_keys),
            "encodings": dict(self.encodings),
            "container": None if self.container is None else self.container.to_json(),
            "emitter": None if self.emitter is None else self.emitter.to_json(),
            "forces": [f.to_json() for f in self.forces],
            "boundary": self.boundary, "fill": self.fill,
            "orientation": list(self.orientation) if isinstance(self.orientation, tuple)
            else self.orientation,
            "rotate": self.rotate, "blocks": list(self.blocks), "iterations": self.iterations,
            "footprint": self.footprint, "margin_of": self.margin_of,
            "x_scale": self.x_scale, "y_scale": self.y_scale,
            "arrange": self.arrange,
            **{k: list(getattr(self, k)) for k in RANGES if getattr(self, k) is not None},
            # written when set: a design without them keeps one mark per row
            **{k: getattr(self, k) for k in TALLY if getattr(self, k) != TALLY_DEFAULTS[k]},
        }

    @classmethod
    def from_json(cls, d: dict, on_change=None) -> "Layer":
        """A layer from its design dict; ValueError for a malformed one. A design is
        self-contained: images are data: URLs and SVG marks are inline text, never paths.
        Reads version 2 (``marks``, ``mark_keys``) and version 1 (``mark``) layers."""
        if not isinstance(d, dict):
            raise ValueError(f"design layer must be a JSON object, got {type(d).__name__}")
        who = f"design layer {short(d.get('name', '?'))}"
        missing = [k for k in ("name", "marks") if k not in d and not (k == "marks" and "mark" in d)]
        if missing:
            raise ValueError(f"{who}: missing {' and '.join(map(repr, missing))}")
        for key, kind in (("encodings", dict), ("forces", list), ("blocks", list)):
            if d.get(key) is not None and not isinstance(d[key], kind):
                raise ValueError(f"{who}: {key} must be a JSON {'object' if kind is dict else 'array'}, "
                                 f"got {type(d[key]).__name__}")
        for key, bound in (("forces", MAX_FORCES), ("blocks", MAX_BLOCKS)):
            check_length(f"{who}: {key}", d.get(key) or [], bound)
        if isinstance(d.get("rows"), dict):
            check_length(f"{who}: rows index", d["rows"].get("index") or [], MAX_ROW_LABELS,
                         "labels")
        _check_inline(who, d)
        enc = {k: v for k, v in (d.get("encodings") or {}).items() if k in CHANNELS}
        return cls(d["name"], mark=_design_marks(who, d), rows=d.get("rows"),
                   container=_container(d.get("container")),
                   emitter=_emitter(d.get("emitter")),
                   forces=_forces(d.get("forces") or []),
                   boundary=d.get("boundary", "closed"), fill=d.get("fill"),
                   orientation=d.get("orientation"), rotate=d.get("rotate", False),
                   blocks=d.get("blocks", []), iterations=d.get("iterations", 600),
                   footprint=d.get("footprint", "silhouette"),
                   margin_of=d.get("margin_of", "median"), on_change=on_change,
                   **{k: d[k] for k in RANGES if d.get(k) is not None},
                   **{k: d[k] for k in ("x_scale", "y_scale", "arrange") + TALLY if k in d},
                   **enc)

    def __repr__(self) -> str:
        bound = ", ".join(f"{k}={v!r}" for k, v in self.encodings.items() if v not in (None, 0.0))
        marks = self.mark.kind if len(self.marks) == 1 else f"{len(self.marks)} marks"
        return (f"Layer({self.name!r}, mark={marks}, {bound or 'no encodings'}, "
                f"container={self.container.kind if self.container else 'canvas'}, "
                f"forces={len(self.forces)}, boundary={self.boundary!r})")


def _design_marks(who: str, d: dict):
    """The ``mark=`` value of a design layer: its marks list (version 2), as a
    ``{category: mark}`` dict when ``mark_keys`` is set, or its one mark (the version 1
    key ``mark``, which wins when an editor that knows only version 1 set it)."""
    if "mark" in d:
        return _mark(d["mark"], Mark.from_json)
    marks, keys = d["marks"], d.get("mark_keys")
    if not isinstance(marks, list) or not marks:
        raise ValueError(f"{who}: marks must be a non-empty JSON array of marks, got {marks!r:.60}")
    if len(marks) > MAX_MARKS:
        _mark_set(marks)   # raises: too many marks
    marks = [_mark(m, Mark.from_json) for m in marks]
    if keys is None:
        return marks
    if not (isinstance(keys, list) and len(keys) == len(marks)
            and all(isinstance(k, (str, int, float, bool)) for k in keys) and len(set(keys)) == len(keys)):
        raise ValueError(f"{who}: mark_keys must be null or a list of {len(marks)} distinct "
                         f"categories, one per mark; got {keys!r:.80}")
    return dict(zip(keys, marks))


def _check_inline(who: str, d: dict) -> None:
    """ValueError unless the layer's marks and image container are inline data (no paths)."""
    container = d.get("container")
    marks = (d["marks"] if isinstance(d.get("marks"), list) else []) + [d.get("mark")]
    for mark in marks:
        if isinstance(mark, dict) and mark.get("kind") == "svg" and not (
                isinstance(mark.get("svg"), str) and mark["svg"].lstrip("\ufeff \t\r\n").startswith("<")):
            raise ValueError(f"{who}: an svg mark must hold SVG text starting with '<', not a file "
                             f"path; got {str(mark.get('svg'))[:60]!r}")
    if isinstance(container, dict) and container.get("kind") == "image" and not (
            isinstance(container.get("image"), str)
            and container["image"].lstrip()[:5].lower() == "data:"):
        raise ValueError(f"{who}: an image container must hold a data:image/png or "
                         f"data:image/jpeg URL, not a file path; got "
                         f"{str(container.get('image'))[:60]!r}")


def _from_json(what: str, build, d):
    """``build(d)``, a missing key in ``d`` reported as a ValueError naming ``what``."""
    try:
        return build(d)
    except KeyError as exc:
        kind = d.get("kind") if isinstance(d, dict) else None
        raise ValueError(f"{what}: a {kind!r} {what} dict lacks the key {exc}; got "
                         f"{d!r:.80}") from None


def _mark(value, build=Mark.from_spec):
    """A Mark from any ``mark=`` spec; errors say that the mark is the culprit."""
    try:
        return build(value)
    except ValueError as exc:
        raise ValueError(f"mark: {exc}") from None


def is_category_dict(mark) -> bool:
    """True for ``{category: mark spec}``, False for a mark dict such as ``{"kind": "shape", ...}``."""
    return isinstance(mark, dict) and mark.get("kind") not in _MARK_KINDS


def _mark_set(value, build=Mark.from_spec) -> tuple[list, list | None]:
    """``(marks, mark_keys)`` of a ``mark=`` value: one spec, a list of specs or
    ``{category: spec}`` (keys kept in order; JSON-safe str, int, float or bool)."""
    keys = None
    if is_category_dict(value):
        keys = [k.item() if isinstance(k, np.generic) else k for k in value]
        bad = [k for k in keys if not isinstance(k, (str, int, float, bool))]
        if bad:
            raise TypeError(f"mark: the categories of a {{category: mark}} dict must be str, int, "
                            f"float or bool (as in the shape= column), got {bad[0]!r}")
        specs = list(value.values())
    elif isinstance(value, (list, tuple)):
        specs = list(value)
    else:
        return [_mark(value, build)], None
    if not 1 <= len(specs) <= MAX_MARKS:
        raise ValueError(f"mark: a group needs 1 to {MAX_MARKS} marks, got {len(specs)}")
    marks = []
    for i, spec in enumerate(specs):
        if isinstance(spec, (list, tuple)) or is_category_dict(spec):
            raise ValueError(f"mark: entry {i} of the group is itself a list or dict; give one "
                             f"mark spec per entry, got {spec!r:.60}")
        marks.append(_mark(spec, build))
    return marks, keys


def _rows(rows):
    """None, ``{"column": name, "value": v}`` or ``{"index": [labels]}``."""
    if rows is None or (isinstance(rows, dict) and (
            set(rows) == {"column", "value"} or (set(rows) == {"index"}
                                                 and isinstance(rows["index"], list)))):
        if rows is not None and "index" in rows:
            check_length("layer rows index", rows["index"], MAX_ROW_LABELS, "labels")
            seen, twice = set(), {}
            for label in rows["index"]:
                key = repr(label)
                if key in seen:
                    twice.setdefault(key, label)
                seen.add(key)
            twice = list(twice.values())
            if twice:
                raise ValueError(f"layer rows: {len(twice)} label(s) listed more than once in "
                                 f"'index', e.g. {twice[0]!r:.60}; list each row once")
        return rows
    raise ValueError(f"layer rows must be None, {{'column': name, 'value': v}} or "
                     f"{{'index': [labels]}}; got {rows!r:.80}")


def _container(value):
    if value is None or isinstance(value, Container):
        return value
    if isinstance(value, dict):
        return _from_json("container", Container.from_json, value)
    raise TypeError(f"container must be a uw.Container (rect, ellipse, polygon, path, image, "
                    f"canvas) or None, got {type(value).__name__}")


def _emitter(value):
    if value is None or isinstance(value, (GridEmitter, CurveEmitter)):
        return value
    if isinstance(value, dict):
        return _from_json("emitter", emitter_from_json, value)
    raise TypeError(f"emitter must be uw.GridEmitter(...), uw.CurveEmitter(...) or None, "
                    f"got {type(value).__name__}")


def _forces(value):
    items = [value] if isinstance(value, (PointForce, DirectionalForce, dict)) else list(value or [])
    check_length("forces", items, MAX_FORCES)
    out = [_from_json("force", force_from_json, f) if isinstance(f, dict) else f for f in items]
    for f in out:
        if not isinstance(f, (PointForce, DirectionalForce)):
            raise TypeError(f"forces must be uw.PointForce or uw.DirectionalForce objects, got {f!r}")
    return out


def _blocks(value) -> list[str]:
    blocks = [value] if isinstance(value, str) else list(value or [])
    check_length("blocks", blocks, MAX_BLOCKS)
    return [str(b) for b in blocks]


def _fill(value):
    if value is None:
        return None
    v = check_finite("Layer", "fill", value)
    if not 0 < v <= 1:
        raise ValueError(f"fill must be None or a share in (0, 1], got {value!r}")
    return v


def _orientation(value):
    if isinstance(value, (list, tuple)) and len(value) == 3 and value[0] == "random":
        lo = check_finite("Layer", "orientation's lowest angle", value[1])
        hi = check_finite("Layer", "orientation's highest angle", value[2])
        if not lo < hi <= lo + 360:
            raise ValueError(f"orientation=('random', lo, hi) needs lo < hi <= lo + 360 degrees; "
                             f"got {tuple(value)!r}")
        return ("random", lo, hi)
    if isinstance(value, str) and value in ORIENTATIONS:
        return value
    if value is None:
        return None
    if isinstance(value, Real) and not isinstance(value, bool):
        return check_finite("Layer", "orientation", value)
    raise ValueError(f"orientation must be one of None, 'to_center', 'along_emitter', 'random', "
                     f"('random', lo, hi) in degrees, or a number of degrees; got {value!r}")


def random_range(orientation) -> tuple[float, float] | None:
    """``(lo, hi)`` in degrees: the angles a layer's ``orientation`` draws each mark's from,
    uniformly (``"random"``: the full turn); None when it does not draw them."""
    if orientation == "random":
        return (-180.0, 180.0)
    if isinstance(orientation, tuple):
        return orientation[1], orientation[2]
    return None


def _rotate(value):
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"rotate must be True or False, got {value!r}")


def _iterations(value):
    if isinstance(value, bool) or not isinstance(value, int) or not 20 <= value <= 100_000:
        raise ValueError(f"iterations must be an integer between 20 and 100000, got {value!r}")
    return value


def _channel(name):
    def check(value):
        if name == "margin" and value is None:
            return 0.0   # no margin (None would reach the encoder as a number)
        if isinstance(value, str):
            check_length(f"{name} (a column name)", value, MAX_COLUMN_NAME, "characters")
        if value is None or isinstance(value, str):
            return value
        if name == "margin" and isinstance(value, Real) and not isinstance(value, bool):
            v = check_finite("Layer", "margin", value)
            if not 0 <= v <= 4:
                raise ValueError(f"margin must be a column name or a fraction in [0, 4], got {value!r}")
            return v
        raise TypeError(f"{name} must be a column name or None, got {value!r}")
    return check


_CHECKS = {
    "mark": _mark_set, "container": _container, "emitter": _emitter, "forces": _forces,
    "boundary": lambda v: check_choice("Layer", "boundary", v, BOUNDARIES),
    "fill": _fill, "orientation": _orientation, "rotate": _rotate,
    "blocks": _blocks,
    "iterations": _iterations, "name": lambda v: layer_name(v),
    "footprint": lambda v: check_footprint("footprint", v),
    "margin_of": lambda v: check_choice("Layer", "margin_of", v, MARGINS_OF),
    "x_scale": lambda v: check_scale("x", v), "y_scale": lambda v: check_scale("y", v),
    "arrange": check_arrange,
    "count": check_count, "per": check_per, "rounding": check_rounding, "partial": check_partial,
    **{c: _channel(c) for c in CHANNELS},
    **{k: (lambda v, k=k: _range(k, v)) for k in RANGES},
}


def _range(name: str, value):
    """None, or ``(min_px, max_px)`` as a tuple of floats with ``0 < min_px <= max_px``."""
    if value is None:
        return None
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be None or (min_px, max_px), two numbers, got "
                         f"{value!r:.60}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo <= hi):
        raise ValueError(f"{name} must be (min_px, max_px) with 0 < min_px <= max_px, "
                         f"got {value!r:.60}")
    return (lo, hi)


def layer_name(value) -> str:
    """A layer name: any value as text, at most ``MAX_NAME`` characters (names are repeated
    in every unit of the SVG and in error messages)."""
    name = str(value)
    if len(name) > MAX_NAME:
        raise ValueError(f"layer name is {len(name)} characters long ({name[:40]!r}...); at most "
                         f"{MAX_NAME} are allowed: choose a shorter name")
    return name


def block_order(layers) -> list[int]:
    """Layer indices with every blocking layer before the layers it blocks.

    Raises ValueError naming an unknown block or the first cycle found.
    """
    names = [layer.name for layer in layers]
    index = {n: i for i, n in enumerate(names)}
    for layer in layers:
        for b in layer.blocks:
            if b not in index:
                raise ValueError(f"layer {layer.name!r} blocks on {b!r}: no such layer"
                                 f"{closest(b, names)}; the layers are {', '.join(map(repr, names))}")
            if b == layer.name:
                raise ValueError(f"block cycle: layer {b!r} blocks on itself")
    state, out = {}, []

    def visit(i, path):
        if state.get(i) == "done":
            return
        if state.get(i) == "open":
            cycle = path[path.index(names[i]):] + [names[i]]
            raise ValueError("block cycle: " + " -> ".join(repr(n) for n in cycle))
        state[i] = "open"
        for b in layers[i].blocks:
            visit(index[b], path + [names[i]])
        state[i] = "done"
        out.append(i)

    for i in range(len(layers)):
        visit(i, [])
    return out


def check_design_header(d) -> None:
    """A ValueError unless ``d`` is a design of a version this package reads."""
    if not isinstance(d, dict) or d.get("schema") != SCHEMA:
        raise ValueError(f"not a unitopia design: expected a JSON object with \"schema\": "
                         f"\"{SCHEMA}\"")
    version = d.get("version")
    if isinstance(version, bool) or not isinstance(version, int) or version < 1:
        raise ValueError(f"design: bad version {version!r}; expected an integer >= 1")
    if version > VERSION:
        raise ValueError(f"design: version {version} is newer than this unitopia-widget reads "
                         f"(up to {VERSION}); upgrade the package to load it")
    if not isinstance(d.get("layers"), list) or not d["layers"]:
        raise ValueError("design: \"layers\" must be a non-empty list")
