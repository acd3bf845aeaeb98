"""The schedule: named rules run on the solver's shared ``State`` after every step.

A layout has two phases of iterations, *settle* (forces pull, the fill controller moves the
scales, the marks come to rest) and *polish* (scales frozen, steps decaying, legalising
rounds), and a *finish* run once after the last iteration. Each rule belongs to one phase;
*window* rules run once every ``Steps.patience`` iterations. ``SCHEDULE`` lists them in the
order they run, one module each (its settings, its moves, the ``State`` fields it reads and
writes); a new rule is a new module and one line here. ``run`` applies the rules of the
current phase and counts, per rule, the iterations on which it acted (``State.record``).
Order matters: ``fill-scale`` reads the room ``measure-room`` measured a window before, and
``relocate`` the ink raster it copied this window.
"""
from __future__ import annotations

from .best_loss import BestLoss
from .contacts import Contacts
from .decay import Decay
from .drop import Drop
from .exchange import Exchange
from .fill_scale import FillScale
from .legalize import Legalize
from .measure_room import MeasureRoom
from .pour import Pour
from .relocate import Relocate
from .resurface import Resurface
from .rest import Rest
from .start_polish import StartPolish
from .state import Rule, State, Steps
from .step_size import StepSize
from .strays import Strays
from .uncross import Uncross

PHASES = ("settle", "polish", "finish")
STEPS = Steps()

SCHEDULE = (
    BestLoss(),      # settle, every iteration: the best loss and the iterations since it
    StepSize(),      # settle, every iteration: big steps while marks travel, small once they press
    FillScale(),     # settle, every iteration: controlled scales grow into room, give way to crowding
    MeasureRoom(),   # settle, each window: which closed containers still have room
    Relocate(),      # settle, each window: jammed marks jump into holes
    Exchange(),      # settle, each window: poked-out thin marks trade places with shorter ones
    Uncross(),       # settle, each window: crossing thin marks turn side by side
    Resurface(),     # settle, each window: buried marks lifted back onto their stratum
    Rest(),          # settle, each window (paths every iteration): marks at rest, none falling; the pull weakens
    Pour(),          # settle, each window: the next held-back stage released
    StartPolish(),   # settle, every iteration: the settle ends, scales shrink and freeze
    Decay(),         # polish, every iteration: the steps decay to nothing
    Legalize(),      # polish, every iteration: the layout is done, or gives up scale and polishes again
    Strays(),        # finish, once: marks that ended outside their container brought back in
    Drop(),          # finish, once: open piles under a directional pull fall until their ink meets
    Contacts(),      # finish, once: hollow marks moved off contacts finer than the raster
)

__all__ = ["PHASES", "SCHEDULE", "STEPS", "Rule", "State", "Steps", "run", "start"]


def start(s: State, schedule=SCHEDULE) -> None:
    """Let every rule see the state the first iteration starts from."""
    for rule in schedule:
        rule.start(s)


def run(s: State, schedule=SCHEDULE) -> None:
    """One iteration of the schedule (or the finish): the rules of the phase the iteration
    began in, in order; counts the iteration for its phase and for each rule that acted."""
    phase = s.phase
    s.record[phase] = s.record.get(phase, 0) + 1
    for rule in schedule:
        if rule.phase == phase and (not rule.window or s.iteration % s.steps.patience == 0) and rule(s):
            key = f"{phase}.{rule.name}"
            s.record[key] = s.record.get(key, 0) + 1
