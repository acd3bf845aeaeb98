"""The solver's ``Problem``: everything a layout needs, made once (``assemble.build_problem``)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..step.losses import CanvasTerms
from ..step.placement import Placement
from ..step.raster import RasterGrid


@dataclass
class Problem:
    """Everything the solver needs to know of one layout, data only (the tuning numbers are
    the rules' settings, ``rules.Steps`` and each rule's); ``N`` units, ``L`` layers.
    Lengths in canvas px."""

    grid: RasterGrid
    pyramids: list                 # per sprite: list of (1, 1, h, w) tensors, finest first
    sprite_sides: list[int]        # long side of each sprite's finest level
    sprite: np.ndarray             # (N,) sprite id per unit
    layer: np.ndarray              # (N,) layer index per unit
    half_w: np.ndarray             # (N,) half box width at scale 1 (drawn, no margin)
    half_h: np.ndarray             # (N,) half box height at scale 1
    margin: np.ndarray             # (N,) margin fraction: footprint = box * footprint(margin)
    placement: Placement           # positions and angles, with their constraints
    terms: CanvasTerms             # containment / fill fields per layer, blocks
    forces: list                   # per layer: list of forces
    scale: float                   # initial global scale (of scale group 0)
    free_scale: bool               # control the scale (some closed layer fills its container)
    scale_group: np.ndarray | None = None  # (L,) scale group per layer; None: one shared scale
    group_scale: np.ndarray | None = None  # (G,) initial scale per group; None: [scale]
    group_free: np.ndarray | None = None   # (G,) bool, controlled groups; None: [free_scale]
    group_cap: np.ndarray | None = None    # (G,) the most a controlled group's scale grows to (fit.group_caps); None: no cap
    reach: np.ndarray | None = None        # (N,) ink radius less margin band at scale 1 (room)
    disc: np.ndarray | None = None         # (N,) the disc a packed footprint needs at scale 1 (start.footprint_radius)
    sprite_aspects: list | None = None     # width / height of each sprite's finest level (None: 1)
    stage: np.ndarray | None = None  # (N,) pouring stage: stage k moves once stage k - 1 rests
    travelling: bool = True        # whether marks start away from where they will rest
    anchor: object | None = None   # positions.Anchor: the pull of x=/y= bound units to their targets
    max_iterations: int = 600      # the iteration cap (the layers' iterations=)
    ink_share: np.ndarray | None = None  # (N,) ink area / footprint area, < 1 for hollow marks; None: all 1
    resolved: bool = False         # every mark solid and TARGET_RADIUS raster px across or more at the
                                   # start (a capped raster: at the resolution aimed at, ``unseen``
                                   # making up the rest): no contact is finer than the raster (rules.decay)
    unseen: float = 0.0            # canvas px the margins add to every footprint's side for a
                                   # capped raster (assemble.unseen_depth)
    device: str = "cpu"
    regions: tuple = ()            # per layer: its allowed region (a design Container), for contacts.clear

    def layer_groups(self) -> np.ndarray:
        """``(L,)`` each layer's scale group (all 0 under one shared scale)."""
        return np.zeros(len(self.forces), int) if self.scale_group is None else np.asarray(self.scale_group)

    def group_scales(self) -> np.ndarray:
        """``(G,)`` float: each scale group's initial scale."""
        return np.array([self.scale] if self.group_scale is None else self.group_scale, dtype=float)

    def group_controlled(self) -> np.ndarray:
        """``(G,)`` bool: the scale groups whose scale the fill controls."""
        return np.array([self.free_scale] if self.group_free is None else self.group_free, dtype=bool)


class Cancelled(Exception):
    """A layout stopped before it had a step to keep."""
