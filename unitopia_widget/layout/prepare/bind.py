"""Binding: every layer's rows encoded into ``Units`` (one per row, layers concatenated
in drawing order)."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ...design.encodings import (Encoded, capped_margin, check_column, continuous_values, encode,
                                 linear_extent, is_continuous, missing_warning, palette_for,
                                 unhashable)
from ...design.bounds import MAX_UNITS
from ...design.groups import mark_choice
from ...design.tally import ink_clip
from ...design.units import Units
from . import positions
from .tally import tally, too_many


def layer_rows(df: pd.DataFrame, layer) -> pd.DataFrame:
    """The rows of ``df`` that ``layer.rows`` selects."""
    rows = layer.rows
    if rows is None:
        return df
    if "column" in rows:
        check_column(df, f"layer {layer.name!r} rows", rows["column"])
        return df[df[rows["column"]] == rows["value"]]
    missing = [i for i in rows["index"] if i not in df.index]
    if missing:
        raise ValueError(f"layer {layer.name!r}: {len(missing)} of its rows are not in the "
                         f"DataFrame (first missing index label: {missing[0]!r})")
    return df.loc[rows["index"]]


def bind(df: pd.DataFrame, layers, warn: bool = True) -> Units:
    """Encode all layers. Raises ValueError for empty layers or bad bindings. ``warn``:
    warn about colour columns with missing values or more categories than colours (False
    when the caller has warned about the same design already)."""
    color_cols = {layer.encodings["color"] for layer in layers
                  if isinstance(layer.encodings["color"], str) and layer.encodings["color"] in df.columns}
    palettes = {}
    for c in color_cols:
        check_column(df, "color", c)
        if warn:   # numbers and text alike: missing values are drawn grey
            missing_warning(df[c], c)
        if not is_continuous(df[c]):
            try:
                palettes[c] = palette_for(df[c], c if warn else None)
            except TypeError:
                raise unhashable("color", c, df[c]) from None
    # numeric colours: one scale per column, shared by the layers (as the palettes are)
    domains = {c: _finite_range(df[c]) for c in color_cols if c not in palettes}
    parts, rows, sprites = [], [], {}
    tallies = _tallies(df, layers)
    position, band, position_scales = positions.bind_positions(
        df, layers, lambda _, layer: tallies[layers.index(layer)].frame)
    for i, layer in enumerate(layers):
        sub = tallies[i].frame   # one row per mark: the row it is encoded from
        e = layer.encodings
        enc: Encoded = encode(sub, size=e["size"], width=e["width"], height=e["height"],
                              color=e["color"], margin=e["margin"], order=e["order"],
                              palette=palettes.get(e["color"]), domain=domains.get(e["color"]))
        for attr, channel in (("area", "size"), ("width", "width"), ("height", "height")):
            span = getattr(layer, f"{channel}_range")
            if span is not None and e[channel] is None:
                raise ValueError(f"layer {layer.name!r}: {channel}_range={span!r} needs "
                                 f"{channel}=<column>; bind {channel} to a numeric column, or "
                                 f"set {channel}_range=None")
            if e[channel] is not None:   # encode normalises per layer; keep layers comparable
                column = sub[e[channel]].to_numpy(dtype=float)
                if span is None:
                    setattr(enc, attr, getattr(enc, attr) * column.mean() / _positive_mean(df[e[channel]]))
                else:   # linear extents over the whole column's range; size is their square
                    setattr(enc, attr, _ranged(column, df[e[channel]], span, channel == "size"))
        choice = mark_choice(df, sub, layer)
        feet = [m.as_footprint(layer.footprint) for m in layer.marks]   # what collides
        sprite = np.array([sprites.setdefault(m, len(sprites)) for m in feet])[choice]
        aspect = np.array([m.aspect for m in feet])[choice]
        fill = np.array([m.fill_fraction for m in feet])[choice]
        # the box whose silhouette has area enc.area: h0 * (aspect * h0) * fill_fraction = area
        h0 = np.sqrt(enc.area / (aspect * fill))
        half_w, half_h = h0 * aspect * enc.width / 2, h0 * enc.height / 2
        enc.margin = capped_margin(enc.margin, half_w, half_h, layer.margin_of)
        parts.append((i, half_w, half_h, enc, choice, sprite))
        rows.extend(sub.index.tolist())
    cat = lambda f: np.concatenate([f(p) for p in parts])  # noqa: E731
    fraction = np.concatenate([t.fraction for t in tallies])
    mark_of = [(layers[p[0]], m) for p in parts for m in p[4]]
    clip = np.ones(len(fraction))
    for k in np.nonzero(fraction < 1)[0]:   # a partial mark: clipped where its ink is the fraction
        clip[k] = ink_clip(mark_of[k][0].marks[mark_of[k][1]], fraction[k])
    offsets = np.cumsum([0] + [len(t.covered) for t in tallies[:-1]])
    return Units(rows=rows, layer=cat(lambda p: np.full(len(p[3].area), p[0])),
                 half_w=cat(lambda p: p[1]), half_h=cat(lambda p: p[2]),
                 area=cat(lambda p: p[3].area * p[3].width * p[3].height),
                 margin=cat(lambda p: p[3].margin), order=cat(lambda p: p[3].order),
                 colors=[c for p in parts for c in p[3].colors],
                 mark=cat(lambda p: p[4]), sprite=cat(lambda p: p[5]), sprites=list(sprites),
                 position=position, band=band, position_scales=position_scales,
                 amount=np.concatenate([t.amount for t in tallies]), fraction=fraction, clip=clip,
                 covered=np.concatenate([t.covered for t in tallies]),
                 cover_start=np.concatenate([t.start + o for t, o in zip(tallies, offsets)]),
                 cover_stop=np.concatenate([t.stop + o for t, o in zip(tallies, offsets)]))


def _tallies(df: pd.DataFrame, layers) -> list:
    """Each layer's ``Tally`` (its marks); ValueError for a layer with nothing to draw or
    for more marks than a chart lays out, naming a ``per=`` that would fit."""
    out = []
    for layer in layers:
        sub = layer_rows(df, layer)
        if len(sub) == 0:
            raise ValueError(f"layer {layer.name!r} has no rows to draw")
        out.append(tally(sub, layer))
        if len(out[-1].frame) == 0:
            raise ValueError(f"layer {layer.name!r} draws no marks: the units of its "
                             f"{len(sub)} rows (count={layer.count!r}) round to none with "
                             f"per={layer.per!r}, rounding={layer.rounding!r}; use a smaller "
                             f"per=, rounding='ceil' or partial=True")
    marks = sum(len(t.frame) for t in out)
    if marks > MAX_UNITS:
        raise too_many(marks, float(sum(t.amount.sum() for t in out)))
    return out


def _ranged(values: np.ndarray, series: pd.Series, span, squared: bool) -> np.ndarray:
    """``(n,)`` factors of ``values`` on the linear scale ``span`` over the finite, positive
    values of ``series`` (mean 1 over the column), squared for an area."""
    full = series.to_numpy(dtype=float, na_value=np.nan)
    full = full[np.isfinite(full) & (full > 0)]
    power = 2 if squared else 1
    mapped = linear_extent(values, span, full.min(), full.max()) ** power
    return mapped / (linear_extent(full, span, full.min(), full.max()) ** power).mean()


def _positive_mean(series: pd.Series) -> float:
    """Mean of the finite, positive values of a numeric column (1 if none)."""
    v = series.to_numpy(dtype=float, na_value=np.nan)
    v = v[np.isfinite(v) & (v > 0)]
    return float(v.mean()) if len(v) else 1.0


def _finite_range(series: pd.Series):
    """(min, max) of the finite values of a numeric or datetime column, or None."""
    v = continuous_values(series)
    v = v[np.isfinite(v)]
    return (float(v.min()), float(v.max())) if len(v) else None
