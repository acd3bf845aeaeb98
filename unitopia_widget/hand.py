"""Hand control of a chart: pins, replacing the data, and the warm start between runs.

``Chart`` takes these methods (and the widget forwards them). A run after a change
starts from the last layout (``layout.prepare.warm``); a run with nothing changed since the last
one would start from where that one started and give the same placements, so it returns the
last layout at once (``_unchanged``): nothing it depends on (the design with its pins, seed,
canvas and scales, the rows, the device, the start) differs.
"""
from __future__ import annotations

import json
import warnings

import pandas as pd

from .design.encodings import tooltip_fields
from .design.pins import Pin, check_pin, json_label, pin_values, row_labels
from .design.validate import check_finite
from .layout.prepare.warm import snapshot


class HandControl:
    """Pins and data replacement; mixed into ``Chart`` (which provides ``df``, ``layers``,
    ``canvas``, ``device``, ``laid``, ``_units``, ``bind_check`` and ``_changed``)."""

    _pins: dict = {}
    _snapshot = None   # the last run's layout (warm.snapshot), or None
    _origin = None     # the snapshot the last run started from (None: fresh)
    _ran = None        # (design JSON text, DataFrame, device) of the last run

    # --- pins -----------------------------------------------------------------
    def pin(self, rows, x=None, y=None, angle=None) -> None:
        """Hold ``rows`` (index labels, or a DataFrame such as ``selected``) at canvas ``x, y``
        px and ``angle`` degrees: one number each, or one per row; None keeps where the row
        is in the last layout. Every layer drawing a row pins it. A pinned mark is an
        obstacle for every layer in its container and keeps its place in later runs."""
        labels = row_labels(rows)
        values = [pin_values(n, v, len(labels)) for n, v in (("x", x), ("y", y), ("angle", angle))]
        names = [layer.name for layer in self.layers]
        drawn = {}
        for li, row in zip(self._units.layer, self._units.rows):
            drawn.setdefault(row, []).append(names[li])
        keys, where = [], []
        for label, *at in zip(labels, *values):
            if label not in drawn:
                raise KeyError(f"pin: row {label!r:.40} is not drawn by any layer")
            keys += [(name, label) for name in drawn[label]]
            where += [at] * len(drawn[label])
        self.pin_units(keys, *(list(v) for v in zip(*where)))

    def pin_units(self, keys, x, y, angle=None) -> None:
        """Pin the units ``keys`` (``(layer name, row)`` pairs) at ``x, y`` and ``angle``
        (lists, one per key; None entries, or None: where the unit is in the last layout)."""
        angle = [None] * len(keys) if angle is None else angle
        last = {} if self._snapshot is None else {
            (r.layer, r.row): r for r in self._snapshot.itertuples(index=False)}
        new = {}
        for (name, label), px, py, pa in zip(keys, x, y, angle):
            now = last.get((name, label))
            if now is None and (px is None or py is None):
                raise RuntimeError(f"pin: row {label!r:.40} has no place yet: run the layout "
                                   f"first, or give x= and y=")
            pin = Pin(name, json_label(label),
                      *(check_finite("pin", n, v) for n, v in (
                          ("x", now.x if px is None else px), ("y", now.y if py is None else py),
                          ("angle", (now.angle if now is not None else 0.0) if pa is None else pa))))
            check_pin(pin, self.layer(name), self.canvas)
            new[pin.key] = pin
        self._pins = {**self._pins, **new}
        self._changed()

    def unpin(self, rows=None) -> None:
        """Release the pins of ``rows`` (index labels or a DataFrame; None: every pin)."""
        if rows is None:
            self._pins = {}
        else:
            labels = {json_label(r) for r in row_labels(rows)}
            self._pins = {k: v for k, v in self._pins.items() if k[1] not in labels}
        self._changed()

    @property
    def pinned(self) -> pd.DataFrame:
        """The pins: one row per pinned unit (layer, row, x, y, angle)."""
        return pd.DataFrame([(p.layer, p.row, p.x, p.y, p.angle) for p in self._pins.values()],
                            columns=["layer", "row", "x", "y", "angle"])

    def _pins_json(self) -> dict:
        """The design's ``"pins"`` field, present only when some row is pinned."""
        return {"pins": [p.to_json() for p in self._pins.values()]} if self._pins else {}

    def _read_pins(self, d: dict, layers, units, canvas) -> dict:
        """The pins of design ``d`` for ``layers`` and their ``units``; a ValueError for a pin
        on an unknown layer or row, or outside its container."""
        raw = d.get("pins", [])
        if not isinstance(raw, list):
            raise ValueError(f"design: \"pins\" must be a list, got {type(raw).__name__}")
        names = [layer.name for layer in layers]
        drawn = set(zip((names[li] for li in units.layer), units.rows))
        pins = {}
        for x in raw:
            pin = Pin.from_json(x)
            if pin.layer not in names:
                raise ValueError(f"design: a pin names layer {pin.layer!r:.60}, which the design "
                                 f"does not have; layers: {names}")
            if pin.key not in drawn:
                raise ValueError(f"design: the pin of row {pin.row!r:.40} names a row that layer "
                                 f"{pin.layer!r:.60} does not draw")
            check_pin(pin, layers[names.index(pin.layer)], canvas)
            pins[pin.key] = pin
        return pins

    def _check_pins(self) -> None:
        """Every pin inside its layer's container (the design may have changed since)."""
        names = [layer.name for layer in self.layers]
        for pin in self._pins.values():
            if pin.layer in names:
                check_pin(pin, self.layer(pin.layer), self.canvas)

    # --- data -----------------------------------------------------------------
    def set_data(self, df: pd.DataFrame) -> None:
        """Replace the rows by ``df``'s, matched by index: the next run keeps the marks of
        rows still there where they were, adds the new ones, drops the gone ones (and
        their pins). Layers keep their row selections (``by=`` layers select by value)."""
        if not isinstance(df, pd.DataFrame):
            raise TypeError(f"set_data: df must be a pandas DataFrame, got {type(df).__name__}")
        if len(df) == 0:
            raise ValueError("set_data: df is empty: a unit chart needs at least one row")
        if not df.index.is_unique:
            raise ValueError("set_data: df has duplicate index labels; call "
                             "df.reset_index(drop=True) first")
        tooltip_fields(df, self._tooltip)
        old = self.df
        self.df = df
        try:
            self.bind_check()
        except Exception:
            self.df = old
            self.bind_check()
            raise
        names = [layer.name for layer in self.layers]
        drawn = set(zip((names[li] for li in self._units.layer), self._units.rows))
        gone = [k for k in self._pins if k not in drawn]
        if gone:
            warnings.warn(f"set_data: {len(gone)} pinned row(s) are gone and unpinned (first: "
                          f"{gone[0][1]!r:.40})", stacklevel=2)
            self._pins = {k: v for k, v in self._pins.items() if k in drawn}
        self._changed()

    # --- warm starts -------------------------------------------------------------
    def _start_from(self, fresh: bool):
        """``(snapshot to start from or None, this run's inputs)``."""
        inputs = (json.dumps(self.design(), sort_keys=True, default=str), self.df, self.device)
        if fresh or self._snapshot is None:
            return None, inputs
        return (self._origin if self._same_inputs(inputs) else self._snapshot), inputs

    def start_from_last(self) -> None:
        """Let the next run start from the last layout even when that run was stopped and
        nothing changed since (a run again then starts over from that run's start): a live
        drag's reflow cut short by the next position leaves the marks where the user sees them
        (``jupyter/drag.py``)."""
        self._origin = self._snapshot

    def _same_inputs(self, inputs) -> bool:
        """Whether ``inputs`` (``_start_from``'s) are the last run's: the same design text,
        equal rows (values, dtypes, index and columns) and the same device."""
        ran = self._ran
        return (ran is not None and ran[0] == inputs[0] and ran[2] == inputs[2]
                and ran[1].equals(inputs[1]))

    def _unchanged(self, origin, inputs) -> bool:
        """Whether a run from ``origin`` with ``inputs`` (``_start_from``'s) would repeat the
        last one exactly: that run completed (not cancelled), started from ``origin`` itself
        and had the same inputs; its layout is then this run's."""
        return (self.laid is not None and not self.laid.result.cancelled and origin is self._origin
                and self._same_inputs(inputs))

    def _reusable(self, origin, inputs):
        """The last run's ``Layout.problem`` when this run starts warm from its layout and
        only the pins, the rows, the margins or point forces' places changed since (the design
        otherwise equal, the same device, the same marks in the same order): a reflow reuses
        it (its raster, fields and sprites depend on none of these; ``layout.reflow``); else
        None."""
        ran = self._ran
        if origin is None or origin is not self._snapshot or self.laid is None \
                or ran is None or ran[2] != inputs[2]:
            return None
        same_marks = list(self._units.sprites) == list(self.laid.units.sprites)   # its pyramids
        same_design = _reflowable(ran[0]) == _reflowable(inputs[0])
        return self.laid.problem if same_marks and same_design else None

    def _settled(self) -> bool:
        """Whether the last run's layout is one a reflow may start from: not a full run cut
        short after its first steps (a Stop, a newer drag message), whose marks are still on
        their way. (A full run a drag message cut before its first step, as one where the
        reflow gave up, left its start: the last layout, with the pins moved.)"""
        result = None if self.laid is None else self.laid.result
        return result is None or not result.cancelled or "reflow" in result.phases \
            or result.iterations == 0

    def _remember_run(self, origin, inputs, units, result) -> None:
        self._origin, self._ran = origin, (inputs[0], inputs[1].copy(), inputs[2])
        self._snapshot = snapshot(units, self.layers, result)


def _reflowable(text: str) -> dict:
    """The design JSON ``text`` without what a run may answer from the last run's problem:
    its pins, margins and point forces' places (``layout.engine.layout``'s ``reuse``)."""
    design = json.loads(text)
    design.pop("pins", None)
    for layer in design.get("layers", []):
        layer.get("encodings", {}).pop("margin", None)
        for force in layer.get("forces", []):
            if force.get("kind") == "point":
                force.pop("x", None)
                force.pop("y", None)
    return design
