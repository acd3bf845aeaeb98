"""Size-aware start: each mark packed into the cheapest spot that holds it.

A wide spread of sizes jams on a lattice sized for the mean mark: large marks
overlap their neighbours and small ones leave holes. Here each layer's marks
take, one by one, the cheapest spot (lowest force potential, or nearest the
container's centre) whose *clearance* holds their footprint disc, in the
order the caller asks (``start.pack_layer``: largest first at random spots,
small marks into the gaps, or in ``order=``'s order). The clearance is the
distance to the container's edge and to every disc already placed. Spots lie
on a fine hexagonal lattice; each keeps its clearance, lowered around every
disc placed. Layers sharing a container are packed in block order, so a
layer that blocks on another starts in the room the other left, beyond the
shadow it casts along the force (above it under a downward force, outside it
around a point force).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from .lattice import Region, hex_points

SPREAD = 1.5          # footprint radii max / min above which a layer is packed by size
ASPECT = 2.0          # box long / short side up to which a mark's disc stands for it
STEP = 0.3            # spot spacing, in median footprint radii
MAX_SPOTS = 120_000   # spots per container at most (the spacing widens beyond)
ROWS_FILL = 0.75      # rows of thin marks: spaced for this share of the room their length needs
NECK = 0.5            # a row narrowing under this share of the depth it reaches on both sides: cut
CHUNK = 4096          # spots scanned at once for the first that fits
SPARSE = 0.5          # footprint share of a closed container below which marks spread over it


def thin(half_w: np.ndarray, half_h: np.ndarray) -> np.ndarray:
    """Bool ``(N,)``: boxes (half sides ``(N,)``) whose long side is over ``ASPECT`` short sides."""
    return np.maximum(half_w, half_h) > ASPECT * np.minimum(half_w, half_h)


def packable(radius: np.ndarray, half_w: np.ndarray, half_h: np.ndarray) -> bool:
    """Whether a layer's marks get a size-aware start: footprint radii ``(n,)`` spread,
    and no box (half sides ``(n,)``) thin, so that its disc stands for it (a tall, thin
    strand's disc would let neighbours cross it)."""
    return (len(radius) > 1 and float(radius.max()) > SPREAD * float(radius.min())
            and not thin(half_w, half_h).any())


class Packing:
    """Spots of one container and their clearances (canvas px).

    ``region``: the container; ``step``: spot spacing in canvas px; ``reach``:
    the largest disc radius still to be placed (clearances matter up to it).
    """

    def __init__(self, region: Region, step: float, reach: float):
        step = max(step, math.sqrt(region.area / MAX_SPOTS / (math.sqrt(3) / 2)))
        pts = hex_points(region.bbox, step)
        depth = region.depth_at(pts)
        keep = depth > 0
        self.points, self.depth = pts[keep], depth[keep]
        self.clear = self.depth.copy()
        self.tree = cKDTree(self.points) if len(self.points) else None
        self.reach = reach

    def stamp(self, centers: np.ndarray, radii: np.ndarray) -> None:
        """Lower the clearances around discs ``centers (k, 2)``, ``radii (k,)`` placed."""
        if self.tree is None:
            return
        for c, r in zip(centers, radii):
            near = np.asarray(self.tree.query_ball_point(c, r + self.reach), dtype=np.int64)
            if len(near):
                gap = np.hypot(*(self.points[near] - c).T) - r
                self.clear[near] = np.minimum(self.clear[near], gap)

    def lower(self, distance: np.ndarray) -> None:
        """Lower the clearances to ``distance (M,)`` per spot (canvas px, as ordered by
        ``self.points``) where it is less: the room a shadow takes (``strata.shadow_distance``)."""
        np.minimum(self.clear, distance, out=self.clear)

    def place(self, radii: np.ndarray, cost: np.ndarray, ranks: np.ndarray,
              largest_first: bool = True, roomiest: bool = False, later: float | None = None,
              until_miss: bool = False):
        """Centres ``(n, 2)`` for discs ``radii (n,)``, each at the cheapest spot that holds
        it (``cost (M,)`` per spot, as ordered by ``self.points``), else at the roomiest
        spot; and whether all fitted. ``largest_first``: by decreasing size (``ranks`` break
        ties), else in ``ranks`` order. ``roomiest``: every disc, of those that hold it, at the
        spot farthest from the discs placed (the edge counting as a mirror: twice its
        distance), which spreads marks too few to fill a container evenly over it.
        ``later``: the largest disc radius later calls place here (default ``self.reach``).
        ``until_miss``: return ``(centers so far, False)`` at the first disc that fits
        nowhere, the clearances left as they were (a scale search needs only the answer).
        Each disc lowers the clearances only as far as they matter: up to the largest disc
        still to place, of this call's and ``later`` (one huge mark of a heavy tail would
        otherwise make every small disc's update span the whole container)."""
        if self.tree is None:
            raise ValueError("container: no spot inside it to place marks on")
        by_cost = np.argsort(cost, kind="stable")
        points, clear = self.points[by_cost], self.clear[by_cost]
        room = 2 * self.depth[by_cost]      # roomiest: twice the edge distance, then the gaps
        tree = cKDTree(points)
        centers, fitted = np.zeros((len(radii), 2)), True
        dead, smallest = 0, float(radii.min())
        seq = np.lexsort((ranks, -radii)) if largest_first else np.argsort(ranks, kind="stable")
        # (n,) the largest disc from each one on, in placing order
        rest = np.maximum.accumulate(np.asarray(radii, float)[seq][::-1])[::-1]
        reach = np.maximum(np.append(rest[1:], 0.0), self.reach if later is None else later)
        for i, ahead in zip(seq, reach):
            r = float(radii[i])
            dead = _first(clear, smallest, dead, len(clear))   # spots too tight for any mark left
            if roomiest:
                holds = clear >= r
                k = int(np.argmax(np.where(holds, room, -np.inf))) if holds.any() else -1
            else:
                k = _first(clear, r, dead, -1)
            if k < 0:
                if until_miss:   # the caller asks only whether all fit
                    return centers, False
                k, fitted = int(np.argmax(clear)), False
            centers[i] = points[k]
            if roomiest:
                np.minimum(room, np.hypot(*(points - points[k]).T) - r, out=room)
            near = np.asarray(tree.query_ball_point(points[k], r + ahead), dtype=np.int64)
            clear[near] = np.minimum(clear[near], np.hypot(*(points[near] - points[k]).T) - r)
        self.clear[by_cost] = clear
        return centers, fitted

    def place_near(self, radii: np.ndarray, targets: np.ndarray, ranks: np.ndarray) -> np.ndarray:
        """Centres ``(n, 2)`` for discs ``radii (n,)``, each in ``ranks`` order at the spot
        nearest its own target ``targets (n, 2)`` (canvas px) whose clearance holds it, else
        at the roomiest spot; the clearances are lowered as they are placed."""
        if self.tree is None:
            raise ValueError("container: no spot inside it to place marks on")
        centers = np.zeros((len(radii), 2))
        for i in np.argsort(ranks, kind="stable"):
            r, k = float(radii[i]), -1
            count = min(64, len(self.points))
            while k < 0:
                near = np.atleast_1d(self.tree.query(targets[i], k=count)[1])
                holds = near[self.clear[near] >= r]
                if len(holds):
                    k = int(holds[0])
                elif count >= len(self.points):
                    k = int(np.argmax(self.clear))
                count = min(4 * count, len(self.points))
            centers[i] = self.points[k]
            self.stamp(centers[i:i + 1], radii[i:i + 1])
        return centers


def _first(clear: np.ndarray, r: float, start: int, missing: int) -> int:
    """Index of the first spot from ``start`` whose clearance holds ``r``; ``missing`` if none."""
    for lo in range(start, len(clear), CHUNK):
        hit = clear[lo:lo + CHUNK] >= r
        k = int(np.argmax(hit))
        if hit[k]:
            return lo + k
    return missing


def necks(depth: np.ndarray) -> list:
    """Where a row of a region narrows to a neck: the index of the least depth in each run
    of ``depth (k,)`` (canvas px along the row) under ``NECK`` of the depth the row reaches
    on both sides of it. None in a convex region, where the depth along a line rises to
    one peak and falls."""
    beside = np.minimum(np.maximum.accumulate(depth), np.maximum.accumulate(depth[::-1])[::-1])
    narrow = np.diff(np.concatenate([[0], (depth < NECK * beside).astype(np.int8), [0]]))
    return [int(a + np.argmin(depth[a:b]))
            for a, b in zip(np.nonzero(narrow == 1)[0], np.nonzero(narrow == -1)[0])]


def rows(region: Region, length: np.ndarray, width: np.ndarray, axis: float,
         ranks: np.ndarray) -> np.ndarray:
    """Centres ``(n, 2)`` for thin marks laid along ``axis`` (radians) in rows across the
    region, like words in lines: rows evenly spaced over the region's whole breadth so the
    marks' total length fills the area, each mark, longest first, into the row span with the
    largest share of its length still free that holds its ``length (n,)`` (canvas px) and
    whose depth holds half its ``width (n,)``; each span's marks spread evenly along it in
    their start order ``ranks (n,)`` (longest first, every row would grade from long to
    short marks), a span too full for its marks overfilled (the optimiser then parts them).
    A row is cut where it passes a neck (``necks``): a mark laid across one is pulled two
    ways and pokes out there (joined discs, an hourglass)."""
    e1, e2 = np.array([math.cos(axis), math.sin(axis)]), np.array([-math.sin(axis), math.cos(axis)])
    ys, xs = np.nonzero(region.depth > 0)
    pixels = (np.stack([xs, ys], 1) + 0.5) / region.rho
    mid = pixels.mean(0)
    along, across = (pixels - mid) @ e1, (pixels - mid) @ e2
    lo, hi = float(across.min()), float(across.max())
    gap = max(ROWS_FILL * region.area / float(length.sum()), float(width.max()))
    count = max(1, int(round((hi - lo) / gap)))
    gap = (hi - lo) / count          # the outer rows half a gap from the edge
    step = max(float(width.min()) / 2, (hi - lo) / 4000)
    u = np.arange(float(along.min()), float(along.max()) + step, step)
    spans = []   # [v, u start, length]
    for v in lo + gap * (np.arange(count) + 0.5):
        depth = region.depth_at(mid + u[:, None] * e1 + v * e2)
        inside = depth >= float(np.median(width)) / 2
        edge = np.diff(np.concatenate([[0], inside.astype(np.int8), [0]]))
        for a, b in zip(np.nonzero(edge == 1)[0], np.nonzero(edge == -1)[0]):
            cuts = [a, *(a + k for k in necks(depth[a:b])), b]
            for a0, b0 in zip(cuts[:-1], cuts[1:]):
                spans.append([v, u[a0], (b0 - a0) * step])
    if not spans:
        raise ValueError("container: no row inside it to lay thin marks along")
    spans = np.array(spans)
    room, members = spans[:, 2].copy(), [[] for _ in spans]
    longer = 1e-6 * spans[:, 2] / spans[:, 2].max()   # breaks ties towards the longer span
    for i in np.argsort(-length, kind="stable"):
        # the freest span (by share; the longest of equally free ones) that holds the mark
        share = room / spans[:, 2] + longer
        fit = room >= length[i]
        k = int(np.argmax(np.where(fit, share, -np.inf))) if fit.any() else int(np.argmax(share))
        members[k].append(i)
        room[k] -= length[i]
    centers = np.zeros((len(length), 2))
    for (v, start, _), mine, left in zip(spans, members, room):
        free = left / max(len(mine), 1)      # the room left, shared out between the marks
        at = start + free / 2
        for i in sorted(mine, key=lambda i: ranks[i]):
            centers[i] = mid + (at + length[i] / 2) * e1 + v * e2
            at += length[i] + free
    return centers
