"""Encodings: DataFrame rows -> per-unit size factors, colours, margins and order.

``size`` makes the AREA of each mark proportional to its value; ``width`` and
``height`` make that extent proportional. Factors are normalised to a mean of
1; the solver's one global scale turns them into canvas pixels, so ratios are
exact after layout.
"""
from __future__ import annotations

import re
import warnings
from dataclasses import dataclass
from numbers import Number, Real

import numpy as np
import pandas as pd
from PIL import ImageColor

from .validate import closest

# Tableau 20: ten hues, each then in a light tint; distinct to 20 categories
CATEGORICAL = ("#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
               "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#79706e",
               "#a0cbe8", "#ffbe7d", "#ff9d9a", "#86bcb6", "#8cd17d",
               "#f1ce63", "#d4a6c8", "#fabfd2", "#d7b5a6", "#d4d0cc")
MISSING = "missing"       # the category of missing values in a colour column
MISSING_COLOR = "#bab0ac"  # grey, drawn last in the legend
SEQUENTIAL = ("#f7e98e", "#9fd27f", "#3fae8a", "#24868e", "#355f8d", "#46327e")  # light -> dark
DEFAULT_COLOR = "#4e79a7"
NUMERIC_CHANNELS = ("size", "width", "height", "margin", "count")   # count: units per row
MARGINS_OF = ("median", "own")   # what a margin is a fraction of: see capped_margin


@dataclass
class Encoded:
    """Per-unit encodings of one layer, arrays of shape ``(n,)``."""

    area: np.ndarray      # silhouette area factor (mean 1 over the bound column)
    width: np.ndarray     # extra x stretch (width encoding), 1 when unbound
    height: np.ndarray    # extra y stretch (height encoding), 1 when unbound
    margin: np.ndarray    # gap to each neighbour, fraction of the mark's size
    order: np.ndarray     # rank in emission order, 0 first
    colors: list          # CSS hex colour per unit; None keeps the mark's own colours


def footprint(margin):
    """Footprint side over drawn side (``(N,)`` or a float) for ``margin``: two marks with
    margin ``m`` stand ``m`` times their size apart, each keeping half that gap on every side
    (so the container's edge keeps half of it too)."""
    return 1.0 + margin


def capped_margin(margin: np.ndarray, half_w: np.ndarray, half_h: np.ndarray,
                  of: str = "median") -> np.ndarray:
    """``(n,)`` the margin fraction each of one layer's marks keeps, for ``footprint``.

    ``of="own"``: ``margin`` as given, a fraction of each mark's own size however large.
    ``of="median"``: a fraction of the mark's size up to the layer's median mark's, so a
    mark larger than the median keeps the gap the median mark keeps (its fraction falls as
    median size / its size); tied and small marks keep theirs. Without the cap, a few large
    marks' own gaps are wider than a typical mark and read as empty room no mark may enter.
    ``half_w``, ``half_h``: ``(n,)`` box half sides at scale 1; a mark's size is their
    geometric mean."""
    if of == "own":
        return margin
    size = np.sqrt(half_w * half_h)
    return margin * np.minimum(1.0, np.median(size) / size)


def is_css_color(value) -> bool:
    """True when ``value`` is a colour string PIL/CSS understands and not a column."""
    if not isinstance(value, str):
        return False
    try:
        ImageColor.getrgb(value)
    except ValueError:
        return False
    return True


def check_column(df: pd.DataFrame, channel: str, column) -> None:
    """A ValueError naming the channel, the column and the closest existing one; or naming
    the column when the DataFrame has several columns of that name (``df[column]`` would
    be a DataFrame, not one column)."""
    if column not in df.columns:
        names = ", ".join(repr(c) for c in df.columns)
        raise ValueError(f"{channel}={column!r}: no such column{closest(column, df.columns)}; "
                         f"the columns are {names}")
    count = int((df.columns == column).sum())
    if count > 1:
        raise ValueError(f"{channel}={column!r}: the DataFrame has {count} columns named "
                         f"{column!r}; rename them, or drop the repeats with "
                         f"df.loc[:, ~df.columns.duplicated()]")


def check_real(channel: str, column, series: pd.Series) -> None:
    """A ValueError naming the channel, the column and its dtype when ``series`` holds
    numbers that are not real: a complex dtype, or an object column holding complex
    numbers or numbers mixed with other values (text, lists, ...)."""
    if pd.api.types.is_complex_dtype(series):
        raise ValueError(f"{channel}={column!r}: the column must hold real numbers, got dtype "
                         f"{series.dtype}; pass the real part (df[{column!r}].real) or the "
                         f"magnitude (abs)")
    if series.dtype != object:
        return
    values = series.dropna()
    kinds = {type(v).__name__ for v in values}
    numbers = [isinstance(v, Number) and not isinstance(v, bool) for v in values]
    unreal = any(isinstance(v, Number) and not isinstance(v, Real) for v in values)
    if unreal or (any(numbers) and not all(numbers)):
        raise ValueError(f"{channel}={column!r}: the column (dtype object) mixes "
                         f"{', '.join(sorted(kinds))}; it must hold real numbers only (or, for "
                         f"x and y, categories only); convert it (pd.to_numeric, .astype(str))")


def numeric_column(df: pd.DataFrame, channel: str, column, positive: bool) -> np.ndarray:
    """The column as float64, checked: numeric, finite, and > 0 (or >= 0)."""
    check_column(df, channel, column)
    series = df[column]
    check_real(channel, column, series)
    if not pd.api.types.is_numeric_dtype(series) or pd.api.types.is_bool_dtype(series):
        raise ValueError(f"{channel}={column!r}: the column must be numeric, "
                         f"got dtype {series.dtype}")
    values = series.to_numpy(dtype=float, na_value=np.nan)
    bad = ~np.isfinite(values) | ((values <= 0) if positive else (values < 0))
    if bad.any():
        need = "> 0" if positive else ">= 0"
        missing = int(np.isnan(values).sum())
        raise ValueError(f"{channel}={column!r}: {int(bad.sum())} of {len(values)} rows are "
                         f"missing, infinite or not {need} ({missing} missing); values must be "
                         f"finite and {need}; pass dropna=True to drop those rows")
    return values


def invalid_rows(df: pd.DataFrame, bindings: dict) -> np.ndarray:
    """Bool ``(n,)``: rows whose bound numeric values cannot be encoded."""
    bad = np.zeros(len(df), dtype=bool)
    for channel in NUMERIC_CHANNELS:
        column = bindings.get(channel)
        if isinstance(column, str) and (df.columns == column).sum() == 1 and \
                is_real(df[column]):
            values = df[column].to_numpy(dtype=float, na_value=np.nan)
            floor_ok = values >= 0 if channel in ("margin", "count") else values > 0
            bad |= ~np.isfinite(values) | ~floor_ok
    return bad


def encode(df: pd.DataFrame, size=None, width=None, height=None, color=None,
           margin=0.0, order=None, palette: dict | None = None, domain=None) -> Encoded:
    """Encode the rows of ``df``. ``palette`` maps category -> colour and ``domain`` is the
    (min, max) of a numeric colour scale, both shared by layers (default: from ``df``)."""
    n = len(df)
    if size is not None and (width is not None or height is not None):
        raise ValueError(f"size={size!r} cannot be combined with width={width!r} or "
                         f"height={height!r}; bind size alone, or width and/or height")
    area = _factor(df, "size", size, n)
    w = _factor(df, "width", width, n)
    h = _factor(df, "height", height, n)
    if isinstance(margin, str):
        margins = numeric_column(df, "margin", margin, positive=False)
    else:
        m = float(margin)
        if not np.isfinite(m) or m < 0:
            raise ValueError(f"margin must be a column name or a number >= 0, got {margin!r}")
        margins = np.full(n, m)
    return Encoded(area=area, width=w, height=h, margin=margins,
                   order=_order(df, order), colors=_colors(df, color, palette, domain))


def _factor(df, channel, column, n) -> np.ndarray:
    if column is None:
        return np.ones(n)
    if not isinstance(column, str):
        raise TypeError(f"{channel} must be a column name or None, got {column!r}")
    values = numeric_column(df, channel, column, positive=True)
    return values / values.mean()


def linear_extent(values, span, lo, hi) -> np.ndarray:
    """Extents (px, shape of ``values``) of a linear scale from the value range ``(lo, hi)``
    onto ``span = (min_px, max_px)`` (``size_range=`` and the like); ``max_px`` when
    ``lo == hi``."""
    values = np.asarray(values, dtype=float)
    t = np.ones_like(values) if hi <= lo else (values - lo) / (hi - lo)
    return span[0] + t * (span[1] - span[0])


def _order(df, column) -> np.ndarray:
    n = len(df)
    if column is None:
        return np.arange(n)
    check_column(df, "order", column)
    ranks = np.empty(n, dtype=np.int64)
    try:
        ranks[np.argsort(df[column].to_numpy(), kind="stable")] = np.arange(n)
    except TypeError:
        kinds = sorted({type(v).__name__ for v in df[column]})
        raise TypeError(f"order={column!r}: the column's values cannot be put in order (they are "
                        f"{', '.join(kinds)}); bind order to a column of numbers, dates or text"
                        ) from None
    return ranks


def natural_key(value):
    """Sort key that reads digit runs in text as numbers: "cat2" before "cat10"."""
    if isinstance(value, str):
        return tuple((0, int(part), "") if part.isdigit() else (1, 0, part)
                     for part in re.split(r"(\d+)", value) if part)
    return value


def sorted_unique(series: pd.Series) -> list:
    """The distinct non-missing values of ``series``: a pandas Categorical's own category
    order, else natural order when they compare (cat2 before cat10), else first-seen order."""
    if isinstance(series.dtype, pd.CategoricalDtype):
        present = set(series.dropna())
        return [c for c in series.cat.categories if c in present]
    uniq = list(pd.unique(series.dropna()))
    try:
        return sorted(uniq, key=natural_key)
    except TypeError:
        return list(uniq)


def palette_for(series: pd.Series, name=None) -> dict:
    """A categorical palette: one colour per distinct value, in sorted order, then
    :data:`MISSING` in grey when values are missing. Warns (naming the column ``name``)
    when there are more categories than distinct colours."""
    series = series if isinstance(series, pd.Series) else pd.Series(list(series))
    uniq = sorted_unique(series)
    if name is not None and len(uniq) > len(CATEGORICAL):
        repeated = ", ".join(repr(str(v)) for v in uniq[len(CATEGORICAL):len(CATEGORICAL) + 3])
        more = len(uniq) - len(CATEGORICAL)
        warnings.warn(f"color={name!r}: {len(uniq)} categories but {len(CATEGORICAL)} distinct "
                      f"colours; {more} categories ({repeated}{', ...' if more > 3 else ''}) repeat "
                      f"the colours of the first ones; bind color to a column of fewer "
                      f"categories, or to a numeric column", stacklevel=3)
    palette = {v: CATEGORICAL[i % len(CATEGORICAL)] for i, v in enumerate(uniq)}
    if series.isna().any():
        palette[MISSING] = MISSING_COLOR
    return palette


def missing_warning(series: pd.Series, name) -> None:
    """Warn that ``series`` (bound to color=``name``) has missing values, drawn grey."""
    count = int(series.isna().sum())
    if count:
        warnings.warn(f"color={name!r}: {count} of {len(series)} rows are missing; they are "
                      f"drawn as the category {MISSING!r} in grey", stacklevel=3)


def _colors(df, color, palette, domain=None) -> list[str]:
    n = len(df)
    if color is None:   # unbound: every mark keeps its own colours
        return [None] * n
    if not isinstance(color, str):
        raise TypeError(f"color must be a column name or a CSS colour, got {color!r}")
    if color not in df.columns:
        if is_css_color(color):
            return [_hex(color)] * n
        raise ValueError(f"color={color!r} is neither a column{closest(color, df.columns)} "
                         f"nor a CSS colour; the columns are "
                         + ", ".join(repr(c) for c in df.columns))
    check_column(df, "color", color)
    series = df[color]
    if is_continuous(series):
        return sequential(continuous_values(series), domain)
    try:
        palette = palette if palette is not None else palette_for(series, color)
        missing = series.isna().to_numpy()
        return [palette.get(MISSING, MISSING_COLOR) if gone else palette.get(v, DEFAULT_COLOR)
                for v, gone in zip(series, missing)]
    except TypeError:
        raise unhashable("color", color, series) from None


def is_real(series: pd.Series) -> bool:
    """True for a column of real numbers: numeric, not bool, not complex."""
    return (pd.api.types.is_numeric_dtype(series) and not pd.api.types.is_bool_dtype(series)
            and not pd.api.types.is_complex_dtype(series))


def is_temporal(series: pd.Series) -> bool:
    """True for a datetime column (timezone-aware too)."""
    return pd.api.types.is_datetime64_any_dtype(series)


def is_continuous(series: pd.Series) -> bool:
    """True for a column that colour encodes on a continuous scale: numbers or datetimes."""
    return is_temporal(series) or is_real(series)


def continuous_values(series: pd.Series) -> np.ndarray:
    """float ``(n,)`` of a continuous column: the numbers, or a datetime's seconds since
    1970 (UTC); NaN where missing."""
    if is_temporal(series):
        stamps = series.dt.tz_convert(None) if series.dt.tz is not None else series
        seconds = (stamps - pd.Timestamp(0)) / pd.Timedelta(seconds=1)
        return seconds.to_numpy(dtype=float, na_value=np.nan)
    return series.to_numpy(dtype=float, na_value=np.nan)


def unhashable(channel: str, column, series) -> TypeError:
    """The error for a categorical channel bound to a column of unhashable values."""
    kinds = sorted({type(v).__name__ for v in series})
    return TypeError(f"{channel}={column!r}: the column's values must be categories (text, "
                     f"numbers, ...) to pick colours from, got {', '.join(kinds)}; bind "
                     f"{channel} to another column, or convert this one (e.g. .astype(str))")


def sequential(values: np.ndarray, domain=None) -> list[str]:
    """Hex colours of a light-to-dark sequential scale over ``domain`` (min, max; default the
    range of ``values``); NaN is grey."""
    stops = np.array([ImageColor.getrgb(c) for c in SEQUENTIAL], dtype=float)
    lo, hi = domain if domain is not None else (np.nanmin(values), np.nanmax(values))
    t = np.zeros_like(values) if hi <= lo else (values - lo) / (hi - lo)
    out = []
    for v in t:
        if not np.isfinite(v):
            out.append("#bab0ac")
            continue
        x = v * (len(stops) - 1)
        i = min(int(x), len(stops) - 2)
        rgb = stops[i] + (stops[i + 1] - stops[i]) * (x - i)
        out.append("#%02x%02x%02x" % tuple(int(round(c)) for c in rgb))
    return out


def _hex(color: str) -> str:
    rgb = ImageColor.getrgb(color)[:3]
    return "#%02x%02x%02x" % rgb


def rgba(colors: list) -> np.ndarray:
    """uint8 ``(n, 4)`` RGBA of hex colours (None, a mark's own colours, as the default)."""
    out = np.full((len(colors), 4), 255, dtype=np.uint8)
    for i, c in enumerate(colors):
        out[i, :3] = ImageColor.getrgb(c or DEFAULT_COLOR)[:3]
    return out


def tooltip_fields(df: pd.DataFrame, tooltip=None) -> list[tuple]:
    """``[(column, format or None), ...]`` of ``tooltip=``: None (every column), a list of
    columns and ``(column, format)`` pairs, or a dict ``{column: format or None}``; formats
    are Python format specs (".1f", ",d", "%Y-%m-%d" for dates). ValueError for a missing
    column or a format its values do not take."""
    if tooltip is None:
        return [(c, None) for c in df.columns]
    if isinstance(tooltip, str):
        tooltip = [tooltip]
    items = list(tooltip.items()) if isinstance(tooltip, dict) else \
        [tuple(t) if isinstance(t, (list, tuple)) else (t, None) for t in tooltip]
    fields = []
    for item in items:
        if len(item) != 2 or not (item[1] is None or isinstance(item[1], str)):
            raise ValueError(f"tooltip: each entry must be a column or (column, format), got "
                             f"{item!r}; e.g. tooltip=['Task', ('Duration', '.1f')]")
        column, fmt = item
        check_column(df, "tooltip", column)
        if fmt is not None and len(df):
            try:
                _formatted(df[column].iloc[0], fmt)
            except (ValueError, TypeError) as exc:
                raise ValueError(f"tooltip: format {fmt!r} does not apply to column "
                                 f"{column!r} (dtype {df[column].dtype}): {exc}") from None
        fields.append((column, fmt))
    return fields


def _formatted(value, fmt) -> str:
    if fmt is None or pd.isna(value):
        return str(value)
    return format(value, fmt)


def titles(df: pd.DataFrame, tooltip=None) -> list[str]:
    """One tooltip per row: ``column: value`` lines of the ``tooltip=`` columns (see
    :func:`tooltip_fields`; default every column)."""
    fields = tooltip_fields(df, tooltip)
    if not fields:
        return [""] * len(df)
    cols = [df[c].tolist() for c, _ in fields]
    return ["\n".join(f"{c}: {_formatted(v, fmt)}" for (c, fmt), v in zip(fields, row))
            for row in zip(*cols)]


MIN_DRAWN = 2.0   # px: marks drawn narrower than this are hard to see, and warned about


def warn_small_marks(table: pd.DataFrame, layers) -> None:
    """Warn when the smallest laid-out marks of placements ``table`` (its ``width`` and
    ``height`` columns, px) are under ``MIN_DRAWN`` px across, naming the size channels of
    ``layers`` that spread them and what to do instead."""
    side = np.minimum(table["width"].to_numpy(), table["height"].to_numpy())
    if not len(side) or side.min() >= MIN_DRAWN:
        return
    bound = sorted({f"{c}={layer.encodings[c]!r}" for layer in layers
                    for c in ("size", "width", "height") if isinstance(layer.encodings[c], str)})
    small = int((side < MIN_DRAWN).sum())
    # the spread of the side that varies most: strands spread their height, not their width
    w, h = table["width"].to_numpy(), table["height"].to_numpy()
    ratio = max(w.max() / w.min(), h.max() / h.min())
    spread = f" ({', '.join(bound)} spans {ratio:,.0f}x in extent)" if bound else ""
    warnings.warn(f"{small} of {len(side)} marks are drawn under {MIN_DRAWN:g} px across (the "
                  f"smallest {side.min():.2g} px){spread}; bind a log-scaled column "
                  f"(np.log1p), map it onto a range of sizes (size_range=(min_px, max_px), or "
                  f"width_range/height_range) or aggregate rows into fewer, larger marks",
                  stacklevel=3)
