"""``best-loss``: the settle's reference for patience."""
from __future__ import annotations

import math
from dataclasses import dataclass

from .state import Rule


@dataclass(frozen=True)
class BestLossSettings:
    improve: float = 1e-3    # a loss better than the best by this share of its size improves
    floor: float = 1e-6      # ... and by this much more (a best near 0)
    pile: float = 0.5        # a rise by this share of the best while marks travel: a new best


class BestLoss(Rule):
    """Every settle iteration: track the best loss and the iterations since it. A loss that
    rises while marks travel (they pile up: emitters, pouring) becomes the new best, since
    the best from before they met is no reference for whether the pile has settled.
    Needed by emitted and poured designs."""

    name = "best-loss"
    reads = ("loss_value", "travelling")
    writes = ("best", "since_best")
    Settings = BestLossSettings

    def __call__(self, s):
        c = self.settings
        # tolerances relative to the loss's magnitude: with forces the loss is negative
        # (their potential), and a share of it must not turn a rise into an improvement
        first = not math.isfinite(s.best)
        improved = first or s.loss_value < s.best - c.improve * abs(s.best) - c.floor
        piled = not first and s.travelling and s.loss_value > s.best + c.pile * abs(s.best)
        if improved or piled:
            s.best, s.since_best = s.loss_value, 0
        else:
            s.since_best += 1
        return True
