"""Mark groups: which of a layer's marks each of its rows draws.

A layer draws a *group* of marks (``layer.marks``, at least one). Without
``shape=``, row i of the layer (in DataFrame order) draws mark ``i mod k``.
With ``shape=<column>``, a ``{category: mark}`` dict (``layer.mark_keys``)
gives each category its mark, and a list goes to the column's sorted
categories in turn (cycling, like colours from a palette).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .encodings import check_column, sorted_unique


def sorted_categories(series: pd.Series) -> list:
    """The distinct non-missing values of ``series``, in the order palettes use."""
    return sorted_unique(series.dropna())


def mark_choice(df: pd.DataFrame, sub: pd.DataFrame, layer) -> np.ndarray:
    """int ``(n,)``: the index into ``layer.marks`` of each row of ``sub`` (the layer's
    rows of ``df``). ValueError for a dict that misses categories or lacks ``shape=``."""
    n, k = len(sub), len(layer.marks)
    column, keys = layer.encodings["shape"], layer.mark_keys
    if column is None:
        if keys is not None:
            raise ValueError(f"layer {layer.name!r}: mark is a dict of category -> mark "
                             f"({_listed(keys)}); set shape=<column> to pick each row's mark")
        return np.arange(n) % k
    check_column(df, "shape", column)
    if k == 1:
        raise ValueError(f"shape={column!r}: layer {layer.name!r} draws a single mark "
                         f"({layer.marks[0]!r}), "
                         f"so every category would look the same; pass a list of marks "
                         f"(mark=['circle', 'square', ...]) or a dict {{category: mark}}")
    values = sub[column]
    try:
        categories = sorted_categories(df[column])
    except TypeError:
        raise ValueError(f"shape={column!r}: the column's values must be hashable categories "
                         f"(str, number, ...), got {type(values.iloc[0]).__name__}") from None
    if values.isna().any():
        raise ValueError(f"shape={column!r}: {int(values.isna().sum())} rows of layer "
                         f"{layer.name!r} are missing; fill them or pass dropna=True")
    if keys is None:
        code = {v: i % k for i, v in enumerate(categories)}
        return np.array([code[v] for v in values], dtype=np.int64)
    lookup = {}
    for i, key in enumerate(keys):
        lookup.setdefault(str(key), i)
    for i, key in enumerate(keys):   # exact keys win over their text (1 vs "1")
        lookup[key] = i
    missing = [v for v in sorted_categories(values) if v not in lookup and str(v) not in lookup]
    if missing:
        raise ValueError(f"shape={column!r}: mark has no entry for the categories "
                         f"{_listed(missing)}; the keys given are {_listed(keys)}; add a mark "
                         f"for each category")
    return np.array([lookup[v] if v in lookup else lookup[str(v)] for v in values], dtype=np.int64)


def _listed(values, limit: int = 12) -> str:
    """``'a', 'b', ... (n in all)`` for an error message."""
    shown = ", ".join(repr(v.item() if isinstance(v, np.generic) else v) for v in values[:limit])
    return shown + (f", ... ({len(values)} in all)" if len(values) > limit else "")
