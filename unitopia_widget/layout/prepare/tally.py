"""A layer's rows made marks: one per row, ``count=`` units per row, or one for ``per=`` units.

``tally(sub, layer)`` returns a ``Tally``: the frame the encodings read (one row per mark:
the row itself, a row repeated once per unit, or the first row a ``per=`` mark covers),
the units each mark stands for, the drawn share of its ink (1 but for a partial mark) and
the rows each mark covers. ``per=`` groups the rows by every categorical channel the layer
binds (colour, shape, x, y; ``by=`` made the layers), with pandas, never a loop over rows,
so a million rows bind in well under a second. The rounding is ``design.tally``'s.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ...design.bounds import MAX_UNITS
from ...design.encodings import check_column, is_continuous, is_css_color, numeric_column
from ...design.tally import marks_per_group

GROUPED = ("color", "shape", "x", "y")   # categorical channels a per= mark takes one value of
SINGLE = ("size", "width", "height", "margin", "order")   # numeric channels per= refuses


@dataclass
class Tally:
    """One layer's marks, ``(n,)`` arrays but ``covered``."""

    frame: pd.DataFrame     # the row each mark is encoded from
    amount: np.ndarray      # units each mark stands for
    fraction: np.ndarray    # drawn share of each mark's ink: 1, or a partial mark's fraction
    covered: np.ndarray     # (M,) index labels of the rows the marks cover, mark after mark
    start: np.ndarray       # each mark's first entry in ``covered``
    stop: np.ndarray        # one past its last


def tally(sub: pd.DataFrame, layer) -> Tally:
    """The marks of ``layer`` over its rows ``sub``. ValueError for a bad ``count=`` column,
    a channel ``per=`` cannot take, or more units than a chart lays out."""
    n = len(sub)
    labels = sub.index.to_numpy()
    if layer.count is None and layer.per is None:
        return Tally(sub, np.ones(n), np.ones(n), labels, np.arange(n), np.arange(1, n + 1))
    units = np.ones(n) if layer.count is None else numeric_column(sub, "count", layer.count,
                                                                  positive=False)
    if layer.per is None:
        return _expanded(sub, layer, units)
    keys = _grouping(sub, layer)
    group = np.zeros(n, dtype=np.int64)
    if keys:
        try:
            group = sub.groupby(keys, sort=True, dropna=False, observed=True).ngroup().to_numpy()
        except TypeError:   # categories that do not compare: first-seen order
            group = sub.groupby(keys, sort=False, dropna=False, observed=True).ngroup().to_numpy()
    order = np.argsort(group, kind="stable")
    order = order[units[order] > 0]           # rows of no units cover no mark
    totals = np.bincount(group, weights=units, minlength=int(group.max()) + 1)
    per = float(layer.per)
    marks, fraction = marks_per_group(totals, per, layer.rounding, layer.partial)
    if marks.sum() > MAX_UNITS:
        raise too_many(int(marks.sum()), float(totals.sum()))
    # each group's units on one line, groups end to end: mark j of group g covers
    # [base + j * per, base + (j + 1) * per), its last mark up to the group's end
    base = np.concatenate([[0.0], np.cumsum(totals)[:-1]])
    of = np.repeat(np.arange(len(totals)), marks)
    j = np.arange(len(of)) - np.repeat(np.cumsum(marks) - marks, marks)
    last = j == marks[of] - 1
    lo = base[of] + j * per
    hi = np.where(last, base[of] + totals[of], lo + per)
    end = np.cumsum(units[order])             # the sorted rows' units on the same line
    begin = end - units[order]
    start = np.searchsorted(end, lo, side="right")
    stop = np.maximum(np.searchsorted(begin, hi, side="left"), start + 1)
    drawn = np.where(last, fraction[of], 1.0)
    return Tally(sub.iloc[order[np.minimum(start, len(order) - 1)]], hi - lo, drawn,
                 labels[order], start, stop)


def _expanded(sub, layer, units) -> Tally:
    """``count=`` without ``per=``: each row repeated once per unit."""
    whole = units == np.floor(units)
    if not whole.all():
        at = int(np.argmin(whole))
        raise ValueError(f"count={layer.count!r}: without per=, each row draws one mark per "
                         f"unit, so counts must be whole numbers; row {sub.index[at]!r:.40} has "
                         f"{units[at]:g}; round the column, or pass per=1 (one mark per unit of "
                         f"each category's total, rounded)")
    if units.sum() > MAX_UNITS:
        raise too_many(int(units.sum()), float(units.sum()))
    each = np.repeat(np.arange(len(sub)), units.astype(np.int64))
    ones = np.ones(len(each))
    return Tally(sub.iloc[each], ones, ones, sub.index.to_numpy(), each, each + 1)


def _grouping(sub, layer) -> list:
    """The columns a ``per=`` mark takes one value of; ValueError for a channel bound to a
    column whose values a mark of k units cannot share."""
    e = layer.encodings
    for channel in SINGLE:
        if isinstance(e[channel], str):
            raise ValueError(f"{channel}={e[channel]!r} cannot be combined with per={layer.per!r}: "
                             f"a mark of {layer.per} units has no single {channel}; drop "
                             f"{channel}= or per=")
    keys = []
    for channel in GROUPED:
        column = e[channel]
        if not isinstance(column, str) or (channel == "color" and column not in sub.columns
                                           and is_css_color(column)):
            continue
        check_column(sub, channel, column)
        if channel != "shape" and is_continuous(sub[column]):
            raise ValueError(f"{channel}={column!r} is numeric, so it cannot be combined with "
                             f"per={layer.per!r}: a mark of {layer.per} units stands for one "
                             f"category; bind {channel} to a categorical column (bin it with "
                             f"pd.cut), or drop per=")
        if column not in keys:
            keys.append(column)
    return keys


def too_many(marks: int, units: float) -> ValueError:
    """The refusal of ``marks`` marks, naming a ``per=`` that would draw ``units`` units in at
    most ``MAX_UNITS`` marks (1, 2 or 5 times a power of ten, with room for rounding)."""
    need = units / (0.95 * MAX_UNITS)
    step = 10 ** math.floor(math.log10(max(need, 1.0)))
    per = next(k * step for k in (1, 2, 5, 10) if k * step >= need)
    return ValueError(f"{marks} units is more than this widget lays out ({MAX_UNITS}); sample "
                      f"or aggregate the rows first, or draw one mark for several units: "
                      f"per={per:g} draws these {units:,.0f} units as about "
                      f"{units / per:,.0f} marks")


def mark_titles(df: pd.DataFrame, units, layers, plain: list) -> list:
    """Tooltip text per unit: ``plain`` (the rows' own tooltips) but for the marks of a
    ``per=`` layer, which give their category, the units they stand for and the rows they
    cover (one row by its label; more by their count and the first few labels)."""
    out = list(plain)
    for i, layer in enumerate(layers):
        if layer.per is None:
            continue
        keys = [c for c in dict.fromkeys(layer.encodings[ch] for ch in GROUPED)
                if isinstance(c, str) and c in df.columns]
        what = "units" if layer.count is None else str(layer.count)
        mine = np.nonzero(units.layer == i)[0]
        values = df.loc[[units.rows[k] for k in mine], keys].to_numpy(dtype=object)
        for k, rep in zip(mine, values):
            lines = [f"{c}: {v}" for c, v in zip(keys, rep)]
            lines.append(f"{what}: {units.amount[k]:,.4g}" + (
                f" ({units.fraction[k]:.0%} of a mark)" if units.fraction[k] < 1 else ""))
            covered = units.covered[units.cover_start[k]:units.cover_stop[k]].tolist()
            first = ", ".join(str(r) for r in covered[:3]) + (", ..." if len(covered) > 3 else "")
            lines.append(f"row: {covered[0]}" if len(covered) == 1
                         else f"rows: {len(covered):,} ({first})")
            out[k] = "\n".join(lines)
    return out
