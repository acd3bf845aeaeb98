"""Marks across a narrow join: a mark whose silhouette splits its container into more large
pieces (each at least ``SHARE`` of the container) than the container has alone, such as the
largest disc bridging two touching heads, or a mark plugging a neck.

Masks are bool ``(H, W)`` at one px per canvas px; a mark is its silhouette's crop and the
rows and columns (slices) it covers.
"""
from __future__ import annotations

import numpy as np
from scipy import ndimage

SHARE = 0.1


def large_pieces(mask: np.ndarray, area: float) -> int:
    """How many 4-connected pieces of ``mask`` hold at least ``SHARE`` of ``area`` px."""
    labels, n = ndimage.label(mask)
    if n == 0:
        return 0
    return int((np.bincount(labels.ravel())[1:] >= SHARE * area).sum())


def coarse(silhouette: np.ndarray, k: int) -> np.ndarray:
    """A ``(h k, w k)`` silhouette at one px per canvas px: a px is covered when any of its
    ``k x k`` samples is."""
    h, w = silhouette.shape[0] // k, silhouette.shape[1] // k
    return silhouette[:h * k, :w * k].reshape(h, k, w, k).any(axis=(1, 3))


def splits(mask: np.ndarray, silhouette: np.ndarray, rows: slice, cols: slice, pieces: int) -> bool:
    """True when ``mask`` less the mark has more large pieces than ``pieces`` (the
    container's own count)."""
    rest = mask.copy()
    rest[rows, cols] &= ~silhouette
    return large_pieces(rest, float(mask.sum())) > pieces
