"""The solver's schedule as data: named rules, each run on a shared ``State`` every iteration.

The layout has two phases: *settle* (forces pull, the fill controller moves the scales, the
marks come to rest) and *polish* (scales frozen, steps decaying, legalising rounds). Each
rule belongs to one phase; *window* rules run once every ``patience`` iterations. ``SCHEDULE``
lists them in the order they run; ``run`` applies those of the current phase and counts, per
rule, the iterations on which it acted (``State.record``). ``p`` is the solver's ``Problem``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import torch

from .moves import relocate, rescale_moments, resurface, uncross
from ..step.optim import Adam
from ..step.placement import Placement
from ..step.scales import Scales, coverage


@dataclass
class State:
    """What the rules share: the problem ``p``, the scales, the placement and its optimizer,
    the schedule's counters, and this iteration's readback (``values``, ``index``, ``owner``:
    the rendered samples; ``overlap_g``, ``outside_g``: shares ``(G,)`` per scale group)."""

    p: object                      # the solver's Problem
    ctl: Scales
    place: Placement
    optimizer: Adam
    radius: float                  # mean mark radius at the start, canvas px
    force_layers: list             # (unit indices, forces) of the layers with forces
    stage: np.ndarray              # (N,) pouring stage per unit
    window_start: torch.Tensor     # (N, 2) centres at the start of the window
    travelling: bool               # marks still travel (a strong pull, big steps)
    base_lrs: list = field(default_factory=list)
    phase: str = "settle"
    iteration: int = 0
    best: float = math.inf         # best settle loss, the reference for patience
    since_best: int = 0
    polish_left: int = 0
    gain: float = 1.0              # settle step gain over the base translation step
    rounds: int = 0                # legalising rounds so far
    last_overlap: float = math.inf
    straggling: bool = False       # a tenth of the marks still travel, though most rest
    calm: bool = False             # no mark travelled settle_motion mean radii two windows running
    moving: torch.Tensor | None = None   # (N,) bool, marks that travelled that far last window
    poured: int = 0                # the last stage poured
    poured_at: int = 0
    room: np.ndarray | None = None   # (G,) bool, groups whose closed containers have room
    cover: np.ndarray | None = None  # (H, W) ink raster of the window (where room is measured)
    done: bool = False
    loss_value: float = math.inf
    stats: dict = field(default_factory=dict)
    overlap_g: np.ndarray | None = None
    outside_g: np.ndarray | None = None
    values: torch.Tensor | None = None
    index: torch.Tensor | None = None
    owner: torch.Tensor | None = None
    record: dict = field(default_factory=dict)   # "phase", "phase.rule" -> iterations acted on

    def settle_more(self) -> None:
        """Marks were moved by hand: settle a little longer before polishing."""
        self.since_best = min(self.since_best, self.p.patience // 2)


class Rule:
    """A named step of the schedule; ``__call__(state)`` returns whether it acted."""

    name = ""
    phase = "settle"
    window = False   # runs once every ``patience`` iterations only


class BestLoss(Rule):
    """Every settle iteration: track the best loss and the iterations since it. A loss that
    rises while marks travel (they pile up: emitters, pouring) becomes the new best, since
    the best from before they met is no reference for whether the pile has settled.
    Needed by emitted and poured designs."""

    name = "best-loss"

    def __call__(self, s):
        # tolerances relative to the loss's magnitude: with forces the loss is negative
        # (their potential), and a share of it must not turn a rise into an improvement
        first = not math.isfinite(s.best)
        improved = first or s.loss_value < s.best - 1e-3 * abs(s.best) - 1e-6
        piled = not first and s.travelling and s.loss_value > s.best + 0.5 * abs(s.best)
        if improved or piled:
            s.best, s.since_best = s.loss_value, 0
        else:
            s.since_best += 1
        return True


class StepSize(Rule):
    """Every settle iteration: big translation steps while marks travel freely, small ones
    once they press on each other; while marks travel only crowding that gets worse slows
    them (an emitter's first pile-up resolving is no reason to slow down). Needed by
    emitters: marks that start far from where they rest."""

    name = "step-size"

    def __call__(self, s):
        p, overlap = s.p, s.stats["overlap"]
        crowded = overlap > p.overlap_target and (not s.travelling or overlap > s.last_overlap * 1.001)
        s.last_overlap = overlap
        gain_max = p.lr_travel / p.lr
        s.gain = max(1.0, s.gain * 0.7) if crowded else min(gain_max, s.gain * (1.1 if s.travelling else 1.05))
        s.optimizer.param_groups[0]["lr"] = s.base_lrs[0] * s.gain
        return True


class FillScale(Rule):
    """Every settle iteration, controlled scales (closed layers filling their containers):
    grow while the measured overlap stays below ``grow_overlap / 2``, or while the container
    has room (even as jammed marks keep some overlap, and while footprints poke out a
    little); give way above it once marks rest, or as they leave the container. Poking out is
    worse than touching: room never grows a scale past a mark outside. Needed by closed
    boundaries (the scale is controlled, not learned: a gradient balance between fill and
    overlap settles at a few percent of overlap with spiky marks). Acts when a scale moved."""

    name = "fill-scale"

    def __call__(self, s):
        p, ctl = s.p, s.ctl
        crowd = np.maximum(s.overlap_g, s.outside_g)
        grow = ctl.free & ((crowd < 0.5 * p.grow_overlap) | (
            s.room & (s.overlap_g < 1.5 * p.grow_overlap) & (s.outside_g < ctl.grow_outside)))
        shrink = ctl.free & ((crowd > 1.5 * p.grow_overlap) | (s.outside_g > p.grow_overlap)) \
            & (not s.travelling)
        ctl.log += p.scale_step * (grow.astype(float) - shrink.astype(float))
        if grow.any():
            s.since_best = 0
        return bool(grow.any() or shrink.any())


class MeasureRoom(Rule):
    """Each settle window, where some scale fills closed containers: copy the ink raster to
    the host once and measure which groups' containers still have room (``room.py``), for
    the fill controller and relocation. Needed by containers that stay part empty while
    spiky or heavy-tailed marks jam."""

    name = "measure-room"
    window = True

    def __call__(self, s):
        s.cover = coverage(s.p, s.values.detach(), s.index) if s.ctl.measures_room else None
        s.room = s.ctl.room(s.cover)
        return s.cover is not None


class Relocate(Rule):
    """Each settle window in the first quarter of the iterations: in groups with room whose
    overlap still keeps the scale from growing (jammed), move the most overlapped free marks
    into the container's holes (``relocate.py``). Needed by necked and holed containers
    where a pile jams on one side while the other stays empty."""

    name = "relocate"
    window = True

    def __call__(self, s):
        p = s.p
        jammed = s.room & (s.overlap_g > 0.5 * p.grow_overlap)
        if jammed.any() and s.iteration < p.max_iterations // 4 and \
                relocate(p, s.ctl, s.place, s.optimizer, jammed, s.cover, s.values.detach(),
                         s.index, s.owner):
            s.settle_more()
            return True
        return False


class Uncross(Rule):
    """Each settle window (and each legalising round): thin marks whose ink crosses turn
    side by side (``uncross.py``); no gradient undoes a crossing. Needed by hair, strands
    and rotating rectangles."""

    name = "uncross"
    window = True

    def __call__(self, s):
        if uncross(s.p, s.ctl, s.place, s.optimizer, s.values, s.index, s.owner):
            s.settle_more()
            return True
        return False


class Resurface(Rule):
    """Each settle window (and each legalising round), on stacks: free marks buried in
    their stratum's obstacle (a large mark of a lower layer rolled over them) are lifted
    back onto its surface (``surface.py``); the flat obstacle gives them no gradient out.
    The settle then starts its patience afresh: the lifted marks have their own layer and
    those above to part. Needed by stacks whose layers differ in size."""

    name = "resurface"
    window = True

    def __call__(self, s):
        if resurface(s.p, s.place, s.optimizer, s.values, s.index, s.owner):
            s.best, s.since_best = math.inf, 0
            return True
        return False


class Rest(Rule):
    """Each settle window, on layouts with forces: marks rest when the mean travel of the
    stage being poured over the window is under ``settle_motion`` mean radii (a tenth still
    travelling, or one mark still falling that far, keeps the settle going: a mark falls when
    it travels that far in two windows running, as the jitter of a large pile does not). On
    coming to rest the pull weakens, so the best loss is reset and Adam's moments are scaled
    with the force (marks still in the air keep falling at pace). Needed by emitters and
    pouring. Acts when the marks come to rest."""

    name = "rest"
    window = True

    def __call__(self, s):
        p = s.p
        with torch.no_grad():
            now = s.place.transforms()[0].detach().clone()
        pouring = torch.as_tensor(s.stage == s.poured, device=now.device)
        distance = (now - s.window_start).norm(dim=1)
        travel = distance[pouring]
        bar = p.settle_motion * s.radius
        moved = float(travel.mean())
        s.straggling = bool(s.force_layers) and float(torch.quantile(travel, 0.9)) > bar
        moving = pouring & (distance > bar)
        s.calm = s.moving is not None and not bool((moving & s.moving).any())
        s.moving = moving
        came_to_rest = s.travelling and moved <= bar and bool(s.force_layers)
        if came_to_rest:
            s.best, s.since_best = math.inf, 0
            rescale_moments(s.optimizer, s.place.t, p.force_weight / p.force_travel)
        s.travelling = moved > bar
        s.window_start = now
        return came_to_rest


class Pour(Rule):
    """Each settle window, with layers held back for pouring (a layer that blocks on one
    emitted from the same place): release the next stage once the one before rests, or after
    ``stage_wait`` iterations; its marks start travelling."""

    name = "pour"
    window = True

    def __call__(self, s):
        p = s.p
        if s.poured < s.stage.max() and (not s.travelling or s.iteration - s.poured_at >= p.stage_wait):
            s.poured, s.poured_at, s.travelling = s.poured + 1, s.iteration, True
            s.place.hold(s.stage > s.poured)
            return True
        return False


class StartPolish(Rule):
    """End the settle phase when the loss stopped improving for ``patience`` iterations and
    the marks rest (under forces: no mark travelled ``settle_motion`` mean radii in both of
    the last two windows, ``State.calm``; a pile's noisy loss can stall while its last marks
    still fall), or when only the polishing iterations are left: controlled scales shrink by
    ``polish_shrink`` and freeze. Every design ends its settle here."""

    name = "start-polish"

    def __call__(self, s):
        p = s.p
        if (s.since_best >= p.patience and not s.travelling and not s.straggling
                and (s.calm or not s.force_layers)) \
                or s.iteration >= p.max_iterations - p.polish_iterations \
                - min(p.polish_iterations, p.max_iterations // 10):
            s.phase = "polish"
            s.ctl.log -= p.polish_shrink * s.ctl.free
            return True
        return False


class Decay(Rule):
    """Every polish iteration: the steps decay linearly to nothing over the polish, so the
    last overlaps go without new ones made (every design)."""

    name = "decay"
    phase = "polish"

    def __call__(self, s):
        p = s.p
        s.polish_left -= 1
        for g, lr0 in zip(s.optimizer.param_groups, s.base_lrs):
            g["lr"] = lr0 * max(s.polish_left, 1) / p.polish_iterations
        return True


class Legalize(Rule):
    """At the end of a polish: a layout that still overlaps more than ``final_overlap`` or
    pokes out more than ``final_outside``, or one of whose units has more than
    ``final_unit_overlap`` of its ink overlapped (``unit_crowding``), gives up a little scale
    (open scales faster: no room is lost, and forces keep their piles pressed; a crowded
    hollow unit, wedged between neighbours, makes it give up a share of its overlap, up to
    ``legalize_shrink_max``), thin marks uncross, and a shorter polish runs again, up to
    ``legalize_rounds`` (``legalize_rounds_open`` without a controlled scale); otherwise the
    layout is done.
    ``max_iterations`` caps it all. Needed by data-true sizes that never push a mark out,
    open piles, spiky marks, and hollow ones (whose contacts are a large share of their ink)."""

    name = "legalize"
    phase = "polish"

    def __call__(self, s):
        p, ctl = s.p, s.ctl
        if not (s.polish_left <= 0 or s.iteration >= p.max_iterations):
            return False
        worst = unit_crowding(s)
        bad = (s.overlap_g > p.final_overlap) | (s.outside_g > p.final_outside) \
            | (worst > p.final_unit_overlap)
        limit = p.legalize_rounds if ctl.free.any() else p.legalize_rounds_open
        if bad.any() and s.rounds < limit and s.iteration < p.max_iterations:
            s.rounds += 1
            s.polish_left = p.polish_iterations // 3
            uncross(p, ctl, s.place, s.optimizer, s.values, s.index, s.owner)
            resurface(p, s.place, s.optimizer, s.values, s.index, s.owner)
            give = np.where(ctl.free, 1.0, p.legalize_gain_open)
            # a wedged hollow unit's contact opens as the scale gives up a share of its size: the
            # shrink follows the worst unit's overlapped share, up to legalize_shrink_max
            wedged = np.minimum(p.legalize_gain_unit * worst, p.legalize_shrink_max)
            ctl.log -= bad * np.maximum(np.maximum(p.legalize_shrink, wedged),
                                        give * np.maximum(s.overlap_g, s.outside_g))
            return True
        s.done = True
        return False


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
    layer = torch.as_tensor(p.layer, device=values.device, dtype=torch.long)
    over = p.terms.unit_overlap(values, s.index, s.owner, layer, n).cpu().numpy()
    drawn = torch.zeros(n, dtype=values.dtype, device=values.device).index_add_(0, s.owner, values)
    share = over[hollow] / np.maximum(drawn.cpu().numpy()[hollow] * p.ink_share[hollow], 1e-6)
    np.maximum.at(worst, s.ctl.unit_group[hollow], share)
    return worst


SCHEDULE = (BestLoss(), StepSize(), FillScale(), MeasureRoom(), Relocate(), Uncross(), Resurface(), Rest(),
            Pour(), StartPolish(), Decay(), Legalize())


def run(s: State, schedule=SCHEDULE) -> None:
    """One iteration of the schedule: the rules of the phase the iteration began in, in
    order; counts the iteration for its phase and for each rule that acted."""
    phase = s.phase
    s.record[phase] = s.record.get(phase, 0) + 1
    for rule in schedule:
        if rule.phase == phase and (not rule.window or s.iteration % s.p.patience == 0) and rule(s):
            key = f"{phase}.{rule.name}"
            s.record[key] = s.record.get(key, 0) + 1
