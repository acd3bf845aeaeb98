"""``start-polish``: the end of the settle phase."""
from __future__ import annotations

from dataclasses import dataclass

from .measure_room import jammed
from .state import Rule


@dataclass(frozen=True)
class StartPolishSettings:
    polish_shrink: float = 0.008   # log-scale the controlled scales give up as the polish starts
    reserve: int = 10              # a polish more is kept for legalising: 1 / reserve of the cap
    jammed: float = 0.005          # overlap or outside share of a group with room that keeps it settling


class StartPolish(Rule):
    """End the settle phase when the loss stopped improving for ``patience`` iterations and
    the marks rest (under forces: no mark travelled ``settle_motion`` mean radii in both of
    the last two windows, ``State.calm``; a pile's noisy loss can stall while its last marks
    still fall), or when only the polishing iterations are left: controlled scales shrink by
    ``polish_shrink`` and freeze. Every design ends its settle here."""

    name = "start-polish"
    reads = ("since_best", "travelling", "straggling", "calm", "force_layers", "iteration", "room",
             "overlap_g", "outside_g")
    writes = ("phase", "ctl")
    Settings = StartPolishSettings

    def __call__(self, s):
        p, steps = s.p, s.steps
        # a closed container with room whose marks still overlap or poke out is not settled:
        # the fill controller is still trading scale for crowding
        stuck = bool(jammed(s, self.settings.jammed).any())
        if (s.since_best >= steps.patience and not s.travelling and not s.straggling
                and (s.calm or not s.force_layers) and not stuck) \
                or s.iteration >= p.max_iterations - steps.polish_iterations \
                - min(steps.polish_iterations, p.max_iterations // self.settings.reserve):
            s.phase = "polish"
            s.ctl.log -= self.settings.polish_shrink * s.ctl.free
            return True
        return False
