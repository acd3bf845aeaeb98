"""``drop``: open piles under a directional pull dropped onto what holds them, by their ink.

A pile settles until its marks press on each other's footprints as the layout's raster
sees them: a big mark is sampled a block of pixels at a time there, and the force that
presses the pile weakens once it rests, so marks whose boxes interlock (thin arrows in
staggered rows, the arms of stars) stop short of where their ink would meet. After the
last iteration every movable unit of such a pile falls along the pull, by whole pixels of a
fine raster (``step.fine``: footprints cut at alpha 0.5, margins included), until its
footprint would meet another footprint it may not share a pixel with, or leave its region.
A unit that then rests on an edge of another's footprint (an arrow's head on the head of
another a row away, a disc on the crest of two) steps aside, deepest first, across the pull
by at most half its width and no further than its path is clear, to the place from which
it falls furthest, where that fall is longer than the step (``step_aside``); the pile then
falls again behind it. Strata keep their columns: a unit of a layer resting on others has
its floor in the shadow they cast there, and one that others rest on holds them up.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ...design.encodings import footprint
from ..step.fine import FineRaster, draw
from .legalize import extents, pull_of, shadows
from .state import Rule, shift, unbound


@dataclass(frozen=True)
class DropSettings:
    fine_rho: float = 2.0          # fine raster px per canvas px
    max_fine: int = 24_000_000     # fine raster px over all layer slabs at most (more get coarser)
    rounds: int = 6                # falls; in each, every unit falls at once (those above follow)
    gap: float = 1.0               # canvas px each unit stops short of what it meets: a contact
                                   # closer reads as overlap on a raster made for thin marks (finer)
    slides: int = 1                # passes in which each unit resting on an edge steps aside
    places: int = 16               # sideways places it tries each way, spread over its clear path


def piles(s) -> list:
    """``[(pull (2,), units (n,) int), ...]``: the movable units of the layers pulled by
    directional forces alone at a fixed (open) scale, one entry per direction of pull
    (units bound to ``x=``/``y=`` positions keep their places)."""
    free = unbound(s.p, s.place)
    out = {}
    for members, forces in s.force_layers or ():
        m = members.cpu().numpy()
        pull = pull_of(forces)
        if pull is None or s.ctl.free[s.ctl.unit_group[int(m[0])]]:
            continue
        m = m[free[m]]
        if len(m):
            out.setdefault(tuple(np.round(pull, 9)), []).append(m)
    return [(np.asarray(key), np.concatenate(groups)) for key, groups in out.items()]


def line(pull: np.ndarray, k_max: int) -> np.ndarray:
    """``(k_max + 1, 2)`` int: the (row, column) offset of each of ``0..k_max`` whole-pixel
    steps along the unit vector ``pull (2,)`` (x, y): the digital line nearest it."""
    k = np.arange(k_max + 1)
    return np.stack([np.round(k * pull[1]), np.round(k * pull[0])], 1).astype(np.int64)


def fronts(which: torch.Tensor, r: torch.Tensor, c: torch.Tensor, kinds: np.ndarray, owned):
    """The pixels (``which``, ``r``, ``c``: unit, row, column, ``(P,)``) that a step of one
    of ``kinds (k, 2)`` (the distinct (row, column) steps of a line, ``kinds_of``) moves onto
    pixels not already their unit's (``owned(which, rows, columns)``): each step puts a unit
    on new pixels only there."""
    front = torch.zeros_like(which, dtype=torch.bool)
    for dr, dc in kinds:
        front |= ~owned(which, r + int(dr), c + int(dc))
    return which[front], r[front], c[front]


def kinds_of(steps: np.ndarray) -> np.ndarray:
    """``(k, 2)`` the distinct single steps of a line ``steps (K + 1, 2)`` (``line``)."""
    return np.unique(steps[1:] - steps[:-1], axis=0)


def sweep(fine: FineRaster, which, r, c, lay, steps: np.ndarray, limit: np.ndarray,
          owned=None, chunk: int = 2_000_000) -> np.ndarray:
    """``(n,)`` for each of ``n`` candidate placements, the most steps ``k <= limit`` along
    ``steps (K + 1, 2)`` (row, column offsets; K >= limit.max()) it takes with none of its
    pixels (``which``: candidate, ``r``, ``c``, ``lay``: the layer it is judged in, ``(P,)``)
    on a footprint that layer collides with (less its own, ``owned(which, rows, columns)``,
    where given), outside its region or off the raster at any step up to k. The steps are
    looked up in runs that double in length."""
    rows, cols = fine.grid.shape
    dev = which.device
    fell = np.array(limit, dtype=np.int64)
    going = torch.as_tensor(limit > 0, device=dev)
    limit_t = torch.as_tensor(limit, device=dev)
    done, run, k_max = 0, 4, int(limit.max(initial=0))
    while done < k_max and bool(going.any()):
        keep = going[which]
        which, r, c, lay = which[keep], r[keep], c[keep], lay[keep]
        m = max(1, min(run, k_max - done, chunk // max(len(which), 1)))
        off = torch.as_tensor(steps[done + 1:done + m + 1], device=dev)    # (m, 2)
        rr, cc = r[:, None] + off[None, :, 0], c[:, None] + off[None, :, 1]   # (P, m)
        on = (rr >= 0) & (rr < rows) & (cc >= 0) & (cc < cols)
        q = rr.clamp(0, rows - 1) * cols + cc.clamp(0, cols - 1)
        crowd = fine.seen[lay[:, None], q]
        if owned is not None:
            crowd = crowd - owned(which[:, None], rr, cc).float()
        hit = ~on | ~fine.inside[lay[:, None], q] | (crowd > 0.5)
        first = torch.where(hit.any(1), hit.float().argmax(1), m)       # (P,) steps clear
        clear = torch.full((len(limit),), m, device=dev).scatter_reduce(0, which, first, "amin")
        stop = going & ((clear < m) | (limit_t <= done + m))
        halt = stop.cpu().numpy()
        fell[halt] = np.minimum(done + clear.cpu().numpy()[halt], limit[halt])
        going &= ~stop
        done, run = done + m, run * 2
    return fell


def owner_test(fine: FineRaster, which_unit: torch.Tensor, pix: torch.Tensor, who=None):
    """``owned(which, rows, columns)``: whether each pixel is one of its unit's own, the
    pixels ``pix (P,)`` of units ``which_unit (P,)`` (indices into the caller's list). A
    pixel two of them share is the later one's only (a maximum, not an assignment: two
    threads writing one pixel land in an order the machine's load decides, and so did the
    layout); the other, looking it up, finds it crowded anyway.
    ``who``: an int32 buffer of -1 on every fine px to mark them on (the caller sets ``pix``
    back to -1), else a new one."""
    rows, cols = fine.grid.shape
    if who is None:
        who = torch.full((rows * cols,), -1, dtype=torch.int32, device=pix.device)
    who.scatter_reduce_(0, pix, which_unit.to(torch.int32), "amax")

    def owned(which, rr, cc):
        on = (rr >= 0) & (rr < rows) & (cc >= 0) & (cc < cols)
        return on & (who[rr.clamp(0, rows - 1) * cols + cc.clamp(0, cols - 1)] == which)
    return owned


def pixels(fine: FineRaster, units: np.ndarray):
    """``(which, pix, r, c)``: the footprint pixels of ``units`` (``which`` indexes ``units``;
    flat index, row, column), each ``(P,)``."""
    dev = fine.index.device
    cols = fine.grid.shape[1]
    counts = torch.as_tensor(fine.bounds[units + 1] - fine.bounds[units], device=dev)
    which = torch.repeat_interleave(torch.arange(len(units), device=dev), counts)
    pix = torch.cat([fine.pixels(i) for i in units])
    return which, pix, pix // cols, pix % cols


def reach(fine: FineRaster, units: np.ndarray, pull: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """``(n,)`` fine px each of ``units`` can fall along ``pull (2,)`` (at most ``limit (n,)``)
    before a pixel of its footprint meets one it collides with, or one outside its region or
    the raster, the others staying where they are. All fall at once: two units that each
    keep off the other's place keep off each other (a pull is one direction). The fall is
    the digital line of whole pixels nearest the pull; a step of it moves a unit onto new
    pixels only at its front for that step (``fronts``), so only those are looked up."""
    if int(limit.max(initial=0)) <= 0:
        return np.zeros(len(units), dtype=np.int64)
    steps = line(pull, int(limit.max()))
    which, pix, r, c = pixels(fine, units)
    owned = owner_test(fine, which, pix)
    which, r, c = fronts(which, r, c, kinds_of(steps), owned)
    lay = fine.layer[torch.as_tensor(units, device=which.device)][which]
    return sweep(fine, which, r, c, lay, steps, limit, owned)


def step_aside(fine: FineRaster, u: int, pull: np.ndarray, down: np.ndarray, kinds: np.ndarray,
               half_across: float, gap: int, who: torch.Tensor, c) -> tuple[int, int] | None:
    """``(row, column)`` fine px that unit ``u`` (lifted off ``fine.seen``) moves: sideways
    across ``pull (2,)`` by at most ``half_across`` px and as far as its path is clear, to
    the place from which it falls furthest along ``down`` (``line(pull, limit)``, whose kinds
    of step are ``kinds``: at most ``limit`` px, ``gap`` short of what it meets), then that
    fall; None where no place lets it fall further than it moves aside. Only the unit's
    front pixels are looked up (``fronts``); ``who``: ``owner_test``'s buffer, one for a pile."""
    dev = fine.index.device
    pix = fine.pixels(u)
    limit = len(down) - 1
    if not len(pix) or limit <= gap:
        return None
    cols = fine.grid.shape[1]
    row, col = pix // cols, pix % cols
    zero = torch.zeros(len(pix), dtype=torch.long, device=dev)
    owned = owner_test(fine, zero, pix, who)
    lay = fine.layer[u]
    _, r_down, c_down = fronts(zero, row, col, kinds, owned)
    # how far it can move each way (its front pixels swept sideways), then one fall from
    # each of up to ``places`` sideways places spread over that
    span = max(1, int(half_across))
    side = np.array([-pull[1], pull[0]])
    ks, offsets = [], []
    for sign in (1.0, -1.0):
        path = line(sign * side, span)
        which, r, c_side = fronts(zero, row, col, kinds_of(path), owned)
        clear = int(sweep(fine, which, r, c_side, lay.expand(len(which)), path,
                          np.array([span]))[0])
        if clear > 0:
            k = np.unique(np.linspace(1, clear, min(c.places, clear)).round().astype(int))
            ks.append(k)
            offsets.append(path[k])
    best = None
    if ks:
        ks, offsets = np.concatenate(ks), np.concatenate(offsets)
        off = torch.as_tensor(offsets, device=dev)
        which = torch.arange(len(ks), device=dev).repeat_interleave(len(r_down))
        rr = (r_down[None] + off[:, :1]).reshape(-1)
        cc = (c_down[None] + off[:, 1:]).reshape(-1)
        falls = sweep(fine, which, rr, cc, lay.expand(len(which)), down,
                      np.full(len(ks), limit)) - gap
        gain = falls - ks
        k = int(np.argmax(gain))
        if gain[k] > 0:
            shift = offsets[k] + down[falls[k]]
            best = (int(shift[0]), int(shift[1]))
    who[pix] = -1
    return best


@torch.no_grad()
def fall(s, c: DropSettings = DropSettings()) -> np.ndarray:
    """``(N, 2)`` canvas px each unit of the ``piles`` of the solver's state ``s`` falls: up to
    ``rounds`` falls of all at once (``reach``), each unit as far as the last left it room;
    then ``slides`` times each unit that can step aside and fall further does
    (``step_aside``), and all fall again."""
    p, place = s.p, s.place
    center, angle = place.transforms()
    unit_scale = s.ctl.unit_scale()
    fine = draw(p, center.detach(), angle.detach(), unit_scale, place.rotating(), c.fine_rho,
                c.max_fine)
    rho, far = fine.grid.rho, int(sum(fine.grid.shape))   # far: further than any fall
    xy = center.detach().cpu().numpy().astype(float)
    turn = angle.detach().cpu().numpy().astype(float)
    foot = footprint(p.margin) * unit_scale
    moved = np.zeros((len(p.layer), 2))
    gap = math.ceil(c.gap * rho)
    # a stratum keeps its columns: a unit resting on others has its floor in the shadow cast
    # in its column, and one that others rest on holds them up there
    count = int(p.layer.max()) + 1
    rests = np.zeros((count, count), bool) if p.terms.rests is None \
        else p.terms.rests.cpu().numpy() > 0
    keeps_column = rests.any(0) | rests.any(1)
    who = torch.full((fine.grid.shape[0] * fine.grid.shape[1],), -1, dtype=torch.int32,
                     device=fine.index.device)   # owner_test's buffer for step_aside
    for pull, units in piles(s):
        side = np.array([-pull[1], pull[0]])
        along = extents(p.half_w * foot, p.half_h * foot, turn, pull)
        across = extents(p.half_w * foot, p.half_h * foot, turn, side)
        # a layer resting on another may not fall past the top of its boxes (``shadows``)
        barrier = np.full(len(p.layer), np.inf) if p.terms.rests is None else shadows(
            xy, along, across, pull, p.layer, rests, units)
        down = line(pull, far)
        kinds = kinds_of(down)
        for slide in range(c.slides + 1):
            for _ in range(c.rounds):
                room = (barrier[units] - (xy[units] + moved[units]) @ pull) * rho
                limit = np.where(np.isfinite(room), np.floor(np.maximum(room, 0.0)),
                                 far).astype(np.int64)
                steps = np.maximum(reach(fine, units, pull, limit) - gap, 0)
                if not steps.any():
                    break
                falling = units[steps > 0]
                by = line(pull, int(steps.max()))[steps[steps > 0]]        # (n, 2) rows, columns
                fine.shift(falling, by[:, 0] * fine.grid.shape[1] + by[:, 1])
                moved[falling] += by[:, ::-1] / rho
            if slide == c.slides:
                break
            # units jammed on others' edges (arrowheads in staggered rows) step aside and
            # fall, deepest first; then all fall again behind them
            stepped = False
            depth = (xy[units] + moved[units]) @ pull
            for u in units[np.argsort(-depth, kind="stable")]:
                if keeps_column[p.layer[u]]:
                    continue
                fine.lift(u)
                by = step_aside(fine, u, pull, down, kinds, across[u] * rho, gap, who, c)
                if by is not None:
                    fine.move_lifted(u, *by)
                    moved[u] += np.array([by[1], by[0]]) / rho
                    stepped = True
                fine.put(u)
            if not stepped:
                break
    return moved


class Drop(Rule):
    """Once, after the last iteration of a layout that was not cancelled: the units of open
    piles under directional forces fall along their pull until their footprints meet (``fall``;
    those of a layer resting on another no further than its boxes' top, as ``legalize.press``).
    Needed by open piles of marks whose boxes interlock or whose ink the layout's raster
    samples coarsely: thin marks above all. Corpus, seeds 0-4, all 15 directional piles
    that moved pull further: thin arrows pushed right (m095) 0.55 -> 0.68, thin bars (m109)
    0.50 -> 0.62, the thin-push kind 0.65 -> 0.69, spiky flakes (m029) 0.37 -> 0.41; strata
    in order, thin arrows (m081) 0.95 -> 0.99, stars on a slope 0.94 -> 0.97. Stepping
    aside (``step_aside``) moved 10 single-layer piles of the corpus, pull up or level in
    all, over seeds 0-4 rings in twin discs (m068) 0.667 -> 0.702; the thin-push kind at
    corpus seeds 1-4 0.64 / 0.61 / 0.66 / 0.57 -> 0.69 / 0.64 / 0.69 / 0.62."""

    name = "drop"
    phase = "finish"
    reads = ("ctl", "place", "force_layers")
    writes = ("place",)
    Settings = DropSettings

    def applies(self, s):
        return bool(s.force_layers) and bool(piles(s))

    def __call__(self, s):
        if not self.applies(s):
            return False
        return shift(s.place, fall(s, self.settings))
