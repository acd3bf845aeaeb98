"""Data columns for the size channel: equal, uniform, lognormal, ties and Pareto values,
optionally with missing values (NaN, dropped with ``dropna=True``) and sorted rows.

``column(kind, n, rng)`` returns a float array of ``n`` positive values.
"""
from __future__ import annotations

import numpy as np

KINDS = ("equal", "uniform", "lognormal", "ties", "pareto")


def column(kind: str, n: int, rng) -> np.ndarray:
    if kind == "equal":
        return np.ones(n)
    if kind == "uniform":
        return rng.uniform(1.0, 5.0, n)
    if kind == "lognormal":
        return rng.lognormal(0.0, rng.uniform(0.4, 1.1), n)
    if kind == "ties":
        levels = np.array([1.0, rng.uniform(3, 6), rng.uniform(10, 25)])
        return levels[rng.choice(3, n, p=[0.5, 0.35, 0.15])]
    if kind == "pareto":
        return rng.pareto(rng.uniform(0.9, 1.6), n) + 1.0
    raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")


def with_rows(values: np.ndarray, rows: str, rng) -> np.ndarray:
    """``values`` as the rows arrive: "shuffled" (as drawn), "ascending", "descending", or
    "nan" (5 to 10% of them missing)."""
    if rows == "ascending":
        return np.sort(values)
    if rows == "descending":
        return np.sort(values)[::-1]
    if rows == "nan":
        out = values.copy()
        missing = max(1, int(len(out) * rng.uniform(0.05, 0.1)))
        out[rng.choice(len(out), missing, replace=False)] = np.nan
        return out
    return values
