"""Pins from the widget: ``pin``/``unpin``/``pinned`` (``Chart``'s, see ``hand.py``) and
the front end's drop of dragged marks (the "pin" message, docs/protocol.md)."""
from __future__ import annotations

import numpy as np
import pandas as pd


class Pinning:
    """``UnitoPia``'s pins; needs ``_chart`` and the ``frame`` trait."""

    def pin(self, rows, x=None, y=None, angle=None) -> None:
        """Hold ``rows`` where they are (or at ``x, y`` px, ``angle`` degrees); see ``Chart.pin``."""
        self._chart.pin(rows, x=x, y=y, angle=angle)

    def unpin(self, rows=None) -> None:
        """Release the pins of ``rows`` (None: all)."""
        self._chart.unpin(rows)

    @property
    def pinned(self) -> pd.DataFrame:
        """The pins: layer, row, x, y, angle."""
        return self._chart.pinned

    def _pin_units(self, index, x, y) -> None:
        """The front end dropped units ``index`` (into the shown layout) at ``x, y`` px: pin them
        there (``pinned`` and ``pinned_units`` follow)."""
        shown = self._chart._snapshot
        count = 0 if shown is None else len(shown)
        if not (isinstance(index, list) and isinstance(x, list) and isinstance(y, list)
                and len(index) == len(x) == len(y)
                and all(isinstance(i, int) and 0 <= i < count for i in index)):
            raise ValueError(f"pin message: units, x and y must be lists of equal length with "
                             f"unit indices under {count} (the units laid out), got {index!r:.60}")
        self._chart.pin_units([(shown["layer"].iloc[i], shown["row"].iloc[i]) for i in index], x, y)
        frame = np.frombuffer(self.frame, dtype=np.float32).reshape(-1, 4).copy()
        if len(frame) == count:   # the dropped marks are shown where they are pinned
            frame[index, 0], frame[index, 1] = x, y
            self.frame = frame.tobytes()
