"""The start order: the rank in which each layer's units are emitted, packed from the spots
its forces pull hardest (or its container's centre) out, or laid on a grid.

With ``order=`` bound, the column's ranks (``design.encodings``). Without, the rows' order
is an accident of the file (a table sorted by year would start as rings of years), so each
unit's rank is drawn from the layout's seed and its row's index label: reproducible,
independent of where the row sits in the table, and kept by a row when rows are added or
removed (a warm start places the added ones among the kept ones by the same draw).
"""
from __future__ import annotations

import numpy as np
import pandas as pd


def start_order(units, layers, seed: int) -> np.ndarray:
    """``(N,)`` each unit's rank within its layer: ``units.order`` for the layers that bind
    ``order=``, else a rank drawn from ``seed`` and the unit's row label."""
    order = np.asarray(units.order).copy()
    drawn = draws(units.rows, seed)
    for i, layer in enumerate(layers):
        mine = np.nonzero(units.layer == i)[0]
        if layer.encodings["order"] is None and len(mine):
            order[mine] = np.argsort(np.argsort(drawn[mine], kind="stable"), kind="stable")
    return order


def draws(rows, seed: int) -> np.ndarray:
    """``(N,)`` uint64 keys, one per row label of ``rows``, uniform and independent of the
    labels' order: a hash of the seed and the label's repr (stable across processes)."""
    text = np.array([f"{int(seed)}|{row!r}" for row in rows], dtype=object)
    return pd.util.hash_array(text, categorize=False)
