"""``pour``: layers held back until the one they block on rests."""
from __future__ import annotations

from dataclasses import dataclass

from .state import Rule


@dataclass(frozen=True)
class PourSettings:
    stage_wait: int = 150          # iterations a stage waits at most for the one before


class Pour(Rule):
    """Each settle window, with layers held back for pouring (a layer that blocks on one
    emitted from the same place): release the next stage that has units once the one before
    rests, or after ``stage_wait`` iterations; its marks start travelling. (A warm start
    keeps only its added units held, so stages between may be empty.)"""

    name = "pour"
    window = True
    reads = ("stage", "poured", "poured_at", "travelling", "iteration")
    writes = ("poured", "poured_at", "travelling", "place")
    Settings = PourSettings

    def applies(self, s):
        return bool(s.stage.max() > 0)

    def __call__(self, s):
        if s.poured < s.stage.max() and (not s.travelling
                                         or s.iteration - s.poured_at >= self.settings.stage_wait):
            s.poured = int(s.stage[s.stage > s.poured].min())
            s.poured_at, s.travelling = s.iteration, True
            s.place.hold(s.stage > s.poured)
            return True
        return False
