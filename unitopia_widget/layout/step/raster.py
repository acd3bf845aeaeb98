"""Differentiable patch rasterizer: marks -> per-pixel alpha samples.

Conventions
-----------
* Canvas coordinates are pixels, x right, y down. The raster has ``rho``
  raster pixels per canvas pixel and a border of ``pad`` raster pixels on
  every side, so a patch never leaves the raster: raster pixel ``(i, j)``
  (row, column) has its centre at canvas point
  ``((j - pad + 0.5) / rho, (i - pad + 0.5) / rho)``.
* Angles are radians, clockwise on screen (SVG ``rotate``).
* A sprite is an alpha image ``(h, w)`` spanning the mark's box exactly.

Each mark renders into a small patch around its centre: the pixel centres are
mapped through ``mark_from_canvas`` into sprite coordinates in ``[-1, 1]`` and
sampled bilinearly with ``grid_sample`` (differentiable in centre, angle and
extent). A mark wider than the largest patch side (``PATCH_SIDES[-1]``) is
sampled at a stride: one sample per ``s x s`` block of raster pixels, copied to
every pixel of the block, with ``s`` the least that fits the largest patch (its
texels are then several pixels wide anyway, so little is lost). Marks that share a sprite level and patch size form one group and one
``grid_sample`` call. The result is a flat list of samples: alpha value and
flat raster index, ready for ``index_add_``.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import torch
import torch.nn.functional as F

from .distance import edt

#: Patch sides (raster px) that groups are rounded up to: few groups, little waste.
PATCH_SIDES = (4, 6, 8, 10, 12, 14, 16, 20, 24, 28, 32, 40, 48, 56, 64, 80, 96,
               112, 128, 160, 192, 224, 256, 320, 384, 448, 512, 640, 768, 1024)
SPRITE_SIDE = 256  # long side of the finest sprite level, texels
#: Samples in a part from which its coordinates' backward is reduced once per mark
#: (``PatchCoords``): there the full-size passes of autograd's graph cost a tenth of an
#: iteration; smaller parts keep that graph, and their layouts their placements to the digit.
REDUCE_FROM = 65_536


def sprite_pyramid(alpha: np.ndarray, device, dtype=torch.float32,
                   keep_thin: bool = False) -> list[torch.Tensor]:
    """Box-filtered mip levels of one silhouette.

    ``alpha`` is ``(h, w)`` in [0, 1] with long side ``SPRITE_SIDE``. Returns
    tensors ``(1, 1, h_l, w_l)``, finest first, each level half the previous
    (area averaging keeps the rendered area exact), down to a long side of 4.
    ``keep_thin`` (for marks drawn with thin lines, see ``is_thin``, and
    hollow ones) keeps a line at least one texel wide and opaque on every level,
    so thin strokes that cross still collide instead of averaging away; an edge
    then lies up to half a texel out, so contacts keep that clear of the ink.
    """
    level = torch.as_tensor(np.ascontiguousarray(alpha), dtype=dtype, device=device)[None, None]
    levels = [level]
    while max(level.shape[-2:]) > 4:
        h, w = level.shape[-2:]
        # an exact box filter: F.interpolate(mode="area") overlaps its windows on odd sides,
        # which changed the area of a star's levels by 1 to 16%
        rows, cols = _box_filter(h, max(1, h // 2), level), _box_filter(w, max(1, w // 2), level)
        finer, level = level, rows @ level @ cols.T
        if keep_thin and min(h, w) >= 2:
            level = torch.maximum(level, F.max_pool2d(finer, 2)[..., :level.shape[-2], :level.shape[-1]])
        levels.append(level)
    return levels


def _box_filter(n_in: int, n_out: int, like: torch.Tensor) -> torch.Tensor:
    """``(n_out, n_in)``: output texel i averages the input span ``[i r, (i + 1) r)``, r = n_in / n_out."""
    r = n_in / n_out
    edges = torch.arange(n_out + 1, dtype=torch.float64) * r
    j = torch.arange(n_in, dtype=torch.float64)[None]
    overlap = (torch.minimum(edges[1:, None], j + 1) - torch.maximum(edges[:-1, None], j)).clamp_min(0)
    return (overlap / r).to(dtype=like.dtype, device=like.device)


def is_thin(alpha: np.ndarray, stroke: float = 0.1) -> bool:
    """Whether most of a silhouette ``(h, w)`` is lines thinner than ``stroke`` times its
    long side (a sketch, a line icon): opening by that width removes most of it."""
    ink = alpha >= 0.5
    r = max(1, int(round(stroke * max(alpha.shape) / 2)))
    # the opening by the disc of radius r as two distance transforms (a fifth of the time):
    # what lies over r from the background (the padding too), grown back by r
    eroded = edt(np.pad(ink, r + 1)) > r
    opened = edt(~eroded) <= r if eroded.any() else eroded
    return bool(opened.sum() < 0.5 * max(ink.sum(), 1))


@dataclass
class RasterGrid:
    """The raster the layout is evaluated on: ``(height, width)`` raster pixels incl. padding."""

    canvas: tuple[float, float]  # (width, height), canvas px
    rho: float                   # raster px per canvas px
    pad: int                     # raster px of border on each side

    @property
    def shape(self) -> tuple[int, int]:
        w, h = self.canvas
        return (math.ceil(h * self.rho) + 2 * self.pad, math.ceil(w * self.rho) + 2 * self.pad)

    @property
    def size(self) -> int:
        h, w = self.shape
        return h * w


def _patch_side(extent: np.ndarray, stride=1) -> np.ndarray:
    """Smallest entry of PATCH_SIDES >= extent / stride, times stride (raster px), elementwise.
    ``stride``: see ``_stride``; 1 fits every extent up to the largest entry."""
    sides = np.asarray(PATCH_SIDES)
    return sides[np.searchsorted(sides, np.asarray(extent) / stride, side="left")] * stride


def _stride(ext_w: np.ndarray, ext_h: np.ndarray) -> np.ndarray:
    """``(N,)`` int: the least sampling stride that fits each mark's longer extent
    (raster px) within the largest patch side."""
    return np.maximum(np.ceil(np.maximum(ext_w, ext_h) / PATCH_SIDES[-1]), 1).astype(int)


def patch_stride(ph: int, pw: int) -> int:
    """The sampling stride of a ``(ph, pw)`` patch: 1 up to the largest patch side, else the
    least integer that brings the long side within it (``group_keys`` made both sides
    multiples of it)."""
    return max(1, -(-max(ph, pw) // PATCH_SIDES[-1]))


def snap_rho(rho: float, half_w: np.ndarray, half_h: np.ndarray, rotating: bool,
             floor: float = 0.9) -> float:
    """A raster resolution in ``[floor * rho, rho]`` whose patches waste the fewest samples.

    ``half_w``, ``half_h``: ``(N,)`` half footprints, canvas px. Patch sides come
    in steps (``PATCH_SIDES``): a mark just over a step pays the next one, 1.5x
    the samples for equal circles; a slightly coarser raster lets it fit. Returns
    the finest resolution within 2% of the fewest samples.
    """
    half_w, half_h = np.asarray(half_w, float), np.asarray(half_h, float)
    reach = np.hypot(half_w, half_h)
    candidates = np.linspace(floor * rho, rho, 41)
    cost = []
    for r in candidates:
        ext_w = (2 * reach if rotating else 2 * half_w) * r + 2.0
        ext_h = (2 * reach if rotating else 2 * half_h) * r + 2.0
        if max(ext_w.max(), ext_h.max()) > PATCH_SIDES[-1]:
            return rho   # a strided patch: its sample count does not step with rho
        cost.append(float(np.sum(_patch_side(ext_w) * _patch_side(ext_h))))
    cost = np.asarray(cost)
    return float(candidates[cost <= 1.02 * cost.min()].max())


def group_keys(half_w: np.ndarray, half_h: np.ndarray, sprite_ids: np.ndarray,
               sprite_sides: list[int], rotating: np.ndarray, rho: float,
               sprite_aspects=None) -> np.ndarray:
    """``(N, 4)`` int: each mark's (sprite, level, patch_h, patch_w); see ``plan_groups``."""
    radius = np.hypot(half_w, half_h) * rho
    ext_w = np.where(rotating, 2 * radius, 2 * half_w * rho) + 2.0
    ext_h = np.where(rotating, 2 * radius, 2 * half_h * rho) + 2.0
    stride = _stride(ext_w, ext_h)
    pw, ph = _patch_side(ext_w, stride), _patch_side(ext_h, stride)
    sides = np.asarray(sprite_sides, dtype=float)[sprite_ids]
    # level l has sides / 2**l: texels per raster px at level 0, along the long side, or along
    # the axis that packs the most (a mark drawn stretched, by a width or height encoding,
    # packs more texels along its short side)
    if sprite_aspects is None:
        per_px = sides / np.maximum(2.0 * np.maximum(half_w, half_h) * rho, 1.0)
    else:
        aspect = np.asarray(sprite_aspects, dtype=float)[sprite_ids]
        per_px = np.maximum(sides * np.minimum(aspect, 1.0) / np.maximum(2 * half_w * rho, 1.0),
                            sides / np.maximum(aspect, 1.0) / np.maximum(2 * half_h * rho, 1.0))
    # the coarsest level that keeps a texel <= a pixel along the axis drawn at most texels per
    # pixel: finer, a point sample per pixel would skip the ink of a line thinner than a pixel
    level = np.floor(np.log2(np.maximum(per_px, 1.0))).astype(int)
    level = np.minimum(level, int(np.log2(max(sprite_sides) / 4)))   # the coarsest level is 4 texels
    return np.stack([sprite_ids, level, ph, pw], axis=1)


def plan_groups(half_w: np.ndarray, half_h: np.ndarray, sprite_ids: np.ndarray,
                sprite_sides: list[int], rotating: np.ndarray, rho: float, keys=None,
                sprite_aspects=None):
    """Group marks by (sprite, level, patch shape).

    ``half_w``, ``half_h``: ``(N,)`` half extents of each footprint, canvas px.
    ``sprite_ids``: ``(N,)`` index into the sprite pyramids.
    ``sprite_sides``: long side of each sprite's finest level, texels; ``sprite_aspects``:
    its width / height (None: the long side picks the level, as for a mark drawn unstretched).
    ``rotating``: ``(N,)`` bool; rotating marks get a square patch that holds
    any rotation, others a box patch. ``keys``: ``group_keys`` already computed.
    Returns a list of ``(indices, sprite_id, level, patch_h, patch_w)``.
    """
    key = group_keys(half_w, half_h, sprite_ids, sprite_sides, rotating, rho, sprite_aspects) \
        if keys is None else keys
    # one integer per key (each column is small and non-negative): a 1-D unique is cheap
    code = ((key[:, 0].astype(np.int64) * 64 + key[:, 1]) * 2 ** 20 + key[:, 2]) * 2 ** 20 + key[:, 3]
    uniq, first, inverse = np.unique(code, return_index=True, return_inverse=True)
    order = np.argsort(inverse, kind="stable")
    bounds = np.searchsorted(inverse[order], np.arange(len(uniq) + 1))
    return [(order[bounds[g]:bounds[g + 1]], *(int(v) for v in key[first[g]]))
            for g in range(len(uniq))]


class RenderPlan:
    """The groups of ``plan_groups`` prepared on the device for ``render_samples``.

    ``parts``: one per ``grid_sample`` call, ``(indices (n,) long, sprite id or
    (n,) sprite tensor for an atlas, level, ph, pw)``; ``owner (M,)``: the mark
    of each sample, in render order. A plan stays valid while no mark changes
    group (``Planner``), so nothing here is rebuilt every iteration.
    """

    def __init__(self, groups, pyramids, device, grid: RasterGrid):
        from .atlas import SpriteAtlas

        self.atlas = pyramids if isinstance(pyramids, SpriteAtlas) else None
        height, width = grid.shape
        self.parts = []
        for idx, sprite, level, ph, pw in (self.atlas.merge(groups) if self.atlas else groups):
            if self.atlas is not None:
                sprite = sprite.to(device)
            self.parts.append(_Part(torch.as_tensor(idx, device=device), sprite, level, ph, pw,
                                    device, width, height))
        self.owner = torch.cat([part.idx.repeat_interleave(part.ph * part.pw) for part in self.parts])

    @functools.cached_property
    def patches(self) -> tuple:
        """``(first, ph, pw, unit, whole)``, each ``(K,)`` over the plan's marks in render
        order: the sample its patch starts with (its origin pixel, unless ``whole``: a patch
        overhanging the raster, whose samples are clamped onto it), its patch rows and
        columns, and its unit."""
        sizes = [(part.ph, part.pw, len(part.idx), part.overhangs) for part in self.parts]
        dev = self.owner.device
        count = torch.tensor([ph * pw for ph, pw, n, _ in sizes for _ in range(n)], device=dev)
        first = torch.cumsum(count, 0) - count
        ph = torch.tensor([ph for ph, _, n, _ in sizes for _ in range(n)], device=dev)
        pw = torch.tensor([pw for _, pw, n, _ in sizes for _ in range(n)], device=dev)
        whole = torch.tensor([over for *_, n, over in sizes for _ in range(n)], device=dev,
                             dtype=torch.bool)
        unit = torch.cat([part.idx for part in self.parts])
        return first, ph, pw, unit, whole


class _Part:
    """One ``grid_sample`` call: its marks ``idx (n,)``, sprite, level and patch ``(ph, pw)``,
    with the patch's fixed tensors: sample points ``u (pw / stride,)``, ``v (ph / stride,)``
    (raster px from the patch origin: pixel centres, or the centres of ``stride x stride``
    blocks, see ``patch_stride``), ``offsets (ph * pw,)`` int32 flat raster offsets, ``size``
    and the largest origin ``limit`` (x, y)."""

    def __init__(self, idx, sprite, level, ph, pw, device, width, height):
        self.idx, self.sprite, self.level, self.ph, self.pw = idx, sprite, level, ph, pw
        self.stride = s = patch_stride(ph, pw)
        self.u = (torch.arange(pw // s, device=device, dtype=torch.float32) + 0.5) * s
        self.v = (torch.arange(ph // s, device=device, dtype=torch.float32) + 0.5) * s
        rows, cols = torch.arange(ph, device=device), torch.arange(pw, device=device)
        self.offsets = (rows[:, None] * width + cols[None, :]).reshape(-1).to(torch.int32)
        self.size = torch.tensor([pw, ph], device=device, dtype=torch.float32)
        self.limit = torch.tensor([width, height], device=device, dtype=torch.float32) - self.size
        self.overhangs = ph > height or pw > width


class Planner:
    """Builds a ``RenderPlan`` when the marks' groups change, and reuses it otherwise."""

    def __init__(self, sprite_ids, sprite_sides, rotating, pyramids, grid: RasterGrid, device,
                 sprite_aspects=None):
        self.args = (sprite_ids, sprite_sides, rotating, sprite_aspects)
        self.pyramids, self.grid, self.device = pyramids, grid, device
        self.keys, self.current, self.last = None, None, None

    def plan_for(self, half_w: np.ndarray, half_h: np.ndarray) -> RenderPlan:
        """The plan for footprints ``half_w``, ``half_h`` ``(N,)`` canvas px (host arrays);
        footprints equal to the last call's (scales that did not move) keep it unchecked."""
        if self.last is not None and np.array_equal(half_w, self.last[0]) \
                and np.array_equal(half_h, self.last[1]):
            return self.current
        self.last = (np.array(half_w), np.array(half_h))
        sprite_ids, sides, rotating, aspects = self.args
        keys = group_keys(half_w, half_h, sprite_ids, sides, rotating, self.grid.rho, aspects)
        if self.keys is None or not np.array_equal(keys, self.keys):
            groups = plan_groups(half_w, half_h, sprite_ids, sides, rotating, self.grid.rho, keys)
            self.keys, self.current = keys, RenderPlan(groups, self.pyramids, self.device, self.grid)
        return self.current


def sprite_coords(shift, a, b, d, e, u, v, out=None) -> tuple:
    """``(gx, gy)`` ``(n, ph, pw)``: the sprite coordinates of ``PatchCoords`` (see there for
    the arguments) through autograd's own graph; with ``out`` ``(2, n, ph, pw)``, written
    into it, and ``(dx (n, 1, pw), dy (n, ph, 1))`` returned instead."""
    dx = (shift[:, 0:1] + u)[:, None, :]                                    # (n, 1, pw)
    dy = (shift[:, 1:2] + v)[:, :, None]                                    # (n, ph, 1)
    # the (n, 1, pw) and (n, ph, 1) factors are small: one full-size operation a coordinate
    a, b, d, e = (k[:, None, None] for k in (a, b, d, e))
    if out is None:
        return dx * a + dy * b, dy * d - dx * e
    torch.add(dx * a, dy * b, out=out[0])
    torch.sub(dy * d, dx * e, out=out[1])
    return dx, dy


class PatchCoords(torch.autograd.Function):
    """``PatchCoords.apply(shift, a, b, d, e, u, v)`` -> ``(2, n, ph, pw)``: the sprite
    coordinates of a part's samples, ``gx = dx a + dy b`` and ``gy = dy d - dx e`` with
    ``dx = shift_x + u``, ``dy = shift_y + v`` (raster px from each mark's centre), written
    in front of each other as ``grid_sample`` reads them.

    ``shift (n, 2)`` raster px from each centre to its patch origin; ``a, b, d, e (n,)``
    the mark's cos / sx, sin / sx, cos / sy, sin / sy (sx, sy its half extents in raster
    px); ``u (pw,)``, ``v (ph,)`` the sample points (constants). The backward reduces the
    coordinates' gradient once per mark: a shift moves every sample of the mark alike,
    where autograd made and summed a full-size product per term."""

    @staticmethod
    def forward(ctx, shift, a, b, d, e, u, v):
        out = shift.new_empty(2, len(shift), len(v), len(u))
        dx, dy = sprite_coords(shift, a, b, d, e, u, v, out=out)
        ctx.save_for_backward(dx[:, 0], dy[:, :, 0], a, b, d, e)
        return out

    @staticmethod
    def backward(ctx, grad):
        dx, dy, a, b, d, e = ctx.saved_tensors
        g = grad.permute(1, 2, 3, 0)                      # (n, ph, pw, 2), as grid_sample wrote it
        total = g.reshape(len(dx), -1, 2).sum(1)          # (n, 2): each mark's sums of d/dgx, d/dgy
        gx, gy = total[:, 0], total[:, 1]
        shift = torch.stack([a * gx - e * gy, b * gx + d * gy], 1) if ctx.needs_input_grad[0] else None
        da = db = dd = de = None
        if any(ctx.needs_input_grad[1:5]):   # a turning or growing mark: weighted by dx, dy
            cols, rows = g.sum(1), g.sum(2)               # (n, pw, 2), (n, ph, 2)
            da, de = (cols[..., 0] * dx).sum(1), -(cols[..., 1] * dx).sum(1)
            db, dd = (rows[..., 0] * dy).sum(1), (rows[..., 1] * dy).sum(1)
        return shift, da, db, dd, de, None, None


def render_samples(center: torch.Tensor, angle: torch.Tensor, half_w: torch.Tensor,
                   half_h: torch.Tensor, groups, pyramids, grid: RasterGrid):
    """Alpha samples of every mark's footprint.

    ``center``: ``(N, 2)`` canvas px; ``angle``: ``(N,)`` radians;
    ``half_w``, ``half_h``: ``(N,)`` canvas px. All may carry gradients.
    ``groups``: a ``RenderPlan`` or the list ``plan_groups`` returns.
    ``pyramids`` is a list of sprite pyramids or a ``SpriteAtlas`` of them (then
    groups that differ only in their sprite render in one call).
    Returns ``values (M,)`` (alpha, differentiable), ``index (M,)`` (flat
    raster index, int32) and ``owner (M,)`` (the mark of each sample, long).
    """
    plan = groups if isinstance(groups, RenderPlan) else RenderPlan(groups, pyramids, center.device, grid)
    rho, pad = grid.rho, grid.pad
    height, width = grid.shape
    values, indices = [], []
    cos_all, sin_all = torch.cos(angle), torch.sin(angle)
    for part in plan.parts:
        idx, ph, pw = part.idx, part.ph, part.pw
        c = center[idx] * rho + pad                                     # (n, 2) raster px
        # patches stay on the raster; a mark beyond the border is cut off there
        origin = torch.minimum(torch.clamp(torch.floor(c.detach() - part.size / 2), min=0), part.limit)
        shift = origin - c
        cos, sin = cos_all[idx], sin_all[idx]
        sx, sy = rho * half_w[idx], rho * half_h[idx]
        # sprite coordinates in [-1, 1]
        scales = (cos / sx, sin / sx, cos / sy, sin / sy)
        if plan.atlas is None:
            # (2, n, ph, pw) viewed as (n, ph, pw, 2): grid_sample reads strided grids, and
            # interleaving the two coordinates in memory would cost more than the sampling
            coords = PatchCoords.apply(shift, *scales, part.u, part.v) if len(idx) * ph * pw >= REDUCE_FROM \
                else torch.stack(sprite_coords(shift, *scales, part.u, part.v))
            sprite, sample_grid = pyramids[part.sprite][part.level], coords.permute(1, 2, 3, 0)
        else:   # part.sprite: (n,) the sprite of each mark, tiles of one texture, each
            # coordinate mapped on its own (autograd's graph: no stacked gradient to split)
            gx, gy = sprite_coords(shift, *scales, part.u, part.v)
            sprite, sample_grid = plan.atlas.grid(part.level, part.sprite, gx, gy)
        alpha = F.grid_sample(sprite, sample_grid.reshape(1, -1, pw // part.stride, 2),
                              mode="bilinear", padding_mode="zeros",
                              align_corners=False)   # (1, 1, n*ph, pw) / stride
        if part.stride > 1:   # each sample covers its block of stride x stride pixels
            s = part.stride
            alpha = alpha.reshape(-1, ph // s, pw // s).repeat_interleave(s, 1).repeat_interleave(s, 2)
            alpha = alpha.reshape(1, 1, -1, pw)
        o = origin.to(torch.int32)
        if part.overhangs:
            # a patch larger than the raster overhangs it: drop the samples off the raster
            rows = o[:, 1, None] + torch.arange(ph, device=o.device, dtype=torch.int32)   # (n, ph)
            cols = o[:, 0, None] + torch.arange(pw, device=o.device, dtype=torch.int32)   # (n, pw)
            on = ((rows >= 0) & (rows < height))[:, :, None] & ((cols >= 0) & (cols < width))[:, None, :]
            alpha = alpha * on.reshape(1, 1, -1, pw).to(alpha.dtype)
            rows, cols = rows.clamp(0, height - 1), cols.clamp(0, width - 1)
            flat = rows[:, :, None] * width + cols[:, None, :]                        # (n, ph, pw)
        else:
            flat = (o[:, 1] * width + o[:, 0])[:, None] + part.offsets[None, :]       # (n, ph * pw)
        values.append(alpha.reshape(-1))
        indices.append(flat.reshape(-1))
    if len(values) == 1:
        return values[0], indices[0], plan.owner
    return torch.cat(values), torch.cat(indices), plan.owner

def accumulate(values: torch.Tensor, index: torch.Tensor, size: int) -> torch.Tensor:
    """Coverage image: the sum of all samples per raster pixel, ``(size,)``."""
    coverage = torch.zeros(size, dtype=values.dtype, device=values.device)
    return coverage.index_add_(0, index, values)
