"""Position channels: ``x=`` and ``y=`` bind a column to where a mark stands.

A numeric column maps to a linear (``x_scale="linear"``, the default) or log
(``"log"``) position across the container's extent along that axis (datetimes as
seconds, linear); any other
column to bands, one per category in sorted order (missing values a last band
named :data:`~.encodings.MISSING`). Here a value becomes a *fraction* of the
extent, in [0, 1]; the layout maps fractions to canvas px (``layout/positions``).
Missing, infinite or (log) non-positive numbers are an error naming
``dropna=True``, which drops those rows, as for ``size=``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .encodings import (MISSING, check_column, check_real, continuous_values, is_continuous,
                        is_temporal, sorted_unique)
from .validate import check_choice

POSITION_CHANNELS = ("x", "y")
POSITION_SCALES = ("linear", "log")
ARRANGEMENTS = ("free", "grid")


@dataclass
class Scale:
    """How one position channel reads its column, shared by the layers bound to it.

    ``kind``: "linear", "log" or "band"; ``domain``: (min, max) of the values
    (numeric kinds) or the categories in band order (``band``)."""

    column: str
    kind: str
    domain: tuple
    temporal: bool = False   # a datetime column: the domain is in seconds since 1970

    def fraction(self, series: pd.Series) -> tuple[np.ndarray, np.ndarray]:
        """``(t (n,), half (n,))``: each value's place in [0, 1] along the extent, and the
        half width of its band (0 for numbers), as fractions of the extent."""
        if self.kind == "band":
            index = {v: k for k, v in enumerate(self.domain)}
            missing = series.isna().to_numpy()
            k = np.array([index[MISSING] if gone else index[v] for v, gone in zip(series, missing)],
                         dtype=float)
            count = len(self.domain)
            return (k + 0.5) / count, np.full(len(k), 0.5 / count)
        values = _transform(self.kind, continuous_values(series))
        lo, hi = _transform(self.kind, np.array(self.domain, dtype=float))
        t = np.full(len(values), 0.5) if hi <= lo else (values - lo) / (hi - lo)
        return t, np.zeros(len(values))


def _transform(kind: str, values: np.ndarray) -> np.ndarray:
    return np.log10(values) if kind == "log" else values


def check_scale(channel: str, value) -> str:
    """``x_scale``/``y_scale``: "linear" or "log"."""
    return check_choice("Layer", f"{channel}_scale", value, POSITION_SCALES)


def check_arrange(value) -> str:
    """``arrange``: "free" (packed where the forces pull) or "grid" (rows and columns)."""
    return check_choice("Layer", "arrange", value, ARRANGEMENTS)


def position_scale(df: pd.DataFrame, channel: str, column, kind: str = "linear") -> Scale:
    """The ``Scale`` of ``channel=column`` over all rows of ``df`` (so layers bound to one
    column share it). ValueError for a missing column, a log scale of text, and missing,
    infinite or (log) non-positive numbers."""
    if not isinstance(column, str):
        raise TypeError(f"{channel} must be a column name or None, got {column!r}")
    check_column(df, channel, column)
    series = df[column]
    check_real(channel, column, series)
    if kind == "log" and not (is_continuous(series) and pd.api.types.is_numeric_dtype(series)):
        raise ValueError(f"{channel}={column!r} with {channel}_scale='log': the column must be "
                         f"numeric, got dtype {series.dtype}; use {channel}_scale='linear'")
    if not is_continuous(series):
        try:
            categories = sorted_unique(series) + ([MISSING] if series.isna().any() else [])
        except TypeError:
            raise TypeError(f"{channel}={column!r}: the column's values must be numbers or "
                            f"categories (text, ...); convert it (e.g. .astype(str))") from None
        return Scale(column, "band", tuple(categories))
    values = continuous_values(series)
    bad = invalid_values(values, kind)
    if bad.any():
        need = f"finite and > 0 ({channel}_scale='log')" if kind == "log" else "finite"
        raise ValueError(f"{channel}={column!r}: {int(bad.sum())} of {len(values)} rows are "
                         f"missing, infinite{' or <= 0' if kind == 'log' else ''} (e.g. "
                         f"{values[bad][0]!r}); values must be {need}; pass dropna=True to drop "
                         f"those rows")
    return Scale(column, kind, (float(values.min()), float(values.max())), is_temporal(series))


def invalid_values(values: np.ndarray, kind: str) -> np.ndarray:
    """Bool ``(n,)``: numbers a position scale of ``kind`` cannot place."""
    return ~np.isfinite(values) | ((values <= 0) if kind == "log" else False)


def invalid_position_rows(df: pd.DataFrame, bindings: dict) -> np.ndarray:
    """Bool ``(n,)``: rows whose numeric x/y values cannot be placed (what ``dropna`` drops)."""
    bad = np.zeros(len(df), dtype=bool)
    for channel in POSITION_CHANNELS:
        column = bindings.get(channel)
        if isinstance(column, str) and (df.columns == column).sum() == 1 and \
                is_continuous(df[column]):
            kind = bindings.get(f"{channel}_scale") or "linear"
            bad |= invalid_values(continuous_values(df[column]), kind)
    return bad
