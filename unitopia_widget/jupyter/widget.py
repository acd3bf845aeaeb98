"""``UnitoPia``: the Jupyter widget. Traitlets and their sync only; the work is in ``Chart``.

The traits and messages are specified in ``docs/protocol.md``.
"""
from __future__ import annotations

import base64
import copy
import pathlib
import threading
import time
import uuid
import warnings

import anywidget
import numpy as np
import pandas as pd
import traitlets as t

from ..design import icons
from ..chart import ARGUMENTS, Chart, check_kwargs
from ..design.files import load_design
from ..design.encodings import rgba
from .keep import DesignFile, KeptDesign
from .drag import LiveDrag
from .pins import Pinning
from .notebook import StaticDisplay
from .drawn import axes_trait, labels_trait, legend_trait, unit_marks
from .runner import Runner
from ..layout.prepare.problem import Cancelled

STATIC = pathlib.Path(__file__).parent.parent / "static"


class _SyncedChart(Chart):
    """A Chart that tells its widget about every design change."""

    widget = None

    def _changed(self) -> None:
        if self.widget is not None:
            self.widget._push_design()


class UnitoPia(LiveDrag, Pinning, KeptDesign, anywidget.AnyWidget):
    """A pictorial unit chart in the notebook: ``UnitoPia(df, mark="star", size="Duration")``.

    Arguments (all but ``df`` keyword-only): ``mark`` (a shape name, an icon name such as
    ``"fa:apple-whole"``, SVG path or text, PNG/JPEG path, array, PIL image, ``uw.Mark``;
    a list of those, drawn in turn by the rows; or ``{category: spec}`` with ``shape``
    or ``by``), ``shape`` (a categorical column picking each row's mark),
    ``size`` (area proportional to a column), ``width``/``height`` (that extent
    proportional), ``size_range``/``width_range``/``height_range`` (``(min_px, max_px)``:
    the values map linearly onto that range of extents instead, not data-true), ``color`` (a column or CSS colour; a multi-colour mark is tinted, keeping its shading), ``by`` (one layer per value, in the colour legend's order),
    ``piles`` (how the layers of ``by`` lie when they have no container, emitter, x or y
    of their own: ``"columns"``, the default, side by side and pulled down, a unit column
    chart; ``"rows"``; ``"grid"``; each pile a labelled rectangle whose area is its total;
    None: together on the whole canvas),
    ``count`` (a column: each row stands for that many units), ``per`` (one mark for that
    many units of one category), ``rounding`` ("largest-remainder", the default, "floor",
    "ceil", "nearest") and ``partial`` (True: each category's remainder drawn as one clipped
    mark), ``margin`` (the gap to its neighbours, a fraction of the mark's size; or a column),
    ``margin_of`` ("median", the default: a mark larger than its layer's median mark keeps
    the median mark's gap; "own": each mark's own size however large), ``order`` (emission
    order column; without it, an order drawn from the seed), ``container``, ``emitter``, ``forces``, ``boundary``
    ("closed" fills, "open" only bounds), ``fill`` (share of the container
    covered; open default 0.5), ``orientation`` (None, "to_center", "along_emitter",
    degrees, "random" or ("random", lo, hi) degrees: each mark its own angle drawn from the
    seed), ``rotate``, ``footprint`` ("silhouette":
    a mark collides with its ink with enclosed holes filled; "ink": its ink alone, so
    marks may nest), ``canvas`` (w, h) px,
    ``background`` (image), ``seed``, ``device`` ("cpu", "cuda", None = automatic),
    ``iterations`` (cap per run), ``dropna`` (drop rows with unusable values, warning),
    ``scales`` ("shared", the default: one global scale, so sizes stay comparable
    across layers; "independent": each layer its own, so each closed container fills),
    ``title``/``caption`` (text above/below the exported chart), ``legend`` (True, False,
    or a position: "right", "bottom", "left", "top", [x, y]; drawn when a channel is bound),
    ``tooltip`` (the tooltip's columns: a list of columns and ``(column, format)`` pairs, or
    a dict ``{column: format}``, e.g. ``["Task", ("Duration", ".1f")]``; default all).
    ``design_path`` (a design file kept current: when it exists the widget starts from the
    design in it, not from the arguments, and every edit writes it, so a re-executed
    notebook keeps its sketch; see ``save_design``).
    ``status`` is "idle", "running", "done", "stopped" or "error"; ``stale`` is True when
    the design changed since the shown layout.
    """

    _esm = STATIC / "widget.js"
    _css = STATIC / "widget.css"

    design = t.Dict().tag(sync=True)                   #: the design JSON (docs/protocol.md)
    marks = t.List(t.Dict()).tag(sync=True)            #: one image per (layer, mark, colour)
    fields = t.List(t.Dict()).tag(sync=True)           #: [{"name", "type"}] of the DataFrame
    units = t.Bytes(b"").tag(sync=True)                #: float32 (N, 4): layer, mark, base w, base h
    colors = t.Bytes(b"").tag(sync=True)               #: uint8 (N, 4) RGBA
    titles = t.List(t.Unicode()).tag(sync=True)        #: tooltip per unit
    clips = t.Bytes(b"").tag(sync=True)                #: float32 (N,) drawn width share, b"" all whole
    frame = t.Bytes(b"").tag(sync=True)                #: float32 (N, 4): x, y, angle deg, scale
    frame_count = t.Int(0).tag(sync=True)              #: frames sent in the current run
    status = t.Unicode("idle").tag(sync=True)          #: idle, running, done, stopped, error
    progress = t.Dict().tag(sync=True)                 #: {"iteration", "max_iterations", "loss", "phase", "seconds", "done", "stopped"}
    error = t.Unicode("").tag(sync=True)               #: last error message, "" if none
    stale = t.Bool(False).tag(sync=True)               #: design changed since the shown layout
    legend_image = t.Dict().tag(sync=True)             #: {} or {"src": svg data URL, "width", "height"}
    pile_labels = t.List(t.Dict()).tag(sync=True)      #: [{"text", "x", "y", "anchor"}] of the piles
    axes_image = t.Dict().tag(sync=True)               #: {} or {"src": svg data URL, "x", "y", "width", "height"}
    selected_units = t.List(t.Int()).tag(sync=True)    #: unit indices selected in the widget
    pinned_units = t.List(t.Int()).tag(sync=True)      #: unit indices the pins hold
    _session_id = t.Unicode("").tag(sync=True)         #: keys the views' shared undo history

    def __init__(self, df: pd.DataFrame, design_path=None, **kwargs):
        check_kwargs("UnitoPia", kwargs, ARGUMENTS + ("design_path",))
        chart = _SyncedChart(df, **kwargs)
        kept = None if design_path is None else DesignFile(design_path)
        if kept is not None and kept.path.exists():
            chart.apply_design(load_design(kept.path))   # the kept sketch wins
            kept.seen()
        super().__init__(_session_id=uuid.uuid4().hex)
        self._design_file = kept
        self._chart = chart
        self._runner = Runner()
        self._applying = False
        self._progress = {}
        self._laid_out = None     # the layout-relevant design of the shown layout
        self._error_from = None   # "edit" or "run": what made the current error
        self._frame_error = None  # a frame that could not be sent ends the run as an error
        self._fresh = False       # the run asked for a fresh start (run(fresh=True))
        self._static = StaticDisplay(self)
        self._init_drag()
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
        """The layer called ``name``, or at position ``name`` (see ``Chart.layer``)."""
        return self._chart.layer(name)

    def add_layer(self, name: str, data: pd.DataFrame | None = None, **fields):
        """Append a layer; ``data`` (a subset of the widget's DataFrame) picks its rows;
        ``fields`` set it as ``Layer.set`` does."""
        return self._chart.add_layer(name, data=data, **fields)

    def remove_layer(self, name) -> None:
        """Remove a layer (see ``Chart.remove_layer``)."""
        self._chart.remove_layer(name)

    def move_layer(self, name, position: int) -> None:
        """Move a layer to ``position`` in drawing order."""
        self._chart.move_layer(name, position)

    @property
    def df(self) -> pd.DataFrame:
        """The widget's rows (replace them with ``set_data``)."""
        return self._chart.df

    @property
    def placements(self) -> pd.DataFrame | None:
        """One row per unit: row, layer, x, y, angle, sx, sy (and width, height in px, and
        mark: the index into the layer's marks)."""
        return self._chart.placements

    @property
    def selected(self) -> pd.DataFrame:
        """The DataFrame rows of the units selected in the widget: each unit's row, every row
        a ``per=`` mark covers, each row once."""
        units = self._chart._units
        chosen = [i for i in self.selected_units if 0 <= i < len(units.rows)]
        return self._chart.df.loc[units.rows_of(chosen)]

    def set_data(self, df: pd.DataFrame) -> None:
        """Replace the rows, matched by index; the next run starts from the last layout."""
        self._chart.set_data(df)
        self.fields = _fields(df)

    def to_svg(self, legend=None, title=None, caption=None, outline: bool = False,
               axes: bool = False) -> str:
        """The laid-out chart as SVG; see ``Chart.to_svg`` for the arguments."""
        return self._chart.to_svg(legend=legend, title=title, caption=caption, outline=outline,
                                  axes=axes)

    def save(self, path, legend=None, title=None, caption=None, outline: bool = False,
             fps=None, seconds=None, axes: bool = False) -> None:
        """``.svg``, ``.png``, ``.json`` (the design, reload with ``UnitoPia.load``), or the
        settling as ``.gif``, ``.webp``, ``.mp4``, ``.webm``, or ``.html`` (one page with tooltips
        and a replay); see ``Chart.save``. Anything but ``.json`` is refused while a layout
        runs (the status stays): call ``wait()`` or ``stop()`` first. A layout older than
        the design (``stale``) is saved with a warning."""
        picture = pathlib.Path(path).suffix.lower() != ".json"
        if self._runner.running and picture:
            raise RuntimeError(f"cannot save {str(path)[:200]!r} while the layout is running: "
                               f"call w.wait() (or w.stop()) first, then save")
        if self.stale and picture:
            warnings.warn(f"saving {str(path)[:200]!r} from a stale layout: the design changed "
                          f"since it was laid out (w.stale); call w.run(wait=True) first to save "
                          f"the current design", UserWarning, stacklevel=2)
        self._chart.save(path, legend=legend, title=title, caption=caption, outline=outline,
                         fps=fps, seconds=seconds, axes=axes)

    title = property(lambda self: self._chart.title, lambda self, v: setattr(self._chart, "title", v),
                     doc="The chart's title, drawn above it in the export (None: none).")
    caption = property(lambda self: self._chart.caption,
                       lambda self, v: setattr(self._chart, "caption", v),
                       doc="The caption drawn under the chart in the export.")
    piles = property(lambda self: self._chart.piles,
                     lambda self, v: setattr(self._chart, "piles", v),
                     doc="How the layers lie as labelled piles (see ``Chart.piles``).")
    legend = property(lambda self: self._chart.legend,
                      lambda self, v: setattr(self._chart, "legend", v),
                      doc='{"visible": bool, "position": ...}; set True, False, a position or '
                          'that dict (the same name as the constructor\'s and save\'s legend=).')

    @property
    def tooltip(self):
        """The tooltip's columns: None (all), a list of columns and (column, format) pairs,
        or a dict {column: format}; as ``tooltip=``."""
        return self._chart.tooltip

    @tooltip.setter
    def tooltip(self, value):
        self._chart.tooltip = value
        if self._chart._units is not None:
            self.titles = self._chart.titles()

    def dismiss_error(self) -> None:
        """Clear ``error`` (the front end's "dismiss-error" message does the same)."""
        with self.hold_sync():
            self.error = ""
            self._error_from = None
            if self.status == "error":
                self.status = "done" if self.placements is not None else "idle"

    # --- running ------------------------------------------------------------
    def run(self, wait: bool = False, fresh: bool = False):
        """Lay out the marks. ``wait=True`` blocks and returns ``placements``;
        otherwise the layout runs in a thread and the widget animates it. A run after
        a change starts from the last layout; ``fresh=True`` starts over."""
        self._fresh = bool(fresh)
        ticket = self._runner.request()   # a stop() from now on reaches this run
        self._runner.end_current()  # a run while running restarts: the old one ends first
        self._chart.bind_check()
        self._push_units()
        self._frame_error = None
        with self.hold_sync():
            self.status, self.frame_count, self.stale = "running", 0, False
            self._progress = {"iteration": 0, "max_iterations": self._cap(), "loss": None}
            self.progress = {**self._progress, "done": False}   # this run's, from 0
        self._laid_out = _layout_key(self._chart.design())
        if not self._runner.start(self._job, self._on_frame, self._on_done, self._on_run_error,
                                  ticket=ticket, nice=0 if self._answering else None):
            self._on_done(None)   # stopped before it started
        elif wait:
            try:
                self._runner.wait()
            except KeyboardInterrupt:   # the notebook's stop button: end the run cleanly
                self._runner.stop()
                raise
            return self.placements
        return None

    def stop(self) -> None:
        """Stop the running layout and any requested one; the last frame becomes the layout
        (status "stopped"). Returns within ``STOP_PATIENCE`` s: a run still in a long setup
        step is let go, and the last good layout stays."""
        if not self._runner.stop(STOP_PATIENCE) or (
                self.status == "running" and not self._runner.running):
            self._on_done(None)

    def wait(self, timeout: float | None = None):
        """Wait for a running layout; re-raises its error. Returns ``placements``."""
        self._runner.wait(timeout)
        return self.placements

    def _cap(self) -> int:
        return max(layer.iterations for layer in self._chart.layers)

    def _job(self, on_frame, cancel):
        started = time.perf_counter()
        on_frame, stop = self._supersedable(on_frame, cancel)   # a newer drag ends it too

        def progress(i, loss, stats):
            self._progress = {"iteration": i, "max_iterations": self._cap(), "loss": loss,
                              "phase": stats["phase"], "seconds": time.perf_counter() - started}
        try:   # every iteration offers its frame: the runner sends at most its fps a second
            return self._chart.layout(on_frame=on_frame, cancel=stop, on_progress=progress,
                                      abort=cancel, fresh=self._fresh, frame_every=1,
                                      warn_bindings=False)   # run() warned
        except Cancelled:   # stopped before its first step: nothing to keep
            return None

    def _on_frame(self, frame: np.ndarray) -> None:
        """Send a frame. One that cannot be sent (a closed comm, a ZMQError) ends the run:
        the layout so far is kept and the error is reported (``_on_done``)."""
        if self._frame_error is not None:
            return
        try:
            with self.hold_sync():
                self.frame = frame.astype(np.float32).tobytes()
                self.frame_count += 1
                self.progress = {**self._progress, "done": False}
        except Exception as exc:
            self._frame_error = exc
            self._runner.stop()   # from the layout thread: only asks the run to end

    def _on_done(self, table) -> None:
        """The run ended: converged, stopped, or cut short by a frame that could not be sent;
        ``table`` None: stopped before its first step, the last good layout is shown again."""
        stopped = table is None or (self._chart.result is not None and self._chart.result.cancelled)
        final = {**self._progress, "done": True, "stopped": stopped}
        if table is not None and self._chart.result is not None:   # the whole run's time
            final["seconds"] = self._chart.result.seconds
        if table is None:
            self._show_kept()
        if self._frame_error is not None:
            exc = self._frame_error
            self._quiet(progress=final)
            self._on_error(exc, source="run", prefix="the layout stopped: a frame could not be sent: ")
            return
        if self._error_from == "run":
            self._error_from = None
            self._quiet(error="")
        self._quiet(progress=final, status="stopped" if stopped else "done")
        self._push_extras(static=not self._dragging)   # a drag's runs: the drop's run draws it

    def _quiet(self, **traits) -> None:
        """Set traits whose sync may fail (a dead comm): the Python side keeps the values."""
        for name, value in traits.items():
            try:
                setattr(self, name, value)
            except Exception:
                if getattr(self, name) != value:   # not even stored: nothing more to do
                    self.set_trait(name, value)

    def _push_extras(self, static: bool = False) -> None:
        """After a design change: the legend, pile labels and axes (of the shown layout,
        none once x= and y= are unbound); after a run (``static``) also the
        notebook's static image (rendering it at every edit would slow big charts down)."""
        self._quiet(legend_image=legend_trait(self._chart), pile_labels=labels_trait(self._chart),
                    axes_image=axes_trait(self._chart))
        if not static:
            return
        try:
            self._static.update()
        except Exception:   # no kernel to publish to: the live view is all there is
            pass

    def _on_run_error(self, exc: BaseException) -> None:
        """A failed run keeps the previous layout: show it again instead of the run's last frame."""
        self._show_kept()
        self._on_error(exc, source="run")

    def _show_kept(self) -> None:
        """Show the chart's layout (none before the first) instead of a run's last frame."""
        result, units = self._chart.result, self._chart._units
        keep = result is not None and units is not None and len(result.center) == len(units.rows)
        frame = (np.column_stack([result.center, result.angle, result.unit_scale])
                 .astype(np.float32).tobytes() if keep else b"")
        self._quiet(frame=frame)

    def _on_error(self, exc: BaseException, source: str = "run", prefix: str = "") -> None:
        """Show an error; it stays until an accepted edit (edit errors), a successful run
        (run errors) or a dismissal (``dismiss_error``, the "dismiss-error" message)."""
        self._error_from = source
        self._quiet(error=f"{prefix}{type(exc).__name__}: {exc}", status="error")
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
        laid_out = self._laid_out is not None and self.placements is not None
        self.stale = laid_out and _layout_key(self.design) != self._laid_out
        self._push_extras()
        self._keep_design()

    def _push_units(self) -> None:
        units = self._chart._units
        if units is None:
            return
        layers = self._chart.layers
        marks, table = unit_marks(units, layers)
        names = [layer.name for layer in layers]
        held = {key for key in self._chart._pins}
        with self.hold_sync():
            self.pinned_units = [k for k, (li, row) in enumerate(zip(units.layer, units.rows))
                                 if (names[li], row) in held]
            self.marks = marks
            self.units = table.tobytes()
            self.colors = rgba(units.colors).tobytes()
            partial = units.clip is not None and (units.clip < 1).any()
            self.clips = units.clip.astype(np.float32).tobytes() if partial else b""
            self.titles = self._chart.titles()

    @t.observe("design")
    def _design_from_front_end(self, change) -> None:
        if self._applying:
            return
        try:
            self._chart.apply_design(change["new"])
            if self._error_from == "edit":   # the design is good again: its error is fixed
                self.error, self._error_from = "", None
        except Exception as exc:  # a bad edit keeps the last good design
            self.error, self._error_from = f"{type(exc).__name__}: {exc}", "edit"
            self._push_design()

    def _on_message(self, _widget, msg, _buffers) -> None:
        kind = msg.get("type") if isinstance(msg, dict) else None
        if kind == "run":
            threading.Thread(target=self._safe(self.run), daemon=True).start()
        elif kind == "stop":
            threading.Thread(target=self._safe(self.stop), daemon=True).start()
        elif kind == "export":
            self._safe(lambda: self._export(msg.get("format")))()
        elif kind == "code":   # the "copy as Python" button: the front end copies it
            self._safe(lambda: self.send({"type": "code", "code": self.to_code()}))()
        elif kind == "icons":
            self._safe(lambda: self._icons(msg.get("query")))()
        elif kind == "dismiss-error":
            self.dismiss_error()
        elif kind in ("drag", "pin"):   # live drag (drag.py): pin, reflow; "pin" is the drop
            self._drag(msg.get("units"), msg.get("x"), msg.get("y"), final=kind == "pin")
        elif kind == "force":   # a point force dragged (drag.py): move it, lay out warm
            self._drag_force(msg.get("layer"), msg.get("index"), msg.get("x"), msg.get("y"),
                             final=bool(msg.get("final")))

    def _safe(self, fn):
        def call():
            try:
                fn()
            except Exception as exc:
                self._on_error(exc)
        return call

    def _icons(self, query) -> None:
        """Reply to the mark panel's icon search with up to 30 closest icon names."""
        query = query if isinstance(query, str) else ""
        self.send({"type": "icons", "query": query, "names": icons.search(query[:100])})

    def _export(self, fmt: str) -> None:
        if self.status == "running":   # refused with a notice: the run and Stop go on
            self.send({"type": "notice", "text": "Export waits for the layout: press it again "
                                                 "when the run has ended (or press Stop first)."})
            return
        if fmt == "png":
            data = "data:image/png;base64," + base64.b64encode(self._chart.to_png(2.0)).decode()
        elif fmt == "svg":
            data = self._chart.to_svg()
        else:
            raise ValueError(f"export format must be 'svg' or 'png', got {fmt!r}")
        self.send({"type": "export", "format": fmt, "data": data})


    # --- the notebook's saved output ------------------------------------------------
    def _repr_mimebundle_(self, **kwargs):
        """The widget view, with a text/plain that says what the chart is."""
        view = super()._repr_mimebundle_(**kwargs)
        data, metadata = view if isinstance(view, tuple) else (view or {}, {})
        return {**data, "text/plain": self._static.view_plain()}, metadata

    def _ipython_display_(self) -> None:
        """The widget view, then its static image (notebook.py), refreshed when a run ends."""
        from IPython.display import display
        data, metadata = self._repr_mimebundle_()
        display(data, raw=True, metadata=metadata)
        self._static.show()


STOP_PATIENCE = 0.25   # s stop() waits for a run to end before letting it go

LAYOUT_FREE = ("title", "caption", "legend", "piles")   # design keys that do not change the layout


def _layout_key(design: dict) -> dict:
    """The part of a design that the layout depends on."""
    return {k: v for k, v in design.items() if k not in LAYOUT_FREE}


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
