"""``legalize``: the end of a polish, or another round of it at a little less scale."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from ...design.forces import DirectionalForce
from .resurface import resurface
from .state import Rule, State, forget, movable, unit_overlap
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
             "owner", "ctl", "force_layers")
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
            shrink = bad * np.maximum(np.maximum(c.shrink, wedged),
                                      give * np.maximum(s.overlap_g, s.outside_g))
            ctl.log -= shrink
            piles = [(m, fs) for m, fs in s.force_layers
                     if not ctl.free[ctl.unit_group[int(m[0])]]] if s.force_layers else []
            if piles:
                press(p, s.place, s.optimizer, piles, np.exp(-shrink)[ctl.unit_group])
            return True
        s.done = True
        return False


def pull_of(forces) -> np.ndarray | None:
    """The unit vector ``(2,)`` of the net pull of ``forces`` when they are all directional,
    else None (a point force holds a pile around it, not on a floor; a net pull of nothing
    holds it nowhere)."""
    if not forces or not all(isinstance(f, DirectionalForce) for f in forces):
        return None
    net = np.sum([np.multiply(f.vector, f.strength) for f in forces], axis=0)
    norm = float(np.hypot(*net))
    return net / norm if norm > 1e-9 else None


def floor_distance(coverage: np.ndarray, rho: float, center: np.ndarray,
                   pull: np.ndarray) -> np.ndarray:
    """``(n,)`` canvas px from each of ``center (n, 2)`` along ``pull (2,)`` to where the
    region (``coverage (H, W)``, ``rho`` raster px per canvas px) ends: each mark's own floor
    (0 for a centre already outside)."""
    h, w = coverage.shape
    reach = np.hypot(h, w) / rho
    t = np.arange(0.0, reach + 1.0 / rho, 0.5 / rho)                    # (K,) half-pixel steps
    at = center[:, None, :] + t[None, :, None] * pull[None, None, :]   # (n, K, 2)
    j, i = np.floor(at[..., 0] * rho).astype(int), np.floor(at[..., 1] * rho).astype(int)
    inside = (i >= 0) & (i < h) & (j >= 0) & (j < w)
    inside[inside] = coverage[i[inside], j[inside]] >= 0.5
    first = np.where(inside.all(1), len(t) - 1, np.argmin(inside, axis=1))
    return t[first]


def press(p, place, optimizer, piles, unit_ratio: np.ndarray) -> None:
    """Keep open piles pressed to their floors as their scale gives up size: marks shrunk
    about their own centres open a gap at every contact, which the legalising rounds (no
    force presses in them) would leave open, a pile as spread as it was at the asked size.
    Each free unit of ``piles`` (``[(unit indices, forces), ...]``, layers pulled by
    directional forces alone) moves along their net pull by ``1 - unit_ratio`` (``(N,)``,
    its new size over its old) of its distance to its own floor, where its container ends
    along the pull (``floor_distance``): a column shrinks onto its floor as one, a stratum
    with the one it rests on, and no mark crosses a floor, however high."""
    free = movable(place)
    with torch.no_grad():
        center = place.transforms()[0].detach().cpu().numpy().astype(float)
        shift = np.zeros_like(center)
        for members, forces in piles:
            pull = pull_of(forces)
            if pull is None:
                continue
            m = members.cpu().numpy()
            m = m[free[m]]
            cover = p.regions[int(p.layer[m[0]])].coverage(p.grid.canvas, p.grid.rho) \
                if len(m) else None
            if cover is not None:
                depth = floor_distance(cover, p.grid.rho, center[m], pull)
                shift[m] = ((1.0 - unit_ratio[m]) * depth)[:, None] * pull[None, :]
        moved = np.flatnonzero(np.abs(shift).sum(1) > 0)
        place.t[moved] += torch.as_tensor(shift[moved], dtype=place.t.dtype, device=place.t.device)
    forget(optimizer, (place.t,), moved.tolist())
