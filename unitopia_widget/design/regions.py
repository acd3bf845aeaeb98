"""Scanline rasterisation of container regions into anti-aliased coverage.

Conventions: canvas pixels, x right, y down. A raster of ``(H, W)`` pixels at
``rho`` raster pixels per canvas pixel puts pixel ``(i, j)`` over canvas
``[j/rho, (j+1)/rho] x [i/rho, (i+1)/rho]``.

A region is cut by horizontal *sample lines* (:class:`Rows`). Each line stands
for a horizontal band of one raster row; on it the region is a set of exact
x-intervals (*spans*), assumed to hold over the whole band. Coverage is then
exact in x and a midpoint rule in y: lines 1/16 of a raster pixel apart for
vector shapes, or one line per (raster row, image row) overlap for masks,
which makes masks exact.

Regions enter as *events* on the lines: even-odd toggles ``(line, x)`` for the
shape (polygon edge crossings, ellipse and rectangle sides, mask run ends) and
depth changes ``(line, x, +1 | -1)`` for eraser strokes, which are removed.

Also here: the geometry sources feeding those events, i.e. SVG path data
flattened to rings, and image pixels turned into masks (the threshold / alpha
rule and the magic wand).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np
from scipy import ndimage
from svgpathtools import parse_path

SUBROWS = 16            # sample lines per raster row for vector shapes
CURVE_TOLERANCE = 0.01  # canvas px: largest distance from a curve to its polyline
EXACT_INTERSECTIONS = 600  # exact even-odd area splits at edge crossings up to this many edges


@dataclass(frozen=True)
class Rows:
    """Sample lines: canvas ``y`` (R,), band ``[lo, hi)`` (R,), raster row index (R,)."""

    y: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    raster: np.ndarray


def subrows(n_raster: int, rho: float, per_row: int = SUBROWS) -> Rows:
    """``per_row`` evenly spaced lines in each of ``n_raster`` raster rows."""
    k = np.arange(n_raster * per_row, dtype=np.float64)
    step = 1.0 / (rho * per_row)
    return Rows(y=(k + 0.5) * step, lo=k * step, hi=(k + 1) * step,
                raster=np.arange(n_raster * per_row) // per_row)


def band_rows(n_raster: int, rho: float, top: float, height: float, n_bands: int) -> Rows:
    """One line per overlap of a raster row with one of ``n_bands`` equal bands
    tiling canvas ``[top, top + height)`` (the rows of an image mask)."""
    bottom = n_raster / rho
    edges = top + np.arange(n_bands + 1) * (height / n_bands)
    edges = edges[(edges > 0) & (edges < bottom)]
    cuts = np.unique(np.concatenate([np.arange(n_raster + 1) / rho, edges,
                                     np.clip([top, top + height], 0, bottom)]))
    lo, hi = cuts[:-1], cuts[1:]
    keep = (hi - lo > 1e-12) & (lo >= top) & (hi <= top + height)
    lo, hi = lo[keep], hi[keep]
    mid = (lo + hi) / 2
    raster = np.clip(np.floor(mid * rho).astype(np.int64), 0, n_raster - 1)
    return Rows(y=mid, lo=lo, hi=hi, raster=raster)


def _expand(start: np.ndarray, stop: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For items with line ranges ``[start, stop)``: (item index, line index) pairs."""
    counts = np.maximum(stop - start, 0)
    item = np.repeat(np.arange(len(counts)), counts)
    offsets = np.cumsum(counts) - counts
    line = start[item] + np.arange(counts.sum()) - offsets[item]
    return item, line


def _lines_between(ys: np.ndarray, lo, hi, closed: bool = False):
    """Index ranges of sorted ``ys`` with lo <= y < hi (lo <= y <= hi if ``closed``)."""
    return (np.searchsorted(ys, lo, "left"),
            np.searchsorted(ys, hi, "right" if closed else "left"))


def ring_edges(rings: list[np.ndarray]) -> np.ndarray:
    """Edges (E, 2, 2) of closed rings, each ring (k, 2) closed implicitly."""
    return np.concatenate([np.stack([r, np.roll(r, -1, axis=0)], axis=1) for r in rings])


def crossings(edges: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where edges (E, 2, 2) cross the sorted lines ``ys``: (line index, x).

    Half-open in y (an edge owns ``min_y <= y < max_y``), so every closed ring
    crosses every line an even number of times.
    """
    x0, y0, x1, y1 = edges[:, 0, 0], edges[:, 0, 1], edges[:, 1, 0], edges[:, 1, 1]
    sloped = y0 != y1
    x0, y0, x1, y1 = x0[sloped], y0[sloped], x1[sloped], y1[sloped]
    item, line = _expand(*_lines_between(ys, np.minimum(y0, y1), np.maximum(y0, y1)))
    t = (ys[line] - y0[item]) / (y1[item] - y0[item])
    return line, x0[item] + t * (x1[item] - x0[item])


def rect_events(x, y, w, h, ys):
    """Toggles of the rectangle ``[x, x + w] x [y, y + h)`` on lines ``ys``."""
    start, stop = _lines_between(ys, y, y + h)
    line = np.arange(start, stop)
    return np.repeat(line, 2), np.tile([x, x + w], len(line))


def ellipse_events(cx, cy, rx, ry, ys):
    """Toggles of the ellipse with centre (cx, cy) and radii (rx, ry)."""
    start, stop = _lines_between(ys, cy - ry, cy + ry)
    line = np.arange(start, stop)
    half = rx * np.sqrt(np.clip(1.0 - ((ys[line] - cy) / ry) ** 2, 0.0, 1.0))
    return np.repeat(line, 2), np.stack([cx - half, cx + half], axis=1).ravel()


def mask_events(mask: np.ndarray, box, ys):
    """Toggles of a boolean mask (h, w) stretched over ``box = (x, y, w, h)``:
    the ends of the inside runs of the mask row under each line."""
    bx, by, bw, bh = box
    h, w = mask.shape
    edge = np.diff(np.pad(mask, ((0, 0), (1, 1))).astype(np.int8), axis=1)  # (h, w + 1)
    run_row, run_start = np.nonzero(edge == 1)
    run_stop = np.nonzero(edge == -1)[1]
    first = np.searchsorted(run_row, np.arange(h + 1))         # CSR offsets per mask row
    k = np.floor((ys - by) / bh * h).astype(np.int64)
    valid = (k >= 0) & (k < h)
    lines = np.nonzero(valid)[0]
    k = k[valid]
    item, run = _expand(first[k], first[k + 1])
    line = lines[item]
    xs = np.stack([bx + run_start[run] * (bw / w), bx + run_stop[run] * (bw / w)], axis=1)
    return np.repeat(line, 2), xs.ravel()


def stroke_events(points: np.ndarray, width: float, ys):
    """Depth changes of a round-capped stroke along polyline ``points`` (k, 2):
    (line index, x, +1 at the left end | -1 at the right end) per capsule."""
    r = width / 2
    p0 = points[:-1] if len(points) > 1 else points
    p1 = points[1:] if len(points) > 1 else points
    item, line = _expand(*_lines_between(ys, np.minimum(p0[:, 1], p1[:, 1]) - r,
                                         np.maximum(p0[:, 1], p1[:, 1]) + r, closed=True))
    a, b, y = p0[item], p1[item], ys[line]
    left = np.full(len(line), np.inf)
    right = np.full(len(line), -np.inf)
    for c in (a, b):  # the round caps
        dy2 = (y - c[:, 1]) ** 2
        half = np.sqrt(np.maximum(r * r - dy2, 0.0))
        hit = dy2 <= r * r
        left = np.where(hit, np.minimum(left, c[:, 0] - half), left)
        right = np.where(hit, np.maximum(right, c[:, 0] + half), right)
    lo, hi = _band_interval(a, b, y, r)
    hit = lo <= hi
    left = np.where(hit, np.minimum(left, lo), left)
    right = np.where(hit, np.maximum(right, hi), right)
    found = left <= right
    line, left, right = line[found], left[found], right[found]
    return (np.repeat(line, 2), np.stack([left, right], axis=1).ravel(),
            np.tile([1, -1], len(line)))


def _band_interval(a, b, y, r):
    """x-interval where the line at ``y`` meets the rectangle of half-width ``r``
    around segment a-b (each (n, 2)); lo > hi when it misses."""
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    safe = np.where(length > 0, length, 1.0)
    ux, uy = d[:, 0] / safe, d[:, 1] / safe
    dy = y - a[:, 1]
    lo_n, hi_n = _linear_interval(-uy, ux * dy, -r, r)           # |normal . (p - a)| <= r
    lo_u, hi_u = _linear_interval(ux, uy * dy, 0.0, length)       # 0 <= dir . (p - a) <= length
    lo, hi = a[:, 0] + np.maximum(lo_n, lo_u), a[:, 0] + np.minimum(hi_n, hi_u)
    return np.where(length > 0, lo, np.inf), np.where(length > 0, hi, -np.inf)


def _linear_interval(coef, offset, lo, hi):
    """The set of u with lo <= coef * u + offset <= hi, as (start, end); start > end if empty."""
    flat = np.abs(coef) < 1e-12
    c = np.where(flat, 1.0, coef)
    u0, u1 = (lo - offset) / c, (hi - offset) / c
    start, end = np.minimum(u0, u1), np.maximum(u0, u1)
    always = (offset >= lo) & (offset <= hi)
    start = np.where(flat, np.where(always, -np.inf, np.inf), start)
    end = np.where(flat, np.where(always, np.inf, -np.inf), end)
    return start, end


def spans(region, cuts, x_min: float, x_max: float):
    """Inside intervals per line: even-odd inside the region toggles and outside
    every cut. ``region = (line, x)``, ``cuts = (line, x, delta)``; returns
    (line, x0, x1) with x clipped to ``[x_min, x_max]``."""
    line = np.concatenate([region[0], cuts[0]]).astype(np.int64)
    x = np.concatenate([region[1], cuts[1]]).astype(np.float64)
    toggle = np.concatenate([np.ones(len(region[0]), np.int64), np.zeros(len(cuts[0]), np.int64)])
    delta = np.concatenate([np.zeros(len(region[0]), np.int64), np.asarray(cuts[2], np.int64)])
    order = np.lexsort((x, line))
    line, x, toggle, delta = line[order], x[order], toggle[order], delta[order]
    if len(line) < 2:
        return np.zeros(0, np.int64), np.zeros(0), np.zeros(0)
    start = np.searchsorted(line, line, "left")  # first event of each event's line
    parity = (np.cumsum(toggle) - (np.cumsum(toggle) - toggle)[start]) & 1
    depth = np.cumsum(delta) - (np.cumsum(delta) - delta)[start]
    inside = (parity == 1) & (depth <= 0)
    keep = inside[:-1] & (line[:-1] == line[1:])
    x0 = np.clip(x[:-1][keep], x_min, x_max)
    x1 = np.clip(x[1:][keep], x_min, x_max)
    nonempty = x1 > x0
    return line[:-1][keep][nonempty], x0[nonempty], x1[nonempty]


def coverage(rows: Rows, line, x0, x1, rho: float, shape: tuple[int, int]) -> np.ndarray:
    """float32 (H, W) share of each raster pixel covered by the spans, in [0, 1]."""
    n_rows, n_cols = shape
    weight = (rows.hi - rows.lo)[line] * rho          # share of the raster row's height
    base = rows.raster[line] * (n_cols + 2)
    a = np.clip(x0 * rho, 0, n_cols)
    b = np.clip(x1 * rho, 0, n_cols)
    ia, ib = np.floor(a).astype(np.int64), np.floor(b).astype(np.int64)
    fa, fb = a - ia, b - ib
    # one cumulative sum along x turns these steps into the per-pixel x-overlap
    idx = np.concatenate([base + ia, base + ia + 1, base + ib, base + ib + 1])
    val = np.concatenate([weight * (1 - fa), weight * fa, -weight * (1 - fb), -weight * fb])
    steps = np.bincount(idx, weights=val, minlength=n_rows * (n_cols + 2))
    steps = steps.astype(np.float64, copy=False)   # with no spans, bincount counts in int64
    # in place: a large raster's fresh arrays cost more than the sums
    cov = np.cumsum(steps.reshape(n_rows, n_cols + 2), axis=1, out=steps.reshape(n_rows, n_cols + 2))
    return np.clip(cov[:, :n_cols], 0.0, 1.0, out=cov[:, :n_cols]).astype(np.float32)


def evenodd_area(rings: list[np.ndarray]) -> float:
    """Even-odd filled area of closed rings (canvas px^2).

    Exact: the plane is cut into slabs at every vertex y (and, up to
    :data:`EXACT_INTERSECTIONS` edges, every edge crossing), inside which the
    crossing x are linear in y, so each slab's midline width times its height
    is its area.
    """
    edges = ring_edges(rings)
    edges = edges[edges[:, 0, 1] != edges[:, 1, 1]]
    if len(edges) == 0:
        return 0.0
    ys = [edges[:, :, 1].ravel()]
    if len(edges) <= EXACT_INTERSECTIONS:
        ys.append(_crossing_ys(edges))
    cuts = np.unique(np.concatenate(ys))
    mids, heights = (cuts[:-1] + cuts[1:]) / 2, np.diff(cuts)
    line, x = crossings(edges, mids)
    order = np.lexsort((x, line))
    line, x = line[order], x[order]
    return float(np.sum(heights[line[0::2]] * (x[1::2] - x[0::2])))


def _crossing_ys(edges: np.ndarray) -> np.ndarray:
    """y of every proper crossing between two edges (E, 2, 2)."""
    i, j = np.triu_indices(len(edges), k=1)
    p, r = edges[i, 0], edges[i, 1] - edges[i, 0]
    q, s = edges[j, 0], edges[j, 1] - edges[j, 0]
    denom = r[:, 0] * s[:, 1] - r[:, 1] * s[:, 0]
    qp = q - p
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = (qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]) / denom
        u = (qp[:, 0] * r[:, 1] - qp[:, 1] * r[:, 0]) / denom
    hit = (denom != 0) & (t > 0) & (t < 1) & (u > 0) & (u < 1)
    return p[hit, 1] + t[hit] * r[hit, 1]


def transparent_background(rgba: np.ndarray) -> bool:
    """True if transparency is the background of a uint8 (h, w, 4) image: at least
    half of its border pixels are transparent (alpha < 50%). A few faint pixels at
    corners or edges are not a background; a figure cut out on transparency is."""
    alpha = rgba[..., 3]
    border = np.concatenate([alpha[0], alpha[-1], alpha[1:-1, 0], alpha[1:-1, -1]])
    return bool(np.mean(border < 128) >= 0.5)


def mask_from_rgba(owner: str, rgba: np.ndarray, threshold: float, invert: bool) -> np.ndarray:
    """Inside mask (h, w) of a uint8 (h, w, 4) image, read as a person sees it.

    If transparency is the background (:func:`transparent_background`), inside is
    the figure: opaque pixels (alpha >= 50%), whatever their colour. Otherwise the
    image is composited over white and inside is what is darker than ``threshold``
    (Rec. 709 luminance in [0, 1]), so faint alpha pixels, antialiased edges and
    JPEGs read as drawn. ``invert`` swaps. ValueError if no pixel is inside."""
    alpha = rgba[..., 3]
    if transparent_background(rgba):
        mask, rule = alpha >= 128, ("opaque", "transparent")
    else:
        weights = np.array([2126, 7152, 722], np.int64)           # Rec. 709 luma, sum 10000
        lum = (rgba[..., :3].astype(np.int64) @ weights) / (10000 * 255)  # exactly 1.0 for white
        a = alpha / 255
        lum = lum * a + (1 - a)                                     # over white
        mask, rule = lum < threshold, (f"darker than threshold {threshold:g}",
                                       f"lighter than threshold {threshold:g}")
    if invert:
        mask = ~mask
    if not mask.any():
        n = mask.size
        hint = ("use invert=False" if invert else "use invert=True") + (
            "" if rule[0] == "opaque" else (" or a lower threshold" if invert else " or a higher threshold"))
        state = rule[0] if invert else rule[1]
        raise ValueError(f"{owner}: no pixel is inside (all {n} pixels are {state}); {hint}")
    return mask


def wand_mask(rgba: np.ndarray, row: int, col: int, tolerance: float) -> np.ndarray:
    """Magic wand on a uint8 (h, w, 4) image: the bool (h, w) 4-connected pixels around
    (row, col) whose colour, composited over white, lies within ``tolerance`` of its
    colour (RGB distance in [0, 1] divided by sqrt(3))."""
    rgba = rgba.astype(np.float32) / 255
    rgb = rgba[..., :3] * rgba[..., 3:] + (1 - rgba[..., 3:])
    near = np.linalg.norm(rgb - rgb[row, col], axis=2) <= tolerance * np.sqrt(3) + 1e-6
    labels, _ = ndimage.label(near, structure=[[0, 1, 0], [1, 1, 1], [0, 1, 0]])
    return labels == labels[row, col]


def flatten_path(d: str) -> list[np.ndarray]:
    """Rings (k, 2) of SVG path data: one per subpath, curves flattened to
    polylines within :data:`CURVE_TOLERANCE` px. Raises ValueError."""
    chunks = [c for c in re.split(r"(?=[Mm])", d) if c.strip()]
    if not chunks or chunks[0].strip()[0] not in "Mm":
        raise ValueError("path data must start with a moveto command (M or m)")
    rings, pos = [], 0j
    for chunk in chunks:
        try:
            path = parse_path(chunk, current_pos=pos)
        except Exception as exc:  # svgpathtools raises several types on bad input
            raise ValueError(f"cannot parse {chunk.strip()[:40]!r}: {exc}") from None
        if len(path) == 0:
            pos = _moveto_point(chunk, pos)
            continue
        for sub in path.continuous_subpaths():
            pts = [sub[0].start] + [p for seg in sub for p in _flatten_segment(seg)]
            rings.append(np.column_stack([np.real(pts), np.imag(pts)]).astype(np.float64))
        pos = path[-1].end
    return rings


def _moveto_point(chunk: str, pos: complex) -> complex:
    """The point a lone ``M x y`` / ``m dx dy`` chunk moves to."""
    nums = re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", chunk)
    if len(nums) < 2:
        raise ValueError(f"cannot parse {chunk.strip()[:40]!r}: a moveto needs x and y")
    point = complex(float(nums[0]), float(nums[1]))
    return pos + point if chunk.strip()[0] == "m" else point


def _flatten_segment(seg) -> list[complex]:
    """Points after the start of one svgpathtools segment, as complex numbers."""
    if type(seg).__name__ == "Line":
        return [seg.end]
    n = 8
    while True:
        t = np.linspace(0.0, 1.0, n + 1)
        pts = np.asarray(seg.point(t), dtype=complex)
        mid = np.asarray(seg.point((t[:-1] + t[1:]) / 2), dtype=complex)
        chord = pts[1:] - pts[:-1]
        off = mid - pts[:-1]
        length = np.abs(chord)
        dev = np.where(length > 0, np.abs((np.conj(chord) * off).imag) / np.where(length > 0, length, 1),
                       np.abs(off))
        if not np.all(np.isfinite(pts)) or dev.max() <= CURVE_TOLERANCE or n >= 4096:
            return list(pts[1:])
        n *= 2
