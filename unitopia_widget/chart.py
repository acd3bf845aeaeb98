"""``Chart``: a DataFrame bound to a design, laid out headless.

The widget (``widget.UnitoPia``) wraps one ``Chart`` and only syncs it; all
behaviour that needs no browser lives here, so scripts and tests run without
a front end.
"""
from __future__ import annotations

import os
import warnings

import numpy as np
import pandas as pd

from .layout import engine
from .layout.prepare.bind import bind
from .layout.prepare.tally import mark_titles
from .layout.shortfall import warn_shortfalls
from .layout.prepare.scale import DEFAULT_OPEN_FILL, MAX_COVER, overfilled
from .design.encodings import (NUMERIC_CHANNELS, check_column, invalid_rows, sorted_unique,
                               titles as row_titles, tooltip_fields, warn_small_marks)
from .output import animation, html
from .output.files import atomic_write, write_json
from .output.publish import export_png, export_svg
from .hand import HandControl
from .piling import Piling
from .design.page import PageOptions
from .design import piles as pile_mod
from .design.scene import SCHEMA, VERSION, Layer, block_order, check_design_header
from .design.files import design_code, load_design
from .design.positions import POSITION_CHANNELS, invalid_position_rows
from .design.arguments import (check_canvas, check_scales, check_seed, parse_marks, pick_mark,
                               read_background, rows_of)
from .design.upgrade import upgrade
from .design.validate import closest
from .design.bounds import MAX_UNITS  # noqa: F401  (the chart's bound, where tests look)

ARGUMENTS = ("mark", "size", "width", "height", "color", "shape", "by", "margin", "order", "container",
             "emitter", "forces", "boundary", "fill", "orientation", "rotate", "footprint",
             "margin_of", "canvas", "background", "seed", "device", "iterations", "dropna",
             "scales", "title", "caption",
             "legend", "tooltip", "size_range", "width_range", "height_range", "x", "y",
             "x_scale", "y_scale", "arrange", "count", "per", "rounding", "partial", "piles")
PLACING = ("container", "emitter", "x", "y")   # arguments that place by= layers: no piles
MAX_LAYERS = 100   # each layer renders its own sprites and fields: by= a column of ids is refused
MIN_MARK_AREA = 4.0   # canvas px^2 of container per mark: below, marks shrink out of sight
MAX_SPREAD = 1e6   # largest / smallest mark extent: beyond, float32 rendering loses the small ones


def check_kwargs(owner: str, kwargs: dict, allowed) -> None:
    """A TypeError for the first unknown keyword, suggesting the closest allowed one."""
    for key in kwargs:
        if key not in allowed:
            raise TypeError(f"{owner}() got an unexpected keyword argument {key!r}"
                            f"{closest(key, allowed)}")


class Chart(Piling, HandControl):
    """A pictorial unit chart: ``Chart(df, mark="star", size="Duration", color="Task")``.

    See ``UnitoPia`` for the arguments; ``Chart`` takes the same ones. Pins, ``set_data``
    and warm starts: ``hand.HandControl``; piles (``by=`` without a container):
    ``piling.Piling``.
    ``scales="shared"`` (default): one global scale for all layers, so sizes
    stay comparable across layers; ``"independent"``: each layer its own scale,
    so each closed container fills (sizes compare only within a layer).
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
        self.canvas = check_canvas(opts.pop("canvas", (800, 500)))
        self.background = read_background(opts.pop("background", None))
        self.seed = check_seed(opts.pop("seed", 0))
        self.scales = check_scales(opts.pop("scales", "shared"))
        self.page = PageOptions(opts.pop("title", None), opts.pop("caption", None),
                                True if opts.get("legend") is None else opts["legend"])
        opts.pop("legend", None)
        self._tooltip = opts.pop("tooltip", None)
        tooltip_fields(df, self._tooltip)
        self.device = engine.pick_device(opts.pop("device", None))
        by = opts.pop("by", None)
        piles = pile_mod.check_piles(opts.pop("piles", "columns"))
        # piles lay out the layers of by= that have no place of their own
        placed = [k for k in PLACING if opts.get(k) is not None]
        if "piles" in kwargs and piles is not None and (by is None or placed):
            why = "by= is not set" if by is None else f"{placed[0]}= places the layers already"
            raise ValueError(f"piles={piles!r} lays out the layers of by=<column> as piles, but "
                             f"{why}; pass by= without {', '.join(PLACING)}, or leave piles out")
        mark = parse_marks(opts.pop("mark", "circle"))   # Marks shared by the layers: renders cached once
        shape = opts.get("shape")
        categories = {c: v for c, v in (("by", by), ("shape", shape)) if v is not None}
        missing_by = np.zeros(len(df), bool)
        for channel, column in categories.items():
            check_column(df, channel, column)
            missing_by |= df[column].isna().to_numpy()
        if opts.pop("dropna", False):
            bad = invalid_rows(df, opts) | invalid_position_rows(df, opts) | missing_by
            if bad.any():
                bound = [f"{c}={opts[c]!r}" for c in NUMERIC_CHANNELS + POSITION_CHANNELS
                         if isinstance(opts.get(c), str) and opts[c] in df.columns]
                bound += [f"{c}={v!r}" for c, v in categories.items() if df[v].isna().any()]
                warnings.warn(f"dropna=True: dropped {int(bad.sum())} of {len(df)} rows whose "
                              f"values are missing, infinite or out of range in "
                              f"{', '.join(bound)}", stacklevel=3)
                df = df[~bad]
                if len(df) == 0:
                    raise ValueError("dropna=True dropped every row")
        elif missing_by.any():
            channel, column = next((c, v) for c, v in categories.items() if df[v].isna().any())
            raise ValueError(f"{channel}={column!r}: {int(df[column].isna().sum())} of {len(df)} "
                             f"rows are missing; fill them (df[{column!r}].fillna(...)) or pass "
                             f"dropna=True to drop them")
        self.df = df
        self.layers: list[Layer] = []
        self.laid: engine.Layout | None = None   # the last run's layout
        self._units = None
        self._piles = None
        if by is None:
            self.add_layer("layer-1", mark=pick_mark(mark, None, shape), **opts)
        else:
            try:
                values = pd.unique(df[by])
            except TypeError:
                raise TypeError(f"by={by!r}: the column's values must be hashable categories "
                                f"(str, number, ...), got {type(df[by].iloc[0]).__name__}") from None
            if len(values) > MAX_LAYERS:
                raise ValueError(f"by={by!r} has {len(values)} distinct values, one layer each; at "
                                 f"most {MAX_LAYERS} layers are supported: group or bin the column "
                                 f"first, or use color={by!r} instead")
            for v in sorted_unique(df[by]):   # the colour legend's order of the categories
                self.add_layer(str(v), mark=pick_mark(mark, v, shape), rows=rows_of(df, by, v),
                               **opts)
        self.bind_check()
        if by is not None and piles is not None and not placed:
            if "piles" not in kwargs and not pile_mod.fits(len(self.layers), self.canvas, piles):
                piles = "grid"   # more categories than columns fit: small multiples, wrapped
            self._lay_piles(piles, keep_forces=bool(opts.get("forces")))

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
        try:
            self._recheck()
            self._regroup()
        except Exception:
            self.layers.remove(layer)
            raise
        self._changed()
        return layer

    def layer(self, name) -> Layer:
        """The layer called ``name``; an int that names no layer is a position
        (so ``layer(2025)`` finds the layer ``by="Year"`` made, and ``layer(0)`` the first)."""
        for layer in self.layers:
            if layer.name == str(name):
                return layer
        names = [layer.name for layer in self.layers]
        if isinstance(name, int) and not isinstance(name, bool):
            if -len(self.layers) <= name < len(self.layers):
                return self.layers[name]
            raise KeyError(f"no layer named {name!r} and no position {name} among "
                           f"{len(self.layers)} layers: {names}")
        raise KeyError(f"no layer {name!r}{closest(str(name), names)}; layers: {names}")

    def remove_layer(self, name) -> None:
        """Remove the layer ``name`` (or position); refused while another layer blocks on it
        or when it is the chart's only layer."""
        layer = self.layer(name)
        users = [other.name for other in self.layers if layer.name in other.blocks]
        if users:
            raise ValueError(f"layer {layer.name!r} is blocked on by {users}; remove those blocks first")
        if len(self.layers) == 1:
            raise ValueError("a chart keeps at least one layer")
        self.layers.remove(layer)
        self._recheck()
        self._changed()

    def move_layer(self, name, position: int) -> None:
        """Move a layer to ``position`` in drawing order."""
        layer = self.layer(name)
        self.layers.remove(layer)
        self.layers.insert(position, layer)
        self._recheck()
        self._changed()

    def _layer_changed(self, layer, keys) -> None:
        if "name" in keys:
            names = [x.name for x in self.layers]
            if names.count(layer.name) > 1:
                raise ValueError(f"a layer named {layer.name!r} exists already")
        self._recheck()   # raising here makes Layer.set undo the change
        if "blocks" in keys:
            self._regroup()
        self._changed()

    def _recheck(self) -> None:
        """After construction, re-bind on every design change: bad bindings fail at once."""
        if self._units is not None:
            self.bind_check()

    def _changed(self) -> None:
        """Called after every design change; the widget overrides it to sync."""

    def bind_check(self, warn: bool = True) -> None:
        """Encode every layer now, so bad bindings fail at binding time (``warn``: give the
        bindings' warnings; False when this call gave them already)."""
        self._units = self._check(self.layers, self.canvas, warn)

    def _check(self, layers, canvas, warn: bool = True):
        """The units of ``layers``, or a ValueError for whatever the layout would fail on."""
        if len(layers) > MAX_LAYERS:
            raise ValueError(f"{len(layers)} layers is more than this widget lays out "
                             f"({MAX_LAYERS}); merge some layers")
        block_order(layers)
        units = bind(self.df, layers, warn)   # more than MAX_UNITS marks: refused there
        for half in (units.half_w, units.half_h):
            if not (np.isfinite(half).all() and half.min() > 0 and half.max() <= MAX_SPREAD * half.min()):
                bound = sorted({f"{c}={layer.encodings[c]!r}" for layer in layers
                                for c in ("size", "width", "height") if layer.encodings[c]})
                raise ValueError(f"the values bound to {', '.join(bound) or 'the marks'} span too "
                                 f"wide a range: the largest mark would be more than {MAX_SPREAD:g} "
                                 f"times the smallest (or overflow); clip, rescale or log-transform "
                                 f"the column")
        for i, layer in enumerate(layers):
            if layer.container is None:
                continue
            area = layer.container.area(canvas)
            if not area > 0:
                raise ValueError(f"layer {layer.name!r}: its container {layer.container!r} has no "
                                 f"area inside the {canvas[0]:g} x {canvas[1]:g} canvas; move it "
                                 f"onto the canvas")
            count = int((units.layer == i).sum())
            if area < MIN_MARK_AREA * count:
                raise ValueError(f"layer {layer.name!r}: its container {layer.container!r} holds "
                                 f"{area:.3g} px^2 for {count} marks, so each mark would be under "
                                 f"{MIN_MARK_AREA ** 0.5:g} px across; make the container larger")
        return units

    # --- layout -------------------------------------------------------------
    def layout(self, on_frame=None, cancel=None, on_progress=None, frame_every: int = 3,
               abort=None, fresh: bool = False, warn_bindings: bool = True):
        """Solve the layout now; returns the placements table and keeps it, and the
        run's frames in ``frames`` (``(F, N, 4)``, see ``layout.frames``). ``abort()``
        True during the setup raises ``Cancelled`` and keeps the previous layout.
        A run after a change starts from the last layout (``fresh=True``: from scratch); a
        run with nothing changed returns the last layout at once, showing its last frame
        (``hand.HandControl._unchanged``). ``warn_bindings=False``: the caller has just bound
        the design and warned (each warning once per call)."""
        self.bind_check(warn_bindings)
        self._check_pins()
        for names, total in overfilled(self.layers, self.scales):
            warnings.warn(f"layers {names} share one container under scales='independent', where "
                          f"each open layer's marks cover its own fill of it (by default "
                          f"{DEFAULT_OPEN_FILL:g}): {total:.0%} of the container in all, "
                          f"more than marks can cover ({MAX_COVER:.0%}), so the layers "
                          f"packed last shrink to fit; give them fills that add up to at most "
                          f"{MAX_COVER:g} (layer(name).set(fill=...)) or use "
                          f"scales='shared'", stacklevel=2)
        origin, inputs = self._start_from(fresh)
        if self._unchanged(origin, inputs):   # the last run's layout, its progress and frame
            result = self.laid.result
            if on_progress is not None:
                on_progress(result.iterations, result.stats["loss"], {**result.stats, "phase": "finish"})
            if on_frame is not None:
                on_frame(self.laid.frames[-1].copy())
            return self.laid.placements
        laid = engine.layout(
            self._units, self.layers, self.canvas, seed=self.seed, device=self.device,
            on_frame=on_frame, cancel=cancel, on_progress=on_progress, frame_every=frame_every,
            scales=self.scales, abort=abort, pins=list(self._pins.values()), previous=origin,
            reuse=self._reusable(origin, inputs), settled=self._settled())
        self.laid = laid
        self._remember_run(origin, inputs, laid.units, laid.result)
        if not laid.result.cancelled:
            warn_shortfalls(laid.units, self.layers, self.canvas, laid.result, self.df)
            warn_small_marks(laid.placements, self.layers)
        return laid.placements

    placements = property(lambda self: None if self.laid is None else self.laid.placements,
                          doc="The last layout's table (``layout.engine.placements``), or None.")
    result = property(lambda self: None if self.laid is None else self.laid.result,
                      doc="The solver's account of the last layout (``layout.solver.Result``), or None.")
    frames = property(lambda self: None if self.laid is None else self.laid.frames,
                      doc="``(F, N, 4)`` the last run's frames, ending on its layout, or None.")
    units = property(lambda self: self._units,
                     doc="The units of the current design, bound (``design.units.Units``).")

    def boxes(self, units) -> np.ndarray:
        """``(N, 2)`` drawn box width and height of ``units``, canvas px: the last layout's when
        it placed them, else at its global scale (or the starting one)."""
        return engine.boxes(self.laid, units, self.layers, self.canvas)

    def titles(self, units=None) -> list[str]:
        """Tooltip text per unit, in unit order: its row's values (``tooltip=``); a ``per=``
        mark's category, the units it stands for and the rows it covers."""
        units = self._units if units is None else units
        if not any(layer.per is not None for layer in self.layers):
            return row_titles(self.df.loc[units.rows], self._tooltip)
        plain = [""] * len(units.rows)   # per= marks have their own; the others their row's
        alone = [k for k, li in enumerate(units.layer) if self.layers[li].per is None]
        for k, text in zip(alone, row_titles(self.df.loc[[units.rows[k] for k in alone]],
                                             self._tooltip)):
            plain[k] = text
        return mark_titles(self.df, units, self.layers, plain)

    @property
    def tooltip(self):
        """The ``tooltip=`` columns: None (every column), a list of columns and
        ``(column, format)`` pairs, or a dict ``{column: format}``."""
        return self._tooltip

    @tooltip.setter
    def tooltip(self, value):
        tooltip_fields(self.df, value)
        self._tooltip = value

    # --- title, caption, legend ------------------------------------------------------
    title = property(lambda self: self.page.title, doc="The chart's title (None: none).")
    caption = property(lambda self: self.page.caption, doc="The caption under the chart.")
    legend = property(lambda self: dict(self.page.legend),
                      doc='{"visible": bool, "position": "right" | "bottom" | "left" | "top" | [x, y]}')

    @title.setter
    def title(self, value):
        self._set_page(title=value)

    @caption.setter
    def caption(self, value):
        self._set_page(caption=value)

    @legend.setter
    def legend(self, value):
        self._set_page(legend=value)

    def _set_page(self, **change) -> None:
        d = {**self.page.to_json(), **change}
        self.page = PageOptions(d["title"], d["caption"], d["legend"])
        self._changed()

    def to_svg(self, legend=None, title=None, caption=None, outline: bool = False,
               axes: bool = False) -> str:
        """The laid-out chart as SVG text (run the layout first).

        ``legend``: None (the chart's setting: shown when a channel is bound), True,
        False, or a position ("right", "bottom", "left", "top", [x, y] canvas px);
        ``title``/``caption``: text drawn above/below (None: the chart's, "" none);
        ``outline``: draw each layer's container as ``<path class="container">``;
        ``axes``: draw the axes (or band labels) of ``x=``/``y=`` as ``<g class="axis">``.
        The size legend is area-true at the layout's scale; layers bound to the same
        size column share one size legend, which says so."""
        return export_svg(self, self._export_units(), legend, title, caption, outline, axes)

    def to_png(self, scale: float = 2.0, legend=None, title=None, caption=None,
               outline: bool = False, axes: bool = False) -> bytes:
        """PNG bytes of ``to_svg``'s chart at ``scale`` (in (0, 8]) px per canvas px; each
        distinct mark is rendered once and composited, so any chart that lays out exports."""
        return export_png(self, self._export_units(), legend, title, caption, outline, axes,
                          scale)

    def _export_units(self):
        """The units an export draws: the layout's, checked against the current layers."""
        if self.placements is None:
            raise RuntimeError("no layout yet: call run() (or run(wait=True)) first")
        gone = sorted(set(self.placements["layer"]) - {layer.name for layer in self.layers})
        if gone:
            raise RuntimeError(f"the layout is out of date: layer(s) {gone} were renamed or "
                               f"removed since it was made; run the layout again")
        stale = sorted({name for name, k in zip(self.placements["layer"], self.placements["mark"])
                        if k >= len(self.layer(name).marks)})
        if stale:
            raise RuntimeError(f"the layout is out of date: layer(s) {stale} now draw fewer marks "
                               f"than when it was made; run the layout again")
        units, placed = self._units, self.laid.units
        if not (units.rows == placed.rows and np.array_equal(units.layer, placed.layer)):
            units = placed   # the design changed which rows each layer draws: keep the layout's
        return units

    def save(self, path, legend=None, title=None, caption=None, outline: bool = False,
             fps=None, seconds=None, axes: bool = False) -> None:
        """Write ``.svg`` (the chart), ``.png`` (rendered at 2x), ``.json`` (the design),
        ``.html`` (one page: the SVG with tooltips and a replay of the settling), or
        the last run's settling as ``.gif``, ``.webp``, ``.mp4``, ``.webm`` (``fps`` frames a
        second for ``seconds``; default 20 and 3; video needs the ``[video]`` extra).
        ``legend``, ``title``, ``caption``, ``outline``, ``axes``: as for ``to_svg``."""
        path = os.fspath(path)
        ext = os.path.splitext(path)[1].lower()
        if (fps is not None or seconds is not None) and ext not in animation.FORMATS:
            raise ValueError(f"save: fps and seconds are for an animation "
                             f"({', '.join(animation.FORMATS)}), not {ext!r}")
        if ext in (".svg", ".html") + animation.FORMATS:
            svg = self.to_svg(legend=legend, title=title, caption=caption, outline=outline,
                              axes=axes)
        if ext in animation.FORMATS:
            fps, seconds = animation.check_timing(fps, seconds)
            images = animation.render(self, svg, fps, seconds)
            atomic_write(path, animation.write(path, images, fps))
        elif ext == ".html":
            title = self.page.title if title is None else title
            atomic_write(path, html.page(svg, title or None, html.replay(self)).encode())
        elif ext == ".svg":
            atomic_write(path, svg.encode())
        elif ext == ".png":
            atomic_write(path, self.to_png(2.0, legend, title, caption, outline, axes))
        elif ext == ".json":
            write_json(path, self.design())
        else:
            raise ValueError(f"save: unknown file type {ext!r} in {path!r}; use .svg, .png, .json, .html, .gif, .webp, .mp4 or .webm")

    def design(self) -> dict:
        """The design JSON (docs/protocol.md)."""
        return {"schema": SCHEMA, "version": VERSION, "canvas": list(self.canvas),
                "background": None if self.background is None else {"image": self.background},
                "seed": self.seed, "scales": self.scales, "piles": self._piles,
                **self.page.to_json(),
                "layers": [layer.to_json() for layer in self.layers], **self._pins_json()}

    @classmethod
    def from_design(cls, df: pd.DataFrame, design: dict, **kwargs) -> "Chart":
        """A chart of ``df`` with ``design`` (a design JSON dict, as ``design()`` returns);
        ``kwargs`` as for the constructor (tooltip, device, ...)."""
        kwargs.setdefault("canvas", design.get("canvas", (800, 500)))
        chart = cls(df, **kwargs)
        chart.apply_design(design)
        return chart

    @classmethod
    def load(cls, path, df: pd.DataFrame, **kwargs) -> "Chart":
        """A chart of ``df`` with the design saved at ``path`` (``save("x.json")``)."""
        return cls.from_design(df, load_design(path), **kwargs)

    def to_code(self, df_name: str = "df") -> str:
        """Python source that rebuilds this design (sketched containers and marks included,
        as their stroke lists and polygons) for the DataFrame named ``df_name``."""
        return design_code(self.design(), f"uw.{type(self).__name__}", df_name)

    def apply_design(self, d: dict) -> None:
        """Replace the design by ``d``, all or nothing: a bad design changes nothing."""
        check_design_header(d)
        d = upgrade(d)
        canvas = check_canvas(d.get("canvas", self.canvas))
        seed = check_seed(d.get("seed", self.seed))
        scales = check_scales(d.get("scales", "shared"), "design: scales")
        try:
            piles = pile_mod.check_piles(d.get("piles"))
        except ValueError as exc:
            raise ValueError(f"design: {exc}") from None
        background = d.get("background")
        if background and not (isinstance(background, dict) and isinstance(background.get("image"), str)
                               and background["image"].lstrip()[:5].lower() == "data:"):
            raise ValueError(f"design: background must be null or {{\"image\": \"data:image/png;"
                             f"base64,...\"}}; got {background!r:.60}")
        background = read_background(background["image"]) if background else None
        try:
            page = PageOptions.from_json(d)
        except (ValueError, TypeError) as exc:
            raise ValueError(f"design: {exc}") from None
        if len(d["layers"]) > MAX_LAYERS:
            raise ValueError(f"design: {len(d['layers'])} layers, more than the {MAX_LAYERS} "
                             f"this widget lays out")
        layers = []
        for i, x in enumerate(d["layers"]):
            try:
                layers.append(Layer.from_json(x))
            except (ValueError, TypeError, KeyError, AttributeError, IndexError) as exc:
                text = str(exc) if isinstance(exc, (ValueError, TypeError)) else repr(exc)
                if not text.startswith("design layer"):
                    name = x.get("name", "?") if isinstance(x, dict) else "?"
                    text = f"design layer {i} ({name!r}): {text}"
                raise ValueError(text) from None
        names = [layer.name for layer in layers]
        if len(set(names)) != len(names):
            raise ValueError(f"design: layer names must be unique, got {names}")
        units = self._check(layers, canvas)
        pins = self._read_pins(d, layers, units, canvas)
        for layer in layers:
            layer._on_change = self._layer_changed
        self.canvas, self.layers, self.background, self.seed = canvas, layers, background, seed
        self._pins = pins
        self.page, self.scales, self._piles = page, scales, piles
        self._units = units
        self._regroup(warn=False)   # a design is taken as it is: piles edited by hand stay
        self._changed()
