"""Strata measured on a placements table: how much of a layer lies below the one it rests on."""
from __future__ import annotations

import numpy as np


def below_envelope(table, lower: str, upper: str) -> float:
    """Share of layer ``upper``'s discs whose centre lies below the upper envelope (the
    topmost ink, column by column, every 2 px across both layers' extent) of layer
    ``lower``'s discs."""
    both = table[table["layer"].isin([lower, upper])]
    left, right = (both["x"] - both["width"] / 2).min(), (both["x"] + both["width"] / 2).max()
    xs = np.arange(2.0 * np.floor(left / 2), right + 2.0, 2.0)
    top = np.full(len(xs), np.inf)
    for x, y, w in table[table["layer"] == lower][["x", "y", "width"]].to_numpy():
        near = np.abs(xs - x) < w / 2
        top[near] = np.minimum(top[near], y - np.sqrt((w / 2) ** 2 - (xs[near] - x) ** 2))
    up = table[table["layer"] == upper]
    column = np.abs(xs[None, :] - up["x"].to_numpy()[:, None]).argmin(1)
    return float(np.mean(up["y"].to_numpy() > top[column]))
