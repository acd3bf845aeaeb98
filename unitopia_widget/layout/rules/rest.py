"""``rest``: whether the marks still travel, and the weaker pull once they rest."""
from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from .state import Rule


@dataclass(frozen=True)
class RestSettings:
    settle_motion: float = 0.75    # mean travel over a window, in mean radii, below which marks rest
    straggle: float = 0.9          # the quantile of travel that must rest too (a tenth may lag)


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
    it travels that far in two windows running, as the jitter of a large pile does not). On
    coming to rest the pull weakens, so the best loss is reset and Adam's moments are scaled
    with the force (marks still in the air keep falling at pace). Needed by emitters and
    pouring. Acts when the marks come to rest."""

    name = "rest"
    window = True
    reads = ("place", "stage", "poured", "window_start", "radius", "force_layers", "moving",
             "travelling")
    writes = ("straggling", "calm", "moving", "travelling", "window_start", "best", "since_best",
              "optimizer")
    Settings = RestSettings

    def applies(self, s):
        return bool(s.force_layers)

    def __call__(self, s):
        c = self.settings
        with torch.no_grad():
            now = s.place.transforms()[0].detach().clone()
        pouring = torch.as_tensor(s.stage == s.poured, device=now.device)
        distance = (now - s.window_start).norm(dim=1)
        travel = distance[pouring]
        bar = c.settle_motion * s.radius
        moved = float(travel.mean())
        s.straggling = bool(s.force_layers) and float(torch.quantile(travel, c.straggle)) > bar
        moving = pouring & (distance > bar)
        s.calm = s.moving is not None and not bool((moving & s.moving).any())
        s.moving = moving
        came_to_rest = s.travelling and moved <= bar and bool(s.force_layers)
        if came_to_rest:
            s.best, s.since_best = math.inf, 0
            rescale_moments(s.optimizer, s.place.t, s.steps.force_weight / s.steps.force_travel)
        s.travelling = moved > bar
        s.window_start = now
        return came_to_rest
