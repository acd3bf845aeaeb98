"""The design model: layers of marks, containers, emitters and forces.

A ``Scene`` is the whole design except the data: canvas, background, seed
and ordered ``Layer``s. It serialises to the versioned design JSON of
``docs/protocol.md``, the one format used by ``save``/``load`` and by the
widget's ``design`` traitlet.
"""
from __future__ import annotations

from numbers import Real

import numpy as np

from .containers import Container
from .emitters import CurveEmitter, GridEmitter, emitter_from_json
from .forces import DirectionalForce, PointForce, force_from_json
from .marks import Mark
from .validate import check_choice, check_finite, closest

SCHEMA, VERSION = "unitopia-design", 1
CHANNELS = ("size", "width", "height", "color", "margin", "order")
BOUNDARIES = ("closed", "open")
MAX_NAME = 200   # characters in a layer name
ORIENTATIONS = (None, "to_center", "along_emitter")
LAYER_FIELDS = ("mark", "container", "emitter", "forces", "boundary", "fill", "orientation",
                "rotate", "blocks", "iterations", "name") + CHANNELS


class Layer:
    """One sub-unit visualization: which rows, drawn how, laid out where.

    Change it with ``set(**fields)``; the owning chart is told, so the widget
    redraws. ``encodings`` maps channel -> column name or literal.
    """

    def __init__(self, name: str, mark=None, rows=None, container=None, emitter=None,
                 forces=(), boundary="closed", fill=None, orientation=None, rotate=False,
                 blocks=(), iterations=600, on_change=None, **encodings):
        self._on_change = None
        self.name, self.rows = layer_name(name), _rows(rows)
        self.mark = _mark("circle" if mark is None else mark)
        self.encodings = {c: None for c in CHANNELS}
        self.encodings["margin"] = 0.0
        self.container = self.emitter = None
        self.forces, self.blocks = [], []
        self.boundary, self.fill, self.orientation = "closed", None, None
        self.rotate, self.iterations = False, 600
        self.set(container=container, emitter=emitter, forces=forces, boundary=boundary,
                 fill=fill, orientation=orientation, rotate=rotate, blocks=blocks,
                 iterations=iterations, **encodings)
        self._on_change = on_change

    def set(self, **fields) -> "Layer":
        """Change fields (any of ``LAYER_FIELDS``); checks every value first, then applies."""
        for key in fields:
            if key not in LAYER_FIELDS:
                raise TypeError(f"Layer.set: unknown field {key!r}{closest(key, LAYER_FIELDS)}; "
                                f"valid fields: {', '.join(LAYER_FIELDS)}")
        checked = {k: _CHECKS[k](v) for k, v in fields.items()}
        old = {k: self.encodings[k] if k in CHANNELS else getattr(self, k) for k in checked}
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
            if key in CHANNELS:
                self.encodings[key] = value
            else:
                setattr(self, key, value)

    @property
    def region(self) -> Container:
        """The container marks are laid out in: the whole canvas when none is set."""
        return self.container if self.container is not None else Container.canvas()

    def to_json(self) -> dict:
        return {
            "name": self.name, "rows": self.rows, "mark": self.mark.to_json(),
            "encodings": dict(self.encodings),
            "container": None if self.container is None else self.container.to_json(),
            "emitter": None if self.emitter is None else self.emitter.to_json(),
            "forces": [f.to_json() for f in self.forces],
            "boundary": self.boundary, "fill": self.fill, "orientation": self.orientation,
            "rotate": self.rotate, "blocks": list(self.blocks), "iterations": self.iterations,
        }

    @classmethod
    def from_json(cls, d: dict, on_change=None) -> "Layer":
        """A layer from its design dict; ValueError for a malformed one. A design is
        self-contained: images are data: URLs and SVG marks are inline text, never paths."""
        if not isinstance(d, dict):
            raise ValueError(f"design layer must be a JSON object, got {type(d).__name__}")
        who = f"design layer {d.get('name', '?')!r}"
        missing = [k for k in ("name", "mark") if k not in d]
        if missing:
            raise ValueError(f"{who}: missing {' and '.join(map(repr, missing))}")
        for key, kind in (("encodings", dict), ("forces", list), ("blocks", list)):
            if d.get(key) is not None and not isinstance(d[key], kind):
                raise ValueError(f"{who}: {key} must be a JSON {'object' if kind is dict else 'array'}, "
                                 f"got {type(d[key]).__name__}")
        _check_inline(who, d)
        enc = {k: v for k, v in (d.get("encodings") or {}).items() if k in CHANNELS}
        return cls(d["name"], mark=_mark(d["mark"], Mark.from_json), rows=d.get("rows"),
                   container=_container(d.get("container")),
                   emitter=_emitter(d.get("emitter")),
                   forces=_forces(d.get("forces") or []),
                   boundary=d.get("boundary", "closed"), fill=d.get("fill"),
                   orientation=d.get("orientation"), rotate=d.get("rotate", False),
                   blocks=d.get("blocks", []), iterations=d.get("iterations", 600),
                   on_change=on_change, **enc)

    def __repr__(self) -> str:
        bound = ", ".join(f"{k}={v!r}" for k, v in self.encodings.items() if v not in (None, 0.0))
        return (f"Layer({self.name!r}, mark={self.mark.kind}, {bound or 'no encodings'}, "
                f"container={self.container.kind if self.container else 'canvas'}, "
                f"forces={len(self.forces)}, boundary={self.boundary!r})")


def _check_inline(who: str, d: dict) -> None:
    """ValueError unless the layer's mark and image container are inline data (no paths)."""
    mark, container = d.get("mark"), d.get("container")
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


def _rows(rows):
    """None, ``{"column": name, "value": v}`` or ``{"index": [labels]}``."""
    if rows is None or (isinstance(rows, dict) and (
            set(rows) == {"column", "value"} or (set(rows) == {"index"}
                                                 and isinstance(rows["index"], list)))):
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
    out = [_from_json("force", force_from_json, f) if isinstance(f, dict) else f for f in items]
    for f in out:
        if not isinstance(f, (PointForce, DirectionalForce)):
            raise TypeError(f"forces must be uw.PointForce or uw.DirectionalForce objects, got {f!r}")
    return out


def _fill(value):
    if value is None:
        return None
    v = check_finite("Layer", "fill", value)
    if not 0 < v <= 1:
        raise ValueError(f"fill must be None or a share in (0, 1], got {value!r}")
    return v


def _orientation(value):
    if value in ORIENTATIONS or (isinstance(value, Real) and not isinstance(value, bool)):
        return value if value in ORIENTATIONS else check_finite("Layer", "orientation", value)
    raise ValueError(f"orientation must be one of None, 'to_center', 'along_emitter', or a number "
                     f"of degrees; got {value!r}")


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
        if value is None or isinstance(value, str):
            return value
        if name == "margin" and isinstance(value, Real) and not isinstance(value, bool):
            v = check_finite("Layer", "margin", value)
            if not 0 <= v <= 2:
                raise ValueError(f"margin must be a column name or a fraction in [0, 2], got {value!r}")
            return v
        raise TypeError(f"{name} must be a column name or None, got {value!r}")
    return check


_CHECKS = {
    "mark": _mark, "container": _container, "emitter": _emitter, "forces": _forces,
    "boundary": lambda v: check_choice("Layer", "boundary", v, BOUNDARIES),
    "fill": _fill, "orientation": _orientation, "rotate": _rotate,
    "blocks": lambda v: [str(b) for b in ([v] if isinstance(v, str) else list(v or []))],
    "iterations": _iterations, "name": lambda v: layer_name(v),
    **{c: _channel(c) for c in CHANNELS},
}


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
