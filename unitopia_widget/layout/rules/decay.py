"""``decay``: the polish's steps shrink to nothing."""
from __future__ import annotations

from dataclasses import dataclass

from .state import Rule


@dataclass(frozen=True)
class DecaySettings:
    floor: int = 1                 # polishing iterations left that the last steps keep at least


class Decay(Rule):
    """Every polish iteration: the steps decay linearly to nothing over the polish
    (``Steps.polish_iterations``), so the last overlaps go without new ones made (every
    design)."""

    name = "decay"
    phase = "polish"
    reads = ("polish_left", "base_lrs")
    writes = ("polish_left", "optimizer")
    Settings = DecaySettings

    def __call__(self, s):
        s.polish_left -= 1
        for g, lr0 in zip(s.optimizer.param_groups, s.base_lrs):
            g["lr"] = lr0 * max(s.polish_left, self.settings.floor) / s.steps.polish_iterations
        return True
