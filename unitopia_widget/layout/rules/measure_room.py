"""``measure-room``: which closed containers still have room, where a typical mark would
still fit.

The fill controller grows the global scale while a container has room. Room is measured as
the layout checker measures emptiness: the share of the container farther than a typical
mark's radius from any mark.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from ..step.distance import edt
from .state import Rule


@dataclass(frozen=True)
class MeasureRoomSettings:
    room_target: float = 0.02      # empty share of a closed container below which it is full


def empty_share(cover: np.ndarray, inside: np.ndarray, reach: float) -> float:
    """Share of the container farther than ``reach`` from every mark.

    ``cover``: ``(H, W)`` raster coverage of all marks' footprints; ``inside``:
    ``(H, W)`` the container's coverage; ``reach``: raster px (a median mark
    radius less its margin band). Returns a share in [0, 1].
    """
    mask = inside >= 0.5
    total = int(mask.sum())
    if total == 0:
        return 0.0
    far = edt(cover < 0.5) > max(reach, 1.0)
    return float((far & mask).sum()) / total


def coverage(p, values, index) -> np.ndarray:
    """``(H, W)`` host copy of the summed sample alphas ``values (M,)`` at raster ``index (M,)``."""
    size = p.terms.penalty.shape[1]
    cover = torch.zeros(size, dtype=values.dtype, device=values.device).index_add_(0, index, values)
    return cover.cpu().numpy().reshape(p.grid.shape)


def measures_room(p, ctl) -> bool:
    """Whether the room of closed containers is measured (some scale fills them)."""
    return p.reach is not None and bool(ctl.free.any())


def jammed(s, share: float) -> np.ndarray:
    """Bool ``(G,)``: groups with room (``State.room``) whose overlap or ink outside is still
    above ``share``: their fill controller still trades scale for crowding. All False
    before room was measured."""
    if s.room is None:
        return np.zeros(len(s.overlap_g), dtype=bool)
    return s.room & ((s.overlap_g > share) | (s.outside_g > share))


def room(p, ctl, cover: np.ndarray | None,
         c: MeasureRoomSettings = MeasureRoomSettings()) -> np.ndarray:
    """Bool ``(G,)``: controlled groups whose closed containers all still have room
    (a shared scale that grows for an empty container overfills a full one), from the
    ink raster ``cover (H, W)`` (``coverage``; None where ``measures_room`` is False)."""
    out = np.zeros(ctl.count, dtype=bool)
    if not measures_room(p, ctl):
        return out
    inside = p.terms.inside_host
    scale = ctl.unit_scale()
    for g in np.nonzero(ctl.free)[0]:
        roomy = []
        for layer in np.nonzero(ctl.group == g)[0]:
            mine = p.layer == layer
            if not inside[layer].any():
                continue
            reach = float(np.median(p.reach[mine] * scale[mine])) * p.grid.rho
            roomy.append(empty_share(cover, inside[layer].reshape(p.grid.shape), reach)
                         > c.room_target)
        out[g] = bool(roomy) and all(roomy)
    return out


class MeasureRoom(Rule):
    """Each settle window, where some scale fills closed containers: copy the ink raster to
    the host once and measure which groups' containers still have room, for the fill
    controller and relocation. Needed by containers that stay part empty while spiky or
    heavy-tailed marks jam."""

    name = "measure-room"
    window = True
    reads = ("values", "index", "ctl")
    writes = ("cover", "room")
    Settings = MeasureRoomSettings

    def applies(self, s):
        return measures_room(s.p, s.ctl)

    def __call__(self, s):
        s.cover = coverage(s.p, s.values.detach(), s.index) if measures_room(s.p, s.ctl) else None
        s.room = room(s.p, s.ctl, s.cover, self.settings)
        return s.cover is not None
