"""What the rules share: the solver's ``State``, the ``Rule`` they are made from, the step
sizes and cadence the solver and the rules both read (``Steps``), and the bookkeeping of a
move made by hand (``movable``, ``bound``, ``unbound``, ``sideways``, ``forget``, ``shift``) and each unit's overlap at the samples
(``unit_overlap``)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import torch

from ..step.optim import Adam
from ..step.placement import Placement
from ..step.scales import Scales


@dataclass(frozen=True)
class Steps:
    """The solver's step sizes, force pressures and cadence, which its rules read too."""

    lr: float = 0.04               # translation step when marks touch, in mean mark radii
    force_weight: float = 0.005    # force pressure relative to overlap, once marks rest
    force_travel: float = 0.03     # force pressure while marks are still travelling
    polish_force: float = 0.05     # force weight in the polish phase, relative
    patience: int = 12             # iterations of a window (window rules run once in each)
    polish_iterations: int = 60


@dataclass
class State:
    """What the rules share: the problem ``p`` (``prepare.problem.Problem``), the step
    settings, the scales, the placement and its optimizer, the schedule's counters, and this
    iteration's readback (``values``, ``index``, ``owner``: the rendered samples;
    ``overlap_g``, ``outside_g``: shares ``(G,)`` per scale group)."""

    p: object                      # the solver's Problem
    steps: Steps
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
    path: torch.Tensor | None = None     # (N,) px each unit's centre went this window, step by step
    last_center: torch.Tensor | None = None  # (N, 2) centres at the last settle iteration (for path)
    poured: int = 0                # the last stage poured
    poured_at: int = 0
    grow_outside: np.ndarray | None = None   # (G,) outside share below which room grows a scale
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
        self.since_best = min(self.since_best, self.steps.patience // 2)


class Rule:
    """A named step of the schedule; ``__call__(state)`` returns whether it acted.

    ``phase``: "settle", "polish" or "finish" (once, after the last iteration); ``window``:
    runs once every ``Steps.patience`` iterations only; ``reads``/``writes``: the ``State``
    fields it reads and writes; ``Settings``: the dataclass of its tuning numbers, whose
    defaults ``settings`` takes unless given others. ``applies(state)``: whether the rule
    can act on this layout at all (what ``explain`` lists); ``start(state)``: called once
    before the first iteration."""

    name = ""
    phase = "settle"
    window = False
    reads: tuple = ()
    writes: tuple = ()
    Settings = None

    def __init__(self, settings=None):
        self.settings = self.Settings() if settings is None and self.Settings else settings

    def applies(self, s: State) -> bool:
        return True

    def start(self, s: State) -> None:
        """Called once, on the state the first iteration starts from."""


def movable(place: Placement) -> np.ndarray:
    """Bool ``(N,)``: units the solver may move by hand: released, and not on a curve track."""
    free = place.keep[:, 0].cpu().numpy() > 0
    for track in place.tracks:
        free[track.index.cpu().numpy()] = False
    return free


def bound(p) -> np.ndarray:
    """Bool ``(N,)``: the units an ``x=``/``y=`` position binds (``p.anchor``, of the solver's
    Problem ``p``)."""
    if p.anchor is None:
        return np.zeros(len(p.layer), bool)
    return (p.anchor.mask.cpu().numpy() > 0).any(1)


def unbound(p, place: Placement) -> np.ndarray:
    """Bool ``(N,)``: the ``movable`` units of ``place`` that no ``x=``/``y=`` position binds
    (``bound``): a finish rule may move them anywhere."""
    return movable(place) & ~bound(p)


def sideways(p, place: Placement) -> np.ndarray:
    """``(N, 2)``: for each unit of a band of ``place`` (a curve emitter's "band" mode) that no
    ``x=``/``y=`` position binds, the unit normal to its curve where it is, the one way a
    finish rule may move it (``CurveTrack.sideways``); 0 for every other unit."""
    out = np.zeros((len(p.layer), 2))
    for track in place.tracks:
        normal = track.sideways()
        if normal is not None:
            out[track.index.cpu().numpy()] = normal.cpu().numpy()
    out[bound(p)] = 0.0
    return out


def shift(place: Placement, move: np.ndarray) -> bool:
    """Move the units of ``place`` by ``move (N, 2)`` canvas px after the last iteration (a
    finish rule's move: no optimizer step follows); a unit of a band by the part of its move
    along the curve's normal (``sideways``). Whether any moved."""
    if not move.any():
        return False
    with torch.no_grad():
        by = torch.tensor(move, dtype=place.t.dtype, device=place.t.device)   # a copy: rows cleared below
        for track in place.tracks:
            track.step_aside(by[track.index])
            by[track.index] = 0.0   # its centre is where its track puts it, not ``t``
        place.t += by
    return True


def forget(optimizer, params, units: list) -> None:
    """Clear Adam's moments of ``units`` in each of ``params``: they were moved by hand."""
    for param in params:
        state = optimizer.state.get(param, {})
        for key in ("exp_avg", "exp_avg_sq"):
            if key in state:
                state[key][units] = 0.0


def unit_overlap(s: State) -> torch.Tensor:
    """``(N,)`` each unit's overlapped alpha as the loss counts it (other units' and lower
    strata's), raster px^2, at this iteration's samples (``CanvasTerms.unit_overlap``)."""
    values = s.values.detach()
    layer = torch.as_tensor(s.p.layer, device=values.device, dtype=torch.long)
    return s.p.terms.unit_overlap(values, s.index, s.owner, layer, len(s.p.layer))
