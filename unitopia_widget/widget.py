"""``UnitoPia``: the Jupyter widget. Traitlets and their sync only; the work is in ``Chart``.

The traits and messages are specified in ``docs/protocol.md``.
"""
from __future__ import annotations

import base64
import copy
import pathlib
import threading
import warnings

import anywidget
import numpy as np
import pandas as pd
import traitlets as t

from .chart import ARGUMENTS, Chart, check_kwargs, load_design
from .encodings import rgba
from .export import to_png
from .runner import Runner

STATIC = pathlib.Path(__file__).parent / "static"


class _SyncedChart(Chart):
    """A Chart that tells its widget about every design change."""

    widget = None

    def _changed(self) -> None:
        if self.widget is not None:
            self.widget._push_design()


class UnitoPia(anywidget.AnyWidget):
    """A pictorial unit chart in the notebook: ``UnitoPia(df, mark="star", size="Duration")``.

    Arguments (all but ``df`` keyword-only): ``mark`` (a shape name, SVG path or text,
    PNG/JPEG path, array, PIL image, ``uw.Mark``; or ``{category: spec}`` with ``by``),
    ``size`` (area proportional to a column), ``width``/``height`` (that extent
    proportional), ``color`` (a column or CSS colour), ``by`` (one layer per value),
    ``margin`` (fraction of the mark's size, or a column), ``order`` (emission
    order column), ``container``, ``emitter``, ``forces``, ``boundary``
    ("closed" fills, "open" only bounds), ``fill`` (share of the container
    covered; open default 0.5), ``orientation``, ``rotate``, ``canvas`` (w, h) px,
    ``background`` (image), ``seed``, ``device`` ("cpu", "cuda", None = automatic),
    ``iterations`` (cap per run), ``dropna`` (drop rows with unusable values, warning),
    ``scales`` ("shared", the default: one global scale, so sizes stay comparable
    across layers; "independent": each layer its own, so each closed container fills).
    """

    _esm = STATIC / "widget.js"
    _css = STATIC / "widget.css"

    design = t.Dict().tag(sync=True)                   #: the design JSON (docs/protocol.md)
    marks = t.List(t.Dict()).tag(sync=True)            #: one image per (layer mark, colour)
    fields = t.List(t.Dict()).tag(sync=True)           #: [{"name", "type"}] of the DataFrame
    units = t.Bytes(b"").tag(sync=True)                #: float32 (N, 4): layer, mark, base w, base h
    colors = t.Bytes(b"").tag(sync=True)               #: uint8 (N, 4) RGBA
    titles = t.List(t.Unicode()).tag(sync=True)        #: tooltip per unit
    frame = t.Bytes(b"").tag(sync=True)                #: float32 (N, 4): x, y, angle deg, scale
    frame_count = t.Int(0).tag(sync=True)              #: frames sent in the current run
    status = t.Unicode("idle").tag(sync=True)          #: idle, running, done, error
    progress = t.Dict().tag(sync=True)                 #: {"iteration", "max_iterations", "loss"}
    error = t.Unicode("").tag(sync=True)               #: last error message, "" if none
    selected_units = t.List(t.Int()).tag(sync=True)    #: unit indices selected in the widget

    def __init__(self, df: pd.DataFrame, **kwargs):
        check_kwargs("UnitoPia", kwargs, ARGUMENTS)
        chart = _SyncedChart(df, **kwargs)
        super().__init__()
        self._chart = chart
        self._runner = Runner()
        self._applying = False
        self._progress = {}
        chart.widget = self
        self.fields = _fields(chart.df)
        self._push_design()
        self.on_msg(self._on_message)

    # --- the chart's API ----------------------------------------------------
    @property
    def layers(self):
        """The layers, in drawing order."""
        return self._chart.layers

    def layer(self, name):
        return self._chart.layer(name)

    def add_layer(self, name: str, data: pd.DataFrame | None = None, **fields):
        return self._chart.add_layer(name, data=data, **fields)

    def remove_layer(self, name) -> None:
        self._chart.remove_layer(name)

    def move_layer(self, name, position: int) -> None:
        self._chart.move_layer(name, position)

    @property
    def df(self) -> pd.DataFrame:
        return self._chart.df

    @property
    def placements(self) -> pd.DataFrame | None:
        """One row per unit: row, layer, x, y, angle, sx, sy (and width, height in px)."""
        return self._chart.placements

    @property
    def selected(self) -> pd.DataFrame:
        """The DataFrame rows of the units selected in the widget."""
        rows = self._chart._units.rows
        return self._chart.df.loc[[rows[i] for i in self.selected_units if 0 <= i < len(rows)]]

    def to_svg(self) -> str:
        return self._chart.to_svg()

    def save(self, path) -> None:
        """``.svg``, ``.png`` or ``.json`` (the design, reload with ``UnitoPia.load``)."""
        self._chart.save(path)

    @classmethod
    def load(cls, path, df: pd.DataFrame, **kwargs) -> "UnitoPia":
        """A widget for ``df`` with the design saved at ``path``."""
        design = load_design(path)
        kwargs.setdefault("canvas", design.get("canvas", (800, 500)))
        w = cls(df, **kwargs)
        w._chart.apply_design(design)
        return w

    # --- running ------------------------------------------------------------
    def run(self, wait: bool = False):
        """Lay out the marks. ``wait=True`` blocks and returns ``placements``;
        otherwise the layout runs in a thread and the widget animates it."""
        self._runner.stop()  # a run while running restarts: the old one ends first
        self._chart.bind_check()
        self._push_units()
        with self.hold_sync():
            self.status, self.error, self.frame_count = "running", "", 0
            self.progress = {"iteration": 0, "max_iterations": self._cap(), "loss": None}
        self._runner.start(self._job, self._on_frame, self._on_done, self._on_run_error)
        if wait:
            self._runner.wait()
            return self.placements
        return None

    def stop(self) -> None:
        """Stop the running layout; the last frame becomes the layout."""
        self._runner.stop()

    def wait(self, timeout: float | None = None):
        """Wait for a running layout; re-raises its error. Returns ``placements``."""
        self._runner.wait(timeout)
        return self.placements

    def _cap(self) -> int:
        return max(layer.iterations for layer in self._chart.layers)

    def _job(self, on_frame, cancel):
        def progress(i, loss, stats):
            self._progress = {"iteration": i, "max_iterations": self._cap(), "loss": loss}
        return self._chart.layout(on_frame=on_frame, cancel=cancel, on_progress=progress)

    def _on_frame(self, frame: np.ndarray) -> None:
        with self.hold_sync():
            self.frame = frame.astype(np.float32).tobytes()
            self.frame_count += 1
            self.progress = dict(self._progress)

    def _on_done(self, table) -> None:
        self.status = "done"

    def _on_run_error(self, exc: BaseException) -> None:
        """A failed run keeps the previous layout: show it again instead of the run's last frame."""
        result, units = self._chart.result, self._chart._units
        keep = result is not None and units is not None and len(result.center) == len(units.rows)
        frame = (np.column_stack([result.center, result.angle, result.unit_scale])
                 .astype(np.float32).tobytes() if keep else b"")
        with self.hold_sync():
            self.frame = frame
        self._on_error(exc)

    def _on_error(self, exc: BaseException) -> None:
        with self.hold_sync():
            self.error = f"{type(exc).__name__}: {exc}"
            self.status = "error"
        warnings.warn(f"UnitoPia layout failed: {self.error}", RuntimeWarning, stacklevel=2)

    # --- sync ---------------------------------------------------------------
    def _push_design(self) -> None:
        """Python -> JS: the design and everything derived from it."""
        self._applying = True
        try:
            self.design = copy.deepcopy(self._chart.design())
        finally:
            self._applying = False
        self._push_units()

    def _push_units(self) -> None:
        units = self._chart._units
        if units is None:
            return
        layers = self._chart.layers
        keys, marks, index = {}, [], np.zeros(len(units.rows), dtype=np.float32)
        for k, (li, color) in enumerate(zip(units.layer, units.colors)):
            key = (int(li), color)
            if key not in keys:
                keys[key] = len(marks)
                mark = layers[li].mark
                svg = mark.to_svg(color, max_side=128)
                marks.append({"layer": layers[li].name, "aspect": mark.aspect,
                              "src": "data:image/svg+xml;base64," + base64.b64encode(svg.encode()).decode()})
            index[k] = keys[key]
        table = np.stack([units.layer.astype(np.float32), index,
                          (2 * units.half_w).astype(np.float32),
                          (2 * units.half_h).astype(np.float32)], axis=1)
        with self.hold_sync():
            self.marks = marks
            self.units = np.ascontiguousarray(table, dtype=np.float32).tobytes()
            self.colors = rgba(units.colors).tobytes()
            self.titles = self._chart.titles()

    @t.observe("design")
    def _design_from_front_end(self, change) -> None:
        if self._applying:
            return
        try:
            self._chart.apply_design(change["new"])
            self.error = ""
        except Exception as exc:  # a bad edit keeps the last good design
            self.error = f"{type(exc).__name__}: {exc}"
            self._push_design()

    def _on_message(self, _widget, msg, _buffers) -> None:
        kind = msg.get("type") if isinstance(msg, dict) else None
        if kind == "run":
            threading.Thread(target=self._safe(self.run), daemon=True).start()
        elif kind == "stop":
            threading.Thread(target=self._safe(self.stop), daemon=True).start()
        elif kind == "export":
            self._safe(lambda: self._export(msg.get("format")))()

    def _safe(self, fn):
        def call():
            try:
                fn()
            except Exception as exc:
                self._on_error(exc)
        return call

    def _export(self, fmt: str) -> None:
        svg = self._chart.to_svg()
        if fmt == "png":
            data = "data:image/png;base64," + base64.b64encode(
                to_png(svg, self._chart.canvas, 2.0)).decode()
        elif fmt == "svg":
            data = svg
        else:
            raise ValueError(f"export format must be 'svg' or 'png', got {fmt!r}")
        self.send({"type": "export", "format": fmt, "data": data})


def _fields(df: pd.DataFrame) -> list[dict]:
    out = []
    for name in df.columns:
        s = df[name]
        if pd.api.types.is_datetime64_any_dtype(s):
            kind = "datetime"
        elif pd.api.types.is_numeric_dtype(s) and not pd.api.types.is_bool_dtype(s):
            kind = "numeric"
        else:
            kind = "categorical"
        out.append({"name": str(name), "type": kind})
    return out
