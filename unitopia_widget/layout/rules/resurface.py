"""``resurface``: marks buried in a stratum's obstacle are lifted back onto it.

A layer that rests on others sees their ink swept along its force (``strata.py``): an
obstacle that is flat, full everywhere below their envelope. A mark wholly inside it (a
large mark of a lower layer rolled over it) gets no gradient out of it, and its force
presses it further in. So a free mark with more than ``buried`` of its alpha on its
obstacle is lifted against its pull (back along a directional sweep, out from the point
that pulls it, or up to 60 degrees aside: a wall may slope across straight back), by whole
raster px, the least distance that leaves at most ``clear`` of its alpha on the obstacle or
outside its region. Layers are lifted lowest stratum first, each
against the surface as the layers below it were lifted; a mark is not cleared of its own
layer (the gradient parts it from its neighbours), nor lifted where no spot clears it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch

from ..step.strata import RadialShadow
from .state import Rule, forget, movable


@dataclass(frozen=True)
class ResurfaceSettings:
    buried: float = 0.5    # share of a mark's alpha on its obstacle above which it is lifted
    clear: float = 0.01    # share of its alpha a lifted mark may keep on the obstacle or outside
    chunk: int = 32        # lift distances tried at once first, raster px
    lookups: int = 1 << 22  # raster lookups in one chunk of lift distances at most (past the first)
    fan: tuple = (0.0, -np.pi / 6, np.pi / 6, -np.pi / 3, np.pi / 3)   # lift directions, off straight back


def strata_order(rests: np.ndarray) -> list:
    """The resting layers of ``rests (L, L)`` (``rests[a, b]``: ``a`` rests on ``b``), each
    after every layer it rests on, directly or not."""
    depth = np.zeros(len(rests), dtype=int)
    for _ in range(len(rests)):   # a layer's depth: 1 + the deepest it rests on
        depth = np.where(rests.any(1), 1 + np.max(np.where(rests, depth[None], -1), 1), 0)
    resting = np.nonzero(rests.any(1))[0]
    return [int(a) for a in resting[np.argsort(depth[resting], kind="stable")]]


def against(sweep, xy: np.ndarray) -> np.ndarray:
    """``(n, 2)`` unit vectors (raster x, y) against ``sweep`` at ``xy (n, 2)`` canvas px:
    back up a raster axis sweep ``(dim, reverse)``, out from the point that pulls each of
    ``xy`` for a ``RadialShadow``."""
    if isinstance(sweep, RadialShadow):
        radial = sweep.radial
        point = np.asarray(radial.points, float)[radial.pulling(xy), :2]
        out = xy - point
        norm = np.hypot(out[:, 0], out[:, 1])[:, None]
        return np.where(norm > 1e-9, out / np.maximum(norm, 1e-9), np.array([0.0, -1.0]))
    dim, reverse = sweep
    step = np.zeros(2)
    step[1 - dim] = 1.0 if reverse else -1.0   # raster dim 0 is y, dim 1 is x
    return np.broadcast_to(step, (len(xy), 2))


def buried(terms, values: torch.Tensor, index: torch.Tensor, owner: torch.Tensor,
           layer: np.ndarray, center: np.ndarray, free: np.ndarray, rho: float,
           c: ResurfaceSettings = ResurfaceSettings()) -> list:
    """Lifts of the buried free marks: ``[(unit, (dx, dy) canvas px)]``. ``values``,
    ``index``, ``owner`` ``(M,)`` the rendered samples (``render_samples``), ``layer (N,)``
    each unit's layer, ``center (N, 2)`` canvas px, ``free (N,)`` bool, ``rho`` raster px
    per canvas px; ``terms`` the ``CanvasTerms`` (its rests, sweeps, outside)."""
    height, width = terms.shape
    _, own = terms.coverage(values, index, owner,
                            torch.as_tensor(layer, device=values.device, dtype=torch.long))
    order = torch.argsort(owner, stable=True)
    counts = torch.bincount(owner, minlength=len(layer)).cpu().numpy()
    starts = np.concatenate([[0], np.cumsum(counts)])
    drawn = torch.zeros(len(layer), dtype=values.dtype, device=values.device).index_add_(0, owner, values)
    lifts = []
    for a in strata_order(terms.rests.cpu().numpy() > 0):
        sweep = terms.sweeps[a]
        mine = np.nonzero((layer == a) & free)[0]
        if sweep is None or not len(mine):
            continue
        block = torch.maximum(terms.obstacle(own, a).clamp(max=1.0), terms.outside[a].to(own))
        on = torch.zeros(len(layer), dtype=values.dtype, device=values.device) \
            .index_add_(0, owner, values * block[index.long()])
        share = (on / drawn.clamp_min(1e-6)).cpu().numpy()
        lifting = mine[share[mine] > c.buried]
        room = _room(block, terms.outside[a], height, width, c.clear) if len(lifting) else None
        for unit, back in zip(lifting, against(sweep, center[lifting])):
            samples = order[starts[unit]:starts[unit + 1]]
            samples = samples[values[samples] > 0]   # its ink (a turning thin mark's patch is most empty)
            alpha, pixel = values[samples], index[samples].long()
            steps = _fan(back, c.fan)
            found = _lift(block, alpha, pixel, np.array(steps), height, width, room, c)
            if found is None:
                continue
            distance, step = found[0], steps[found[1]]
            shift = np.rint(distance * step).astype(int)
            moved = pixel + int(shift[1]) * width + int(shift[0])
            own[a].index_add_(0, pixel, -alpha).index_add_(0, moved, alpha)
            lifts.append((int(unit), (shift[0] / rho, shift[1] / rho)))
    return lifts


def _fan(back: np.ndarray, fan: tuple) -> list:
    """Directions ``(2,)`` at the turns ``fan`` off ``back (2,)``, straight back first: a mark
    wedged against a sloping wall clears the obstacle a little aside from straight back."""
    out = []
    for turn in fan:
        c, s = np.cos(turn), np.sin(turn)
        out.append(np.array([c * back[0] - s * back[1], s * back[0] + c * back[1]]))
    return out


def _room(block: torch.Tensor, outside: torch.Tensor, height: int, width: int, clear: float):
    """Where a lift may end, or None: ``(box, free)``, ``box = (row0, row1, col0, col1)``
    (inclusive) around the pixels of ``outside (S,)`` under 1 (partly inside the layer's
    region; ``block (S,)`` is 1 beyond it), and ``free (H + 1, W + 1)`` the summed-area
    table of the pixels where ``block`` is at most ``clear``: a spot whose box holds none
    leaves more than ``clear`` of any alpha on the block."""
    rows, cols = torch.nonzero((outside < 1.0).reshape(height, width), as_tuple=True)
    if not len(rows):
        return None
    free = np.zeros((height + 1, width + 1), dtype=np.int64)
    free[1:, 1:] = (block <= clear).reshape(height, width).cpu().numpy().cumsum(0).cumsum(1)
    return (int(rows.min()), int(rows.max()), int(cols.min()), int(cols.max())), free


def _lift(block: torch.Tensor, alpha: torch.Tensor, pixel: torch.Tensor, steps: np.ndarray,
          height: int, width: int, room, settings: ResurfaceSettings):
    """``(distance, k)``: the fewest raster px along one of ``steps (D, 2)`` (x, y) that leave
    at most ``settings.clear`` of ``alpha (m,)`` at ``pixel (m,)`` (flat indices of an
    ``(height, width)`` raster) on ``block (S,)``, and that step's index (the first of equal
    distances); beyond the box of ``room`` (``_room``) counts as blocked. None where no
    distance clears it.

    Distances 1, 2, ... are tried in chunks, every step at once: ``settings.chunk`` first,
    then twice as many each time while the ``(D, chunk, m)`` lookups stay under
    ``settings.lookups``. Only the spots whose box holds a free pixel of ``room`` are read; a step
    whose mark's box has left the room's box is dropped (a ray does not come back into a
    box). The chunks end where chunks of ``settings.chunk`` would: past the raster's longer
    side."""
    row, col = pixel // width, pixel % width
    total = float(alpha.sum())
    if total <= 0 or room is None:
        return None
    (row0, row1, col0, col1), free = room
    top, bottom, left, right = int(row.min()), int(row.max()), int(col.min()), int(col.max())
    last = 1 + (max(height, width) - 1) // settings.chunk * settings.chunk + settings.chunk
    live, first, size = np.arange(len(steps)), 1, settings.chunk
    blocked = torch.ones((), dtype=block.dtype, device=block.device)
    while first < last and len(live):
        distance = np.arange(first, min(first + size, last))
        dy = np.rint(distance[None] * steps[live, 1:]).astype(np.int64)        # (D, chunk)
        dx = np.rint(distance[None] * steps[live, :1]).astype(np.int64)
        r0, r1 = np.maximum(top + dy, row0), np.minimum(bottom + dy, row1)
        c0, c1 = np.maximum(left + dx, col0), np.minimum(right + dx, col1)
        meets = (r0 <= r1) & (c0 <= c1)             # the mark's box meets the room's box
        r0, r1, c0, c1 = (np.where(meets, v, 0) for v in (r0, r1, c0, c1))
        held = free[r1 + 1, c1 + 1] - free[r0, c1 + 1] - free[r1 + 1, c0] + free[r0, c0]
        spots = meets & (held > 0)                  # ... and holds a free pixel
        if spots.any():
            k, j = np.nonzero(spots)
            shift_y = torch.as_tensor(dy[k, j], device=pixel.device)[:, None]
            shift_x = torch.as_tensor(dx[k, j], device=pixel.device)[:, None]
            r, c = row + shift_y, col + shift_x                              # (spots, m)
            on = (r >= row0) & (r <= row1) & (c >= col0) & (c <= col1)
            covered = torch.where(on, block[(r * width + c).clamp(0, block.numel() - 1)], blocked)
            ok = ((covered * alpha).sum(-1) <= settings.clear * total).cpu().numpy()
            if ok.any():
                clear = np.zeros(spots.shape, dtype=bool)
                clear[k[ok], j[ok]] = True
                hit = np.where(clear.any(1), clear.argmax(1), len(distance))
                best = int(np.argmin(hit))
                return int(distance[hit[best]]), int(live[best])
        live = live[meets.any(1)]
        first += size
        if len(live) * 2 * size * len(alpha) <= settings.lookups:
            size *= 2
    return None


def resurface(p, place, optimizer, values, index, owner,
              c: ResurfaceSettings = ResurfaceSettings()) -> bool:
    """Lift the free marks buried in their stratum's obstacle back onto its surface and
    forget their Adam momentum. Returns whether any moved."""
    if p.terms.rests is None:   # no layer rests on another (the engine leaves it None)
        return False
    with torch.no_grad():
        center = place.transforms()[0].cpu().numpy().astype(float)
        lifts = buried(p.terms, values.detach(), index, owner, p.layer, center, movable(place),
                       p.grid.rho, c)
        for unit, (dx, dy) in lifts:
            place.t[unit, 0] += dx
            place.t[unit, 1] += dy
    if lifts:
        forget(optimizer, (place.t,), [unit for unit, _ in lifts])
    return bool(lifts)


class Resurface(Rule):
    """Each settle window (and each legalising round, run by ``legalize``), on stacks: free
    marks buried in their stratum's obstacle (a large mark of a lower layer rolled over them)
    are lifted back onto its surface; the flat obstacle gives them no gradient out. The
    settle then starts its patience afresh: the lifted marks have their own layer and those
    above to part. Needed by stacks whose layers differ in size."""

    name = "resurface"
    window = True
    reads = ("values", "index", "owner")
    writes = ("place", "optimizer", "best", "since_best")
    Settings = ResurfaceSettings

    def applies(self, s):
        return s.p.terms.rests is not None

    def __call__(self, s):
        if resurface(s.p, s.place, s.optimizer, s.values, s.index, s.owner, self.settings):
            s.best, s.since_best = math.inf, 0
            return True
        return False
