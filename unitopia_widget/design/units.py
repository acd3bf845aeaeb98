"""``Units``: what the encodings make of a design's rows, one unit (a mark) per row, per
unit of a ``count=`` column, or per ``per=`` units, the layers concatenated in drawing
order (``layout.prepare.bind`` makes them)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Units:
    """Per-unit arrays, ``(N,)`` unless noted, layers concatenated in drawing order."""

    rows: list               # index label of each unit's row (a per= mark: its first row)
    layer: np.ndarray        # layer index
    half_w: np.ndarray       # half box width at scale 1, canvas px
    half_h: np.ndarray       # half box height at scale 1
    area: np.ndarray         # silhouette area at scale 1, canvas px^2
    margin: np.ndarray       # margin fraction
    order: np.ndarray        # emission rank within the layer
    colors: list             # CSS hex colour per unit
    mark: np.ndarray         # index of the unit's mark within its layer's marks
    sprite: np.ndarray       # index of the unit's mark in ``sprites``
    sprites: list            # the distinct footprint Marks (Mark.as_footprint), one sprite pyramid each
    #: position channels (design/positions.py): (N, 2) place along x, y as a fraction of the
    #: container's extent, NaN where unbound; the half band width, same shape; per layer
    #: {"x": Scale, "y": Scale} of its bound channels
    position: np.ndarray | None = None
    band: np.ndarray | None = None
    position_scales: list | None = None
    #: one mark for k units (layout/prepare/tally.py): the units each mark stands for, the
    #: drawn share of its ink and of its box width (1, or a partial mark's), and the rows it
    #: covers: covered[cover_start[i]:cover_stop[i]], index labels
    amount: np.ndarray | None = None
    fraction: np.ndarray | None = None
    clip: np.ndarray | None = None
    covered: np.ndarray | None = None
    cover_start: np.ndarray | None = None
    cover_stop: np.ndarray | None = None

    def rows_of(self, indices) -> list:
        """The index labels of the rows units ``indices`` cover, each once, in order."""
        if self.covered is None:
            return list(dict.fromkeys(self.rows[i] for i in indices))
        parts = [self.covered[self.cover_start[i]:self.cover_stop[i]] for i in indices]
        return list(dict.fromkeys(label for part in parts for label in part.tolist()))

    @property
    def fill_fraction(self) -> np.ndarray:
        """``(N,)`` silhouette area / box area of each unit's mark."""
        return np.array([m.fill_fraction for m in self.sprites])[self.sprite]

    @property
    def ink_share(self) -> np.ndarray:
        """``(N,)`` ink area / footprint area of each unit's mark: 1 but for a mark whose
        footprint fills the holes its ink encloses (a ring: its ink over its filled disc)."""
        return np.array([min(m.as_footprint("ink").fill_fraction / m.fill_fraction, 1.0)
                         if m.solid else 1.0 for m in self.sprites])[self.sprite]

    @property
    def box_size(self) -> np.ndarray:
        """``(N, 2)`` box (w, h) of each unit's mark, in the mark's own units."""
        return np.array([m.box_size for m in self.sprites]).reshape(-1, 2)[self.sprite]
