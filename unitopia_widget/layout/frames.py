"""The settling's frames, kept for replay and animation export.

A frame is float32 ``(N, 4)``: x, y (canvas px), angle (degrees), the unit's global
scale (``step.placement.frame``). ``Frames`` keeps at most ``limit`` of a run's frames,
evenly spaced: when full it drops every other one and keeps one in twice as many
from then on. The run's final layout is always the last frame.
"""
from __future__ import annotations

import numpy as np

LIMIT = 200   # frames kept of one run: 1,000 units x 200 frames x 16 B = 3.2 MB


class Frames:
    """Collects a run's frames; ``add`` is an ``on_frame`` callback."""

    def __init__(self, limit: int = LIMIT):
        if limit < 2:
            raise ValueError(f"Frames: limit must be at least 2, got {limit}")
        self.limit, self.kept, self._stride, self._seen = limit, [], 1, 0

    def add(self, frame: np.ndarray) -> None:
        if self._seen % self._stride == 0:
            self.kept.append(np.array(frame, dtype=np.float32, copy=True))
            if len(self.kept) > self.limit:
                self.kept, self._stride = self.kept[::2], self._stride * 2
        self._seen += 1

    def finish(self, final: np.ndarray) -> np.ndarray:
        """``(F, N, 4)`` the kept frames, ending on ``final`` (the layout)."""
        final = np.asarray(final, dtype=np.float32)
        kept = [f for f in self.kept if f.shape == final.shape]
        if len(kept) >= self.limit:
            kept = kept[:self.limit - 1]
        return np.stack(kept + [final])
