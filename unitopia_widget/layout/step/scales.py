"""The controlled global scales of a layout, one per scale group (the rules ``fill-scale``,
``start-polish`` and ``legalize`` move them; ``measure-room`` says where there is room)."""
from __future__ import annotations

import numpy as np


class Scales:
    """The controlled global scales: one per scale group, as logs ``(G,)``, of the solver's
    ``Problem`` ``p``."""

    def __init__(self, p):
        n_layers = p.terms.penalty.shape[0]
        self.group = np.zeros(n_layers, int) if p.scale_group is None else np.asarray(p.scale_group)
        self.count = int(self.group.max()) + 1
        start = [p.scale] if p.group_scale is None else p.group_scale
        self.log = np.log(np.asarray(start, dtype=float))
        self.free = np.asarray([p.free_scale] if p.group_free is None else p.group_free, bool)
        self.unit_group = self.group[p.layer]
        #: (G,) the median margin of each group's units (0 for a group without units)
        self.margin = group_median(p.margin, self.unit_group, self.count)
        #: (G,) groups whose units' median margin is 0: the overlap the loss reads is their ink's
        self.bare = self.margin == 0.0

    def unit_scale(self) -> np.ndarray:
        """``(N,)`` each unit's current scale."""
        return np.exp(self.log)[self.unit_group]

    def crowding(self, sums: np.ndarray):
        """Overlap and outside shares ``(G,)`` from the loss's per-layer sums ``(3, L)``."""
        per = np.zeros((3, self.count))
        np.add.at(per.T, self.group, sums.T)
        drawn = np.maximum(per[2], 1e-6)
        return per[0] / drawn, per[1] / drawn


def group_median(values: np.ndarray, unit_group: np.ndarray, count: int) -> np.ndarray:
    """``(G,)`` the median of ``values (N,)`` over each group's units (``unit_group (N,)``),
    0 for a group without units."""
    return np.array([np.median(values[unit_group == g]) if (unit_group == g).any() else 0.0
                     for g in range(count)])
