"""One mark for k units: the layer fields ``count``, ``per``, ``rounding`` and ``partial``
checked, the marks a group of units draws, and how far a partial mark is drawn.

``count="col"``: each row stands for that many units. ``per=k``: one mark for k units of
one category (``layout.prepare.tally`` groups the rows). A group of ``U`` units draws
``U / k`` marks, rounded by ``rounding``: ``"largest-remainder"`` (the default: each group
its floor, then one more for the groups with the largest remainders until the layer's
marks sum to ``round(total / k)``), ``"floor"``, ``"ceil"`` or ``"nearest"``; or, with
``partial=True``, ``floor(U / k)`` whole marks and one mark drawn to the fraction
``(U mod k) / k`` of its ink, clipped along its width as ISOTYPE draws it.
"""
from __future__ import annotations

from numbers import Real

import numpy as np

from .bounds import MAX_COLUMN_NAME, check_length
from .validate import check_choice, check_finite

ROUNDINGS = ("largest-remainder", "floor", "ceil", "nearest")
CLIP_SIDE = 256   # px: the long side of the silhouette a partial mark's ink is measured on


def check_count(value):
    """None or a column name (the column is checked when the rows are bound)."""
    if isinstance(value, str):
        check_length("count (a column name)", value, MAX_COLUMN_NAME, "characters")
    if value is None or isinstance(value, str):
        return value
    raise TypeError(f"count must be a column name (each row stands for that many units) or "
                    f"None, got {value!r:.60}")


def check_per(value):
    """None or a number of units > 0 that one mark stands for."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"per must be None or a number of units > 0 (one mark for per units), "
                        f"got {value!r:.60}")
    v = check_finite("Layer", "per", value)
    if not v > 0:
        raise ValueError(f"per must be a number of units > 0 (one mark for per units), got {value!r}")
    return int(v) if float(v).is_integer() else v


def check_rounding(value) -> str:
    """One of ``ROUNDINGS``."""
    return check_choice("Layer", "rounding", value, ROUNDINGS)


def check_partial(value) -> bool:
    """True or False."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"partial must be True (a group's remainder drawn as one clipped mark) or "
                    f"False (rounded), got {value!r:.60}")


def marks_per_group(totals: np.ndarray, per: float, rounding: str, partial: bool):
    """``(marks (G,) int, fraction (G,))``: how many marks each group of ``totals`` units
    draws, and the drawn fraction of its last mark (1 but for a partial mark)."""
    q = np.asarray(totals, dtype=float) / per
    whole = np.floor(q + 1e-9)                # 299.99999999 units of 100 are 3 marks
    rest = np.clip(q - whole, 0.0, None)
    rest[rest < 1e-9] = 0.0
    fraction = np.ones(len(q))
    if partial:
        marks = whole + (rest > 0)
        fraction[rest > 0] = rest[rest > 0]
    elif rounding == "floor":
        marks = whole
    elif rounding == "ceil":
        marks = whole + (rest > 0)
    elif rounding == "nearest":
        marks = np.floor(q + 0.5)
    else:   # largest remainder: the layer's marks sum to round(total / per)
        marks = whole.copy()
        extra = int(np.floor(q.sum() + 0.5) - whole.sum())
        ranked = np.lexsort((np.arange(len(q)), -rest))   # largest first, ties to the first
        marks[ranked[:max(extra, 0)]] += 1
    return marks.astype(np.int64), fraction


def ink_clip(mark, fraction: float) -> float:
    """The share of ``mark``'s box width, from its left edge, that holds ``fraction`` of its
    ink (1 for a whole mark): a partial mark clipped there keeps that share of the ink."""
    if fraction >= 1:
        return 1.0
    ink = mark.as_footprint("ink").silhouette(CLIP_SIDE).sum(axis=0)   # (w,) ink per column
    cumulative = np.concatenate([[0.0], np.cumsum(ink, dtype=float)])
    if cumulative[-1] <= 0:
        return float(fraction)
    at = np.interp(fraction * cumulative[-1], cumulative, np.arange(len(cumulative)))
    return float(np.clip(at / len(ink), 0.0, 1.0))
