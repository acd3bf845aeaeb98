"""A random start for marks of spread sizes: ``scattered`` over the room they take, so that
neither their sizes nor the rows' order show in where they start; and a pile of them
``pressed`` together. Discs at random spots jam near 0.55 of an area, packed ones near 0.85:
a scattered pile is loose, and the raster's gentle pull then closes its gaps one creeping
mark at a time (Table 1, 1,000 discs of areas spread 10x: 756 to 940 iterations). Its
packing discs are pulled by the layer's forces against their overlap energy
(``relax.Discs``) by L-BFGS, a pile's depth in a few hundred cheap steps, then relaxed
without the pull: a dense pile whose sizes stay mixed.
"""
from __future__ import annotations

import copy
import math

import numpy as np
import torch
from scipy.optimize import minimize

from ...design.forces import potential
from .lattice import Region
from .relax import Discs, relax

WIDEN = 1.1         # a pile's scattered start widens its room by this share of spots at a time,
BEYOND = 0.05       # while more than this share of its marks find no random spot in it
PULL = 1.5          # the forces' pull on a disc, median radii over the root of the pile's discs
PRESS = 200         # L-BFGS iterations of the pull at most
SETTLE = 300        # L-BFGS iterations of the relax after it at most
TOLERANCE = 0.003   # the deepest push left on a disc after the relax, in median radii


def scattered(pack, r, cost, ranks, fill: bool, later: float, generator) -> np.ndarray:
    """``(M,)`` a cost per spot of ``pack`` that starts marks ``r (n,)``, placed largest first,
    at random spots (drawn from ``generator``) of the room they take, small ones into the
    gaps the large ones leave: sizes and the rows' order do not show in where marks start.
    The room: the whole container to ``fill``; for a pile, the spots the marks take packed
    in ``ranks`` order from the ``cost``-cheapest out (where the forces gather them), widened
    by ``WIDEN`` of its spots at a time until all but ``BEYOND`` of the marks find a random
    spot in it (discs at random spots jam near 0.55 of an area, packed ones near 0.85:
    near-equal sizes need a wider room, while small ones fill a wide spread's gaps; left
    beyond it, the last and smallest marks ringed the pile), unless layers placed after it
    (``later`` > 0: strata resting on it) start beyond it; spots beyond it follow in
    ``cost`` order, for what the room does not hold."""
    draw = torch.rand(len(cost), generator=generator, dtype=torch.float64).numpy()
    if fill:
        return draw
    trial = copy.copy(pack)
    trial.clear = pack.clear.copy()
    taken = trial.place(r, cost, ranks, largest_first=False, later=later)[0]
    ladder = np.sort(cost)
    room = int(np.searchsorted(ladder, cost[pack.tree.query(taken)[1]].max(), side="right"))
    while True:
        edge = float(ladder[min(room, len(ladder)) - 1])
        beyond = 1.0 + (cost - edge) / max(float(np.ptp(cost)), 1e-12)
        spots = np.where(cost <= edge, draw, beyond)
        if room >= len(ladder) or later > 0:   # layers to come start beyond its exact room
            return spots
        trial.clear = pack.clear.copy()
        at = trial.place(r, spots, ranks, later=later)[0]
        if (cost[pack.tree.query(at)[1]] > edge).mean() <= BEYOND:
            return spots
        room = max(room + 1, int(room * WIDEN))   # a room of under 10 spots grows too


def pressed(center: np.ndarray, radius: np.ndarray, region: Region, forces) -> np.ndarray:
    """``(n, 2)`` the centres ``center (n, 2)`` of a pile's discs ``radius (n,)`` canvas px in
    ``region``, pulled by ``forces`` against their overlap, then relaxed. The pull on each
    disc is ``PULL`` median radii over the root of their number: a pile about that many discs
    deep presses its lowest ones into each other by a fraction of a radius, which the relax
    clears without reordering them. (Strata are not pressed: a pull would sink a layer's
    discs through the one it rests on.)"""
    n, out = len(radius), center.copy()
    discs, pull = Discs(radius, np.arange(n), region), PULL * float(np.median(radius)) / math.sqrt(n)

    def energy(x):
        out[:] = x.reshape(-1, 2)
        overlap, grad = discs.energy(out)
        at = torch.tensor(out, dtype=torch.float64, requires_grad=True)
        drawn = potential(forces, at).sum()
        drawn.backward()
        return overlap + pull * float(drawn), (grad + pull * at.grad.numpy()).reshape(-1)

    found = minimize(energy, center.reshape(-1), jac=True, method="L-BFGS-B",
                     options={"maxiter": PRESS})
    return relax(found.x.reshape(-1, 2), radius, np.arange(n), region, SETTLE, TOLERANCE)
