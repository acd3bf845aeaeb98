"""The solver's ``Problem``: everything a layout needs, made once (``assemble.build_problem``)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..step.losses import CanvasTerms
from ..step.placement import Placement
from ..step.raster import RasterGrid


@dataclass
class Problem:
    """Everything the solver needs; ``N`` units, ``L`` layers. Lengths in canvas px."""

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
    reach: np.ndarray | None = None        # (N,) ink radius less margin band at scale 1 (room)
    disc: np.ndarray | None = None         # (N,) the disc a packed footprint needs at scale 1 (start.footprint_radius)
    sprite_aspects: list | None = None     # width / height of each sprite's finest level (None: 1)
    stage: np.ndarray | None = None  # (N,) pouring stage: stage k moves once stage k - 1 rests
    stage_wait: int = 150          # iterations a stage waits at most for the one before
    travelling: bool = True        # whether marks start away from where they will rest
    anchor: object | None = None   # positions.Anchor: the pull of x=/y= bound units to their targets
    max_iterations: int = 600
    polish_iterations: int = 60
    polish_shrink: float = 0.008
    polish_force: float = 0.05     # force weight in the polish phase, relative
    force_weight: float = 0.005    # force pressure relative to overlap, once marks rest
    force_travel: float = 0.03     # force pressure while marks are still travelling
    lr: float = 0.04               # translation step when marks touch, in mean mark radii
    lr_travel: float = 0.3         # the step while nothing overlaps (marks travelling), mean radii
    overlap_target: float = 0.002  # raster overlap share above which steps shrink
    final_overlap: float = 0.001   # overlap share a layout must reach (scale shrinks until)
    final_outside: float = 0.001   # outside share a layout must reach (scale shrinks until)
    final_unit_overlap: float = 0.003  # overlap share of its ink no hollow unit may keep (scale shrinks until)
    ink_share: np.ndarray | None = None  # (N,) ink area / footprint area, < 1 for hollow marks; None: all 1
    room_target: float = 0.02      # empty share of a closed container below which it is full
    relocate_share: float = 0.05   # share of a roomy layer's marks moved into holes per window
    legalize_rounds: int = 10
    legalize_rounds_open: int = 20  # when no scale fills a container (forces press open piles)
    legalize_shrink: float = 0.005
    legalize_gain_unit: float = 0.3    # log-scale shrink per legalising round / the worst hollow unit's share
    legalize_shrink_max: float = 0.02  # the most log-scale that shrink may give up per round
    legalize_gain_open: float = 2.0   # log-scale shrink per legalising round / overlap, fixed scales
    grow_overlap: float = 0.01     # the fill controller grows the scale below half this overlap
    scale_step: float = 0.003      # log-scale step of the fill controller per iteration
    patience: int = 12
    settle_motion: float = 0.75    # mean travel over a patience window, in mean radii, below which marks rest
    device: str = "cpu"
    regions: tuple = ()            # per layer: its allowed region (a design Container), for contacts.clear


class Cancelled(Exception):
    """A layout stopped before it had a step to keep."""
