"""``rest``: whether the marks still travel or fall, and the weaker pull once they rest."""
from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from .state import Rule, forget, unit_overlap


@dataclass(frozen=True)
class RestSettings:
    settle_motion: float = 0.75    # mean travel over a window, in mean radii, below which marks rest
    straggle: float = 0.9          # the quantile of travel that must rest too (a tenth may lag)
    settle_straight: float = 0.5   # net travel / path over a window above which an untouched mark falls


def rescale_moments(optimizer, param: torch.Tensor, ratio: float) -> None:
    """Scale Adam's moments of ``param`` as if its gradients had been ``ratio`` times as large
    all along: the steps stay as they were, and a gradient that shrinks by ``ratio`` now
    still moves the units at full pace instead of waiting for the second moment to forget."""
    state = optimizer.state.get(param)
    if state:
        state["exp_avg"].mul_(ratio)
        state["exp_avg_sq"].mul_(ratio * ratio)


class Rest(Rule):
    """Each settle window, on layouts with forces: marks rest when the mean travel of the
    stage being poured over the window is under ``settle_motion`` mean radii (a tenth still
    travelling, or one mark still falling that far, keeps the settle going: a mark falls when
    it travels that far in two windows running, as the jitter of a large pile does not). A mark
    that touches no other and whose window went straight on (net travel over
    ``settle_straight`` of its ``path``, and over that share of the ground a window of the
    smallest steps covers) is carried by the pull with nothing to stop it: it falls too,
    however small the steps a crowded pile below leaves it (so a settle does not end with
    marks in mid-air by the last digits of the step size), and Adam forgets its moments so
    that it falls at full pace (the second moment of an earlier collision would hold it near
    still). Every settle iteration adds each unit's step to its ``path``; the rest is decided
    once a window. On coming to rest the pull weakens, so the best loss is reset and Adam's moments
    are scaled with the force (marks still in the air keep falling at pace). Needed by
    emitters and pouring. Acts when the marks come to rest."""

    name = "rest"
    reads = ("place", "stage", "poured", "window_start", "radius", "force_layers", "moving",
             "travelling", "path", "last_center", "values", "index", "owner", "iteration")
    writes = ("straggling", "calm", "moving", "travelling", "window_start", "best", "since_best",
              "optimizer", "path", "last_center")
    Settings = RestSettings

    def applies(self, s):
        return bool(s.force_layers)

    def __call__(self, s):
        c, window = self.settings, s.iteration % s.steps.patience == 0
        if not (s.force_layers or window):
            return False
        with torch.no_grad():
            now = s.place.transforms()[0].detach().clone()
        if s.force_layers:
            if s.path is None:
                s.path = torch.zeros(len(now), dtype=now.dtype, device=now.device)
            else:
                s.path += (now - s.last_center).norm(dim=1)
            s.last_center = now
        if not window:
            return False
        pouring = torch.as_tensor(s.stage == s.poured, device=now.device)
        distance = (now - s.window_start).norm(dim=1)
        travel = distance[pouring]
        bar = c.settle_motion * s.radius
        moved = float(travel.mean())
        s.straggling = bool(s.force_layers) and float(torch.quantile(travel, c.straggle)) > bar
        # half the ground a window of the smallest steps (gain 1) carries a unit: a pile's
        # creep goes less far, a mark falling with nothing under it as far or further
        falling = torch.zeros_like(pouring)
        if s.path is not None:
            smallest = s.steps.patience * s.steps.lr * s.radius   # a window of gain-1 steps
            falling = pouring & (distance > c.settle_straight * smallest) \
                & (distance > c.settle_straight * s.path) & (unit_overlap(s) <= 0.0)
            s.path.zero_()
        moving = pouring & (distance > bar) | falling
        s.calm = s.moving is not None and not bool((moving & s.moving).any())
        s.moving = moving
        came_to_rest = s.travelling and moved <= bar and bool(s.force_layers)
        if came_to_rest:
            s.best, s.since_best = math.inf, 0
            rescale_moments(s.optimizer, s.place.t, s.steps.force_weight / s.steps.force_travel)
        if bool(falling.any()):
            forget(s.optimizer, (s.place.t,), torch.nonzero(falling).reshape(-1).cpu())
        s.travelling = moved > bar
        s.window_start = now
        return came_to_rest
