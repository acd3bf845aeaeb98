"""``Chart``: a DataFrame bound to a design, laid out headless.

The widget (``widget.UnitoPia``) wraps one ``Chart`` and only syncs it; all
behaviour that needs no browser lives here, so scripts and tests run without
a front end.
"""
from __future__ import annotations

import json
import os
import tempfile
import warnings

import pandas as pd

from . import engine
from .encodings import invalid_rows, titles as row_titles
from .export import to_png, to_svg
from .images import image_data_url, load_image
from .scene import SCHEMA, VERSION, Layer, block_order, check_design_header
from .validate import check_finite, closest

ARGUMENTS = ("mark", "size", "width", "height", "color", "by", "margin", "order", "container",
             "emitter", "forces", "boundary", "fill", "orientation", "rotate", "canvas",
             "background", "seed", "device", "iterations", "dropna")
MAX_UNITS = 20_000


def check_kwargs(owner: str, kwargs: dict, allowed) -> None:
    """A TypeError for the first unknown keyword, suggesting the closest allowed one."""
    for key in kwargs:
        if key not in allowed:
            raise TypeError(f"{owner}() got an unexpected keyword argument {key!r}"
                            f"{closest(key, allowed)}")


class Chart:
    """A pictorial unit chart: ``Chart(df, mark="star", size="Duration", color="Task")``.

    See ``UnitoPia`` for the arguments; ``Chart`` takes the same ones.
    """

    def __init__(self, df: pd.DataFrame, **kwargs):
        check_kwargs(type(self).__name__, kwargs, ARGUMENTS)
        if not isinstance(df, pd.DataFrame):
            raise TypeError(f"df must be a pandas DataFrame, got {type(df).__name__}")
        if len(df) == 0:
            raise ValueError("df is empty: a unit chart needs at least one row")
        if not df.index.is_unique:
            raise ValueError("df has duplicate index labels; call df.reset_index(drop=True) first")
        opts = dict(kwargs)
        self.canvas = _canvas(opts.pop("canvas", (800, 500)))
        self.background = _background(opts.pop("background", None))
        self.seed = int(opts.pop("seed", 0))
        self.device = engine.pick_device(opts.pop("device", None))
        by = opts.pop("by", None)
        mark = opts.pop("mark", "circle")
        if opts.pop("dropna", False):
            bad = invalid_rows(df, opts)
            if bad.any():
                warnings.warn(f"dropna=True: dropped {int(bad.sum())} of {len(df)} rows whose "
                              f"bound values are missing, infinite or out of range", stacklevel=3)
                df = df[~bad]
                if len(df) == 0:
                    raise ValueError("dropna=True dropped every row")
        self.df = df
        self.layers: list[Layer] = []
        self.placements: pd.DataFrame | None = None
        self.result = None
        self._units = None
        if by is None:
            self.add_layer("layer-1", mark=_pick_mark(mark, None), **opts)
        else:
            if by not in df.columns:
                engine.check_column(df, "by", by)
            values = pd.unique(df[by])
            try:
                values = sorted(values)
            except TypeError:
                pass
            for v in values:
                self.add_layer(str(v), mark=_pick_mark(mark, v), rows={"column": by, "value": v},
                               **opts)
        self.bind_check()

    # --- layers -------------------------------------------------------------
    def add_layer(self, name: str, data: pd.DataFrame | None = None, rows=None, **fields) -> Layer:
        """Append a layer; ``data`` (a subset of the chart's DataFrame) picks its rows."""
        if any(layer.name == name for layer in self.layers):
            raise ValueError(f"a layer named {name!r} exists already")
        if data is not None:
            if not isinstance(data, pd.DataFrame):
                raise TypeError(f"data must be a DataFrame (rows of the chart's df), got "
                                f"{type(data).__name__}")
            rows = {"index": data.index.tolist()}
        layer = Layer(name, rows=rows, on_change=self._layer_changed, **fields)
        self.layers.append(layer)
        self._changed()
        return layer

    def layer(self, name) -> Layer:
        """The layer called ``name`` (or at position ``name`` when an int)."""
        if isinstance(name, int):
            return self.layers[name]
        for layer in self.layers:
            if layer.name == str(name):
                return layer
        names = [layer.name for layer in self.layers]
        raise KeyError(f"no layer {name!r}{closest(str(name), names)}; layers: {names}")

    def remove_layer(self, name) -> None:
        layer = self.layer(name)
        users = [other.name for other in self.layers if layer.name in other.blocks]
        if users:
            raise ValueError(f"layer {layer.name!r} is blocked on by {users}; remove those blocks first")
        if len(self.layers) == 1:
            raise ValueError("a chart keeps at least one layer")
        self.layers.remove(layer)
        self._changed()

    def move_layer(self, name, position: int) -> None:
        """Move a layer to ``position`` in drawing order."""
        layer = self.layer(name)
        self.layers.remove(layer)
        self.layers.insert(position, layer)
        self._changed()

    def _layer_changed(self, layer, keys) -> None:
        if "name" in keys:
            names = [x.name for x in self.layers]
            if names.count(layer.name) > 1:
                raise ValueError(f"a layer named {layer.name!r} exists already")
        self._changed()

    def _changed(self) -> None:
        """Called after every design change; the widget overrides it to sync."""

    def bind_check(self) -> None:
        """Encode every layer now, so bad bindings fail at binding time."""
        block_order(self.layers)
        units = engine.bind(self.df, self.layers)
        if len(units.rows) > MAX_UNITS:
            raise ValueError(f"{len(units.rows)} units is more than this widget lays out "
                             f"({MAX_UNITS}); sample or aggregate the rows first")
        self._units = units

    # --- layout -------------------------------------------------------------
    def layout(self, on_frame=None, cancel=None, on_progress=None, frame_every: int = 3):
        """Solve the layout now; returns the placements table and keeps it."""
        self.bind_check()
        units, result, table = engine.layout(
            self.df, self.layers, self.canvas, seed=self.seed, device=self.device,
            on_frame=on_frame, cancel=cancel, on_progress=on_progress, frame_every=frame_every)
        self._units, self.result, self.placements = units, result, table
        return table

    def titles(self) -> list[str]:
        """Tooltip text per unit, in unit order."""
        units = self._units
        return row_titles(self.df.loc[units.rows])

    def to_svg(self) -> str:
        """The laid-out chart as SVG text (run the layout first)."""
        if self.placements is None:
            raise RuntimeError("no layout yet: call run() (or run(wait=True)) first")
        return to_svg(self.canvas, self.placements, self.layers, self._units.colors,
                      self.titles(), self.background)

    def save(self, path) -> None:
        """Write ``.svg`` (the chart), ``.png`` (rendered at 2x) or ``.json`` (the design)."""
        path = os.fspath(path)
        ext = os.path.splitext(path)[1].lower()
        if ext == ".svg":
            _atomic_write(path, self.to_svg().encode())
        elif ext == ".png":
            _atomic_write(path, to_png(self.to_svg(), self.canvas, 2.0))
        elif ext == ".json":
            _atomic_write(path, json.dumps(self.design(), indent=1).encode())
        else:
            raise ValueError(f"save: unknown file type {ext!r} in {path!r}; use .svg, .png or .json")

    def design(self) -> dict:
        """The design JSON (docs/protocol.md)."""
        return {"schema": SCHEMA, "version": VERSION, "canvas": list(self.canvas),
                "background": None if self.background is None else {"image": self.background},
                "seed": self.seed, "layers": [layer.to_json() for layer in self.layers]}

    def apply_design(self, d: dict) -> None:
        """Replace the design by ``d``, all or nothing: a bad design changes nothing."""
        check_design_header(d)
        canvas = _canvas(d.get("canvas", self.canvas))
        background = d.get("background")
        layers = [Layer.from_json(x) for x in d["layers"]]
        names = [layer.name for layer in layers]
        if len(set(names)) != len(names):
            raise ValueError(f"design: layer names must be unique, got {names}")
        block_order(layers)
        engine.bind(self.df, layers)
        for layer in layers:
            layer._on_change = self._layer_changed
        self.canvas, self.layers = canvas, layers
        self.background = _background(background["image"]) if background else None
        self.seed = int(d.get("seed", self.seed))
        self.bind_check()
        self._changed()


def load_design(path) -> dict:
    """Read and check a design file; a corrupt or too-new file raises ValueError."""
    try:
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
    except json.JSONDecodeError as e:
        raise ValueError(f"design file {os.fspath(path)!r} is not valid JSON: {e}") from None
    check_design_header(d)
    return d


def _atomic_write(path: str, data: bytes) -> None:
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".unitopia-", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _pick_mark(mark, value):
    if isinstance(mark, dict) and not ("kind" in mark and isinstance(mark.get("kind"), str)):
        if value is None:
            raise ValueError("mark is a dict of category -> mark, which needs by=<column>")
        if value not in mark and str(value) not in mark:
            raise ValueError(f"mark: no mark for category {value!r}; the dict has "
                             f"{list(mark)}")
        return mark[value] if value in mark else mark[str(value)]
    return mark


def _canvas(canvas) -> tuple[float, float]:
    if not hasattr(canvas, "__len__") or len(canvas) != 2:
        raise ValueError(f"canvas must be (width, height) in pixels, got {canvas!r}")
    w, h = (check_finite("canvas", n, v) for n, v in zip(("width", "height"), canvas))
    if not (16 <= w <= 10_000 and 16 <= h <= 10_000):
        raise ValueError(f"canvas must be between 16 and 10000 pixels a side, got {canvas!r}")
    return (w, h)


def _background(source):
    if source is None:
        return None
    return image_data_url(load_image(source))
