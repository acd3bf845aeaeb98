"""The controlled global scales of a layout, one per scale group, and the ink raster that
tells whether their closed containers still have room."""
from __future__ import annotations

import numpy as np
import torch

from .room import empty_share


class Scales:
    """The controlled global scales: one per scale group, as logs ``(G,)``, of the solver's
    ``Problem`` ``p``."""

    def __init__(self, p):
        self.p = p
        n_layers = p.terms.penalty.shape[0]
        self.group = np.zeros(n_layers, int) if p.scale_group is None else np.asarray(p.scale_group)
        self.count = int(self.group.max()) + 1
        start = [p.scale] if p.group_scale is None else p.group_scale
        self.log = np.log(np.asarray(start, dtype=float))
        self.free = np.asarray([p.free_scale] if p.group_free is None else p.group_free, bool)
        self.unit_group = self.group[p.layer]
        # room grows a scale while its footprints poke out by less than this share: 0.4 of
        # grow_overlap for bare marks, all of it with margins of 0.1 and more (a mark pressed
        # against the edge pokes its margin band out long before its ink)
        margin = np.array([np.median(p.margin[self.unit_group == g]) if (self.unit_group == g).any()
                           else 0.0 for g in range(self.count)])
        self.grow_outside = p.grow_overlap * np.minimum(0.4 + 6.0 * margin, 1.0)

    @property
    def measures_room(self) -> bool:
        """Whether the room of closed containers is measured (some scale fills them)."""
        return self.p.reach is not None and bool(self.free.any())

    def unit_scale(self) -> np.ndarray:
        """``(N,)`` each unit's current scale."""
        return np.exp(self.log)[self.unit_group]

    def crowding(self, sums: np.ndarray):
        """Overlap and outside shares ``(G,)`` from the loss's per-layer sums ``(3, L)``."""
        per = np.zeros((3, self.count))
        np.add.at(per.T, self.group, sums.T)
        drawn = np.maximum(per[2], 1e-6)
        return per[0] / drawn, per[1] / drawn

    def room(self, cover: np.ndarray | None) -> np.ndarray:
        """Bool ``(G,)``: controlled groups whose closed containers all still have room
        (a shared scale that grows for an empty container overfills a full one), from the
        ink raster ``cover (H, W)`` (``coverage``; None where ``measures_room`` is False)."""
        p, out = self.p, np.zeros(self.count, dtype=bool)
        if not self.measures_room:
            return out
        inside = p.terms.inside_host
        scale = self.unit_scale()
        for g in np.nonzero(self.free)[0]:
            roomy = []
            for layer in np.nonzero(self.group == g)[0]:
                mine = p.layer == layer
                if not inside[layer].any():
                    continue
                reach = float(np.median(p.reach[mine] * scale[mine])) * p.grid.rho
                roomy.append(empty_share(cover, inside[layer].reshape(p.grid.shape), reach)
                             > p.room_target)
            out[g] = bool(roomy) and all(roomy)
        return out


def coverage(p, values, index) -> np.ndarray:
    """``(H, W)`` host copy of the summed sample alphas ``values (M,)`` at raster ``index (M,)``."""
    size = p.terms.penalty.shape[1]
    cover = torch.zeros(size, dtype=values.dtype, device=values.device).index_add_(0, index, values)
    return cover.cpu().numpy().reshape(p.grid.shape)
