"""``legalize``: the end of a polish, or another round of it at a little less scale."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from .resurface import resurface
from .state import Rule, State, unit_overlap
from .uncross import uncross


@dataclass(frozen=True)
class LegalizeSettings:
    final_overlap: float = 0.001   # overlap share a layout must reach (scale shrinks until)
    final_outside: float = 0.001   # outside share a layout must reach (scale shrinks until)
    final_unit_overlap: float = 0.003  # overlap share of its ink no hollow unit may keep (scale shrinks until)
    rounds: int = 10
    rounds_open: int = 20          # when no scale fills a container (forces press open piles)
    shrink: float = 0.005
    gain_unit: float = 0.3         # log-scale shrink per legalising round / the worst hollow unit's share
    shrink_max: float = 0.02       # the most log-scale that shrink may give up per round
    gain_open: float = 2.0         # log-scale shrink per legalising round / overlap, fixed scales
    round_share: int = 3           # a round polishes 1 / round_share of the polish again


def unit_crowding(s: State) -> np.ndarray:
    """``(G,)`` per scale group, the largest share of one hollow unit's ink that the loss
    counts as overlapped: its overlapped footprint alpha over its drawn alpha times its
    ``ink_share``. A contact a fraction of a raster pixel deep is little of all the ink but
    much of a small ring's, and the contract for hollow marks is per unit (solid marks are
    judged in aggregate: 0 where a group has no hollow unit, and nothing is computed)."""
    p, worst = s.p, np.zeros(s.ctl.count)
    hollow = None if p.ink_share is None else np.nonzero(p.ink_share < 1.0)[0]
    if hollow is None or len(hollow) == 0:
        return worst
    n, values = len(p.layer), s.values.detach()
    over = unit_overlap(s).cpu().numpy()
    drawn = torch.zeros(n, dtype=values.dtype, device=values.device).index_add_(0, s.owner, values)
    share = over[hollow] / np.maximum(drawn.cpu().numpy()[hollow] * p.ink_share[hollow], 1e-6)
    np.maximum.at(worst, s.ctl.unit_group[hollow], share)
    return worst


class Legalize(Rule):
    """At the end of a polish: a layout that still overlaps more than ``final_overlap`` or
    pokes out more than ``final_outside``, or one of whose units has more than
    ``final_unit_overlap`` of its ink overlapped (``unit_crowding``), gives up a little scale
    (open scales faster: no room is lost, and forces keep their piles pressed; a crowded
    hollow unit, wedged between neighbours, makes it give up a share of its overlap, up to
    ``shrink_max``), thin marks uncross and buried ones resurface (the moves of the
    ``uncross`` and ``resurface`` rules, with their default settings), and a shorter polish
    runs again, up to ``rounds`` (``rounds_open`` without a controlled scale); otherwise the
    layout is done.
    ``max_iterations`` caps it all. Needed by data-true sizes that never push a mark out,
    open piles, spiky marks, and hollow ones (whose contacts are a large share of their ink)."""

    name = "legalize"
    phase = "polish"
    reads = ("polish_left", "iteration", "overlap_g", "outside_g", "rounds", "values", "index",
             "owner", "ctl")
    writes = ("rounds", "polish_left", "ctl", "place", "optimizer", "done")
    Settings = LegalizeSettings

    def __call__(self, s):
        p, ctl, c = s.p, s.ctl, self.settings
        if not (s.polish_left <= 0 or s.iteration >= p.max_iterations):
            return False
        worst = unit_crowding(s)
        bad = (s.overlap_g > c.final_overlap) | (s.outside_g > c.final_outside) \
            | (worst > c.final_unit_overlap)
        limit = c.rounds if ctl.free.any() else c.rounds_open
        if bad.any() and s.rounds < limit and s.iteration < p.max_iterations:
            s.rounds += 1
            s.polish_left = s.steps.polish_iterations // c.round_share
            uncross(p, ctl, s.place, s.optimizer, s.values, s.index, s.owner)
            resurface(p, s.place, s.optimizer, s.values, s.index, s.owner)
            give = np.where(ctl.free, 1.0, c.gain_open)
            # a wedged hollow unit's contact opens as the scale gives up a share of its size: the
            # shrink follows the worst unit's overlapped share, up to shrink_max
            wedged = np.minimum(c.gain_unit * worst, c.shrink_max)
            ctl.log -= bad * np.maximum(np.maximum(c.shrink, wedged),
                                        give * np.maximum(s.overlap_g, s.outside_g))
            return True
        s.done = True
        return False
