"""``step-size``: big translation steps while marks travel, small ones once they press."""
from __future__ import annotations

from dataclasses import dataclass

from .state import Rule


@dataclass(frozen=True)
class StepSizeSettings:
    overlap_target: float = 0.002  # raster overlap share above which steps shrink
    lr_travel: float = 0.3         # the step while nothing overlaps (marks travelling), mean radii
    slower: float = 0.7            # gain factor per crowded iteration
    faster_travel: float = 1.1     # gain factor per free iteration, marks travelling
    faster: float = 1.05           # gain factor per free iteration, marks at rest
    worse: float = 1.001           # while travelling, crowding must grow by this factor to slow


class StepSize(Rule):
    """Every settle iteration: big translation steps while marks travel freely, small ones
    once they press on each other; while marks travel only crowding that gets worse slows
    them (an emitter's first pile-up resolving is no reason to slow down). Needed by
    emitters: marks that start far from where they rest."""

    name = "step-size"
    reads = ("stats", "travelling", "last_overlap", "gain", "base_lrs", "optimizer")
    writes = ("last_overlap", "gain", "optimizer")
    Settings = StepSizeSettings

    def __call__(self, s):
        c, overlap = self.settings, s.stats["overlap"]
        crowded = overlap > c.overlap_target and (not s.travelling or overlap > s.last_overlap * c.worse)
        s.last_overlap = overlap
        gain_max = c.lr_travel / s.steps.lr
        s.gain = max(1.0, s.gain * c.slower) if crowded else \
            min(gain_max, s.gain * (c.faster_travel if s.travelling else c.faster))
        s.optimizer.param_groups[0]["lr"] = s.base_lrs[0] * s.gain
        return True
