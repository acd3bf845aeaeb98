"""Strata: a layer pulled by forces rests on the layers it blocks on, as sediment does.

Its obstacle is their ink swept along its force (their *shadow*): each pixel holds the ink
met from it against the pull, summed up to one full pixel (``accumulate``), so everything between
their ink and where the force pulls is taken, and its marks cannot sift into the gaps
between larger marks. (The running sum, not the running maximum: the two agree but on the
antialiased rims of the envelope, where the sum is full a pixel or so sooner, and the sum
is a plain scan, several times faster than a maximum that keeps its indices.)

* Directional forces: the sweep runs down the raster axis nearest the sum of the forces
  (for a downward force, everything below the other layers' upper envelope).
* Point forces: the sweep runs radially in to the point; a pixel at radius ``r`` and angle
  ``a`` holds the ink at that angle at radius ``r`` and beyond (everything inside the
  other layers' outer envelope around the point), so the layer rests outside them in
  rings. With several points each pixel is swept in to the point that pulls it (the nearest,
  weighted by strength, as in ``forces.potential``), seeing the ink that point pulls and the
  ink within a *band* past the border of its cell (the largest footprint radius of the layers
  rested on): where piles grow into one another, the gaps on the border between them are
  blocked as the gaps inside a pile are.

A layer pulled by both kinds of force, or by none, sees the ink itself.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import torch
import torch.nn.functional as F

from ...design.forces import PointForce, net_pull

RAY_STEP = 1.0     # raster px between samples along a ray
RAY_SPACING = 2.0  # raster px between neighbouring rays at the farthest pixel, at most
MAX_RAYS = 2048    # rays per point at most (the spacing widens beyond, on huge rasters)


def sweep_of(forces, band: float = 0.0):
    """The sweep of a layer pulled by ``forces``: ``(dim, reverse)`` for directional forces
    (``shadow``'s raster axis nearest their sum), a ``Radial`` for point forces (``band``:
    see ``Radial``), None for a mix of both or no pull."""
    if not forces:
        return None
    if all(isinstance(f, PointForce) for f in forces):
        pull = tuple((f.x, f.y, f.strength) for f in forces if f.strength > 0)
        return Radial(pull, band) if pull else None
    net = net_pull(forces)
    if net is None or max(abs(net[0]), abs(net[1])) < 1e-9:
        return None
    vx, vy = net
    return (0, vy < 0) if abs(vy) >= abs(vx) else (1, vx < 0)


SCAN_BLOCK = 16    # elements summed by one small matrix product in a scan across memory


def accumulate(ink: torch.Tensor, dim: int) -> torch.Tensor:
    """``ink (..., n, ...)`` swept towards higher indices of ``dim``: each element holds the
    ink at or before it, summed, up to 1 (nonnegative ``ink``, at most 1 per element).

    Along memory (the last dim) a plain ``cumsum``. Across memory (a sweep down the raster's
    columns) ``cumsum`` runs several times slower on a CPU, so the scan is blocked: the sums
    within each ``SCAN_BLOCK`` elements are one product with a lower-triangular matrix, and
    each block then adds the running total of the blocks before it (the same sums, rounded
    in another order: within about 1e-7 of ``cumsum``)."""
    if dim % ink.dim() == ink.dim() - 1:
        return torch.cumsum(ink, dim).clamp_(max=1.0)
    x = ink.movedim(dim, -2)
    *lead, n, w = x.shape
    pad = -n % SCAN_BLOCK
    if pad:
        x = F.pad(x, (0, 0, 0, pad))
    tri = torch.ones(SCAN_BLOCK, SCAN_BLOCK, dtype=ink.dtype, device=ink.device).tril_()
    part = torch.matmul(tri, x.reshape(*lead, (n + pad) // SCAN_BLOCK, SCAN_BLOCK, w))
    before = part[..., -1, :].cumsum(-2)                    # running total at each block's end
    part[..., 1:, :, :] += before[..., :-1, None, :]
    return part.reshape(*lead, n + pad, w)[..., :n, :].clamp_(max=1.0).movedim(-2, dim)


def shadow(ink: torch.Tensor, dim: int, reverse: bool) -> torch.Tensor:
    """``ink (..., H, W)`` swept along raster ``dim`` (0 rows, 1 columns; towards higher
    indices, or lower when ``reverse``), see ``accumulate``. Leading dimensions are slabs swept
    alike, in one scan."""
    axis = dim - 2
    return accumulate(ink.flip(axis), axis).flip(axis) if reverse else accumulate(ink, axis)


@dataclass(frozen=True)
class Radial:
    """The radial sweep of point forces ``points``: ``(x, y, strength)`` canvas px; each
    point's sweep sees the ink up to ``band`` canvas px past the border of its cell."""

    points: tuple
    band: float = 0.0

    def _pull(self, xy: np.ndarray) -> np.ndarray:
        """``(n, K)`` each point's pull distance (strength-weighted) to ``xy (n, 2)`` canvas px."""
        p = np.asarray(self.points, float)
        dist = np.hypot(xy[:, None, 0] - p[None, :, 0], xy[:, None, 1] - p[None, :, 1])
        return dist * p[None, :, 2]

    def pulling(self, xy: np.ndarray) -> np.ndarray:
        """``(n,)`` index of the point that pulls each of ``xy (n, 2)`` canvas px."""
        return np.argmin(self._pull(xy), axis=1)

    def seeing(self, xy: np.ndarray, reach=0.0) -> np.ndarray:
        """``(n, K)`` bool: whether each point's sweep sees ``xy (n, 2)`` canvas px (or a disc
        there of radius ``reach (n,)``): the point pulls it, or it lies within ``band`` px
        past the border of the point's cell (the pull distances differ by twice that across
        the border between two points)."""
        pull = self._pull(xy)
        near = pull - pull.min(1, keepdims=True) < 2 * (self.band + np.reshape(reach, (-1, 1))) \
            * np.asarray(self.points, float)[None, :, 2]
        return near | (np.arange(pull.shape[1])[None] == np.argmin(pull, axis=1)[:, None])

    def on(self, shape, rho: float, pad: int, device) -> "RadialShadow":
        """The sweep on a raster of ``shape (H, W)`` px, ``rho`` raster px per canvas px and
        ``pad`` px of border (``RasterGrid``'s pixel centres)."""
        return RadialShadow(self, tuple(shape), rho, pad, torch.device(device))


class RadialShadow:
    """``shadow(ink (H, W)) -> (H, W)``: ink swept in to the points of a ``Radial``.

    The ink is resampled onto rays from each point (``grid_sample``, ``RAY_STEP`` px apart
    along a ray, at most ``RAY_SPACING`` px apart across), swept in along each ray (a
    reversed ``accumulate``), and resampled back: each pixel reads its own point's rays. Samples
    on a point's rays that it does not see (``Radial.seeing``) read no ink. The sampling
    grids are made once. Only the ray samples that can read ink are taken (the point sees
    them, and their bilinear taps reach the raster: about half of the rays' disc, which
    reaches the raster's farthest corner); they are written into a kept buffer of the rays,
    stored from the far end in, whose other samples stay 0. Called with ``at``, the swept
    ink is resampled at those pixels alone (the loss reads it at its samples only).
    """

    def __init__(self, radial: Radial, shape, rho: float, pad: int, device):
        h, w = shape
        self.shape, self.radial = shape, radial
        # canvas px -> continuous raster pixel index (pixel centres at integers)
        to_px = lambda x, y: (x * rho + pad - 0.5, y * rho + pad - 0.5)   # noqa: E731
        corners = np.array([[-0.5, -0.5], [w - 0.5, -0.5], [-0.5, h - 0.5], [w - 0.5, h - 0.5]])
        centres = np.array([to_px(x, y) for x, y, _ in radial.points])        # (K, 2) u, v
        reach = float(np.hypot(*(corners[None] - centres[:, None]).transpose(2, 0, 1)).max())
        n_r = max(int(math.ceil(reach / RAY_STEP)) + 1, 2)
        n_a = int(min(max(math.ceil(2 * math.pi * reach / RAY_SPACING), 8), MAX_RAYS))
        self.rays = n_a + 1                       # the last ray is the first again (angle 2 pi)
        angle = torch.arange(self.rays, dtype=torch.float64) * (2 * math.pi / n_a)
        radius = torch.linspace(0.0, reach, n_r, dtype=torch.float64)
        grids, owned = [], []
        for k, (cu, cv) in enumerate(centres):
            u = cu + torch.cos(angle)[:, None] * radius[None]                 # (rays, n_r)
            v = cv + torch.sin(angle)[:, None] * radius[None]
            grids.append(torch.stack([u / max(w - 1, 1) * 2 - 1, v / max(h - 1, 1) * 2 - 1], -1))
            canvas = np.stack([(u.numpy() - pad + 0.5) / rho, (v.numpy() - pad + 0.5) / rho], -1)
            owned.append(torch.from_numpy(radial.seeing(canvas.reshape(-1, 2))[:, k])
                         .reshape(u.shape))
        grid = torch.cat(grids).flip(1)         # (K rays, n_r, 2): each ray from its far end in
        u, v = ((grid[..., i] + 1) / 2 * (n - 1) for i, n in ((0, w), (1, h)))
        taps = (u > -1.5) & (u < w + 0.5) & (v > -1.5) & (v < h + 0.5)   # beyond, all four read 0
        kept = (torch.cat(owned).flip(1) & taps).reshape(-1)
        self.kept = torch.nonzero(kept).reshape(-1).to(device)               # (k,) into the rays
        self.to_kept = grid.reshape(-1, 2)[kept][None, None].float().to(device)   # (1, 1, k, 2)
        self.n_r = n_r
        self._rays = {}                         # (dtype, device) -> (K rays * n_r,) buffer
        # every pixel back to its own point's rays: (angle, radius) -> the rays' image
        vv, uu = torch.meshgrid(torch.arange(h, dtype=torch.float64),
                                torch.arange(w, dtype=torch.float64), indexing="ij")
        canvas = np.stack([(uu.numpy() - pad + 0.5) / rho, (vv.numpy() - pad + 0.5) / rho], -1)
        k = torch.from_numpy(radial.pulling(canvas.reshape(-1, 2)).reshape(h, w))
        cu, cv = (torch.from_numpy(centres[:, i])[k] for i in (0, 1))
        a = torch.atan2(vv - cv, uu - cu) % (2 * math.pi)
        row = k * self.rays + a / (2 * math.pi) * n_a                        # ray image row
        total = len(centres) * self.rays
        x = torch.hypot(uu - cu, vv - cv) / reach * 2 - 1
        self.to_pixels = torch.stack([x, row / max(total - 1, 1) * 2 - 1], -1)[None] \
            .float().to(device)                                               # (1, H, W, 2)

    def __call__(self, ink: torch.Tensor, at: torch.Tensor | None = None,
                 out: bool = False) -> torch.Tensor:
        """``ink (H, W)`` swept in to the points (``out``: out from them, each pixel holding
        the ink at its angle at its radius and nearer): ``(H, W)``, or ``(k,)`` at the flat
        pixel indices ``at (k,)`` long."""
        key = (ink.dtype, ink.device)
        if key not in self._rays:
            self._rays[key] = ink.new_zeros(len(self.radial.points) * self.rays * self.n_r)
        rays = self._rays[key]
        on_kept = F.grid_sample(ink[None, None], self.to_kept.to(ink.dtype), mode="bilinear",
                                padding_mode="zeros", align_corners=True)
        rays.index_copy_(0, self.kept, on_kept.reshape(-1))
        # in to the point: the rays run from their far end, so a plain scan, then turned back;
        # out from it: turned first
        rays = rays.view(1, 1, -1, self.n_r)
        swept = accumulate(rays.flip(-1), -1) if out else accumulate(rays, -1).flip(-1)
        grid = self.to_pixels if at is None else self.to_pixels.view(-1, 2).index_select(0, at)[None, None]
        back = F.grid_sample(swept, grid.to(ink.dtype), mode="bilinear", padding_mode="border",
                             align_corners=True)
        return back[0, 0] if at is None else back.reshape(-1)

    def onto(self, obstacle: torch.Tensor, ink: torch.Tensor, slabs, flat: torch.Tensor,
             add: bool) -> None:
        """Write (``add``: add) the shadow of each ``ink (R, H * W)`` row into ``obstacle
        (M,)`` at the samples of ``flat (M,)`` (indices into stacked ``(H, W)`` slabs) in its
        slab of ``slabs (R,)``."""
        size = self.shape[0] * self.shape[1]
        for one, a in zip(ink, slabs):
            mine = torch.nonzero((flat >= a * size) & (flat < (a + 1) * size)).reshape(-1)
            swept = self(one.view(self.shape), at=flat.index_select(0, mine) - a * size)
            (obstacle.index_add_ if add else obstacle.index_copy_)(0, mine, swept)


def swept_along(sweep, ink: torch.Tensor, back: bool = False) -> torch.Tensor:
    """``ink (..., H, W)`` swept along ``sweep``: a raster axis ``(dim, reverse)`` (``shadow``)
    or a ``RadialShadow`` (made for one ``(H, W)`` slab: each slab in turn); ``back``: against
    it (up the axis, out from the points), over what lies beyond the ink."""
    if isinstance(sweep, RadialShadow):
        return torch.stack([sweep(one, out=back) for one in ink.reshape(-1, *sweep.shape)]) \
            .view(ink.shape)
    dim, reverse = sweep
    return shadow(ink, dim, reverse != back)


def shadow_distance(xy: np.ndarray, sweep, centers: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """``(n,)`` signed distance (canvas px, negative inside) from ``xy (n, 2)`` to the shadow
    that discs ``centers (k, 2)``, ``radii (k,)`` cast along ``sweep`` (``sweep_of``): each
    disc swept down a raster axis without end, or radially in to the point that pulls it
    (``cone_distance``), and in to each other point that sees it within its cell
    (``Radial.seeing``); inf without discs."""
    out = np.full(len(xy), np.inf)
    if isinstance(sweep, Radial):
        points = np.asarray(sweep.points, float)[:, :2]
        owner, seen = sweep.pulling(centers), sweep.seeing(centers, radii)
        cell = sweep.pulling(xy) if seen.sum() > len(centers) else None
        for c, r, k, sees in zip(centers, radii, owner, seen):
            np.minimum(out, cone_distance(xy, c, r, points[k]), out=out)
            for j in np.nonzero(sees)[0]:
                if j != k:
                    cone = cone_distance(xy, c, r, points[j])
                    np.minimum(out, np.where(cell == j, cone, np.inf), out=out)
        return out
    dim, reverse = sweep
    d = np.zeros(2)
    d[1 - dim] = -1.0 if reverse else 1.0   # raster dim 0 is y, dim 1 is x
    for c, r in zip(centers, radii):
        rel = xy - c
        along = np.maximum(rel @ d, 0.0)[:, None]
        np.minimum(out, np.hypot(*(rel - along * d).T) - r, out=out)
    return out


def cone_distance(xy: np.ndarray, center: np.ndarray, r: float, point: np.ndarray) -> np.ndarray:
    """``(n,)`` signed distance (canvas px, negative inside) from ``xy (n, 2)`` to the radial
    shadow of the disc ``center (2,)``, ``r`` on ``point (2,)``: the convex hull of the disc
    and the point (a cone with a rounded end; the disc itself when it covers the point)."""
    axis = np.asarray(center, float) - point
    h = float(np.hypot(*axis))
    rel = xy - point
    if h <= r:
        return np.hypot(*(xy - center).T) - r
    e = axis / h
    along, across = rel @ e, np.abs(rel @ np.array([-e[1], e[0]]))
    b = -r / h                      # the cone's side: sin of its half angle, negated
    a = math.sqrt(1.0 - b * b)
    k = across * -b + along * a     # where the side's normal splits the point, side and disc
    side = across * a + along * b
    return np.where(k < 0, np.hypot(along, across),
                    np.where(k > a * h, np.hypot(along - h, across) - r, side))
