"""The chart's legend (key): which colour is which category, what a mark's size means,
what one mark stands for.

``sections(...)`` reads the bound encodings and the laid-out marks and returns
``Section``s of ``Entry``s; ``render(sections, ...)`` draws them as one
``<g class="legend">`` block (its own ``<defs>`` inside, so stripping the group
strips everything) and returns ``(svg_text, width, height)`` in canvas px.

Every entry is a ``<g class="legend-entry" data-channel=... data-value=...>``.
Size entries are area-true: the mark drawn for value v has the box area that a
unit of value v has in the chart (the layer's own box area per unit of value,
taken from the placed units, so it holds at the final scale). A layer with a
``size_range`` has a linear size legend instead, titled with the drawn px of its
range and "not area-true"; a ``width_range``/``height_range`` is named in the unit key.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
import numpy as np
import pandas as pd

from ..design.encodings import (MISSING, MISSING_COLOR, continuous_values, is_css_color,
                                is_continuous, is_temporal, linear_extent, palette_for)
from ..design.groups import sorted_categories
from ..design.marks import Mark
from .text import text_width

FONT = 12            # px, entry labels
TITLE_FONT = 12      # px, section titles (bold)
LABEL_CHARS = 40     # labels longer than this are cut with an ellipsis
MOST_ENTRIES = 20    # a section lists at most this many categories, then "... and n more"
SWATCH = 16          # px, the long side of a colour or shape swatch and of the unit key's mark
PAD = 8              # px between items
BAR = (160, 12)      # px, numeric colour bar (w, h)
TICK_GAP = 6         # px kept between two tick labels
NEUTRAL = "#8c8c8c"  # size and unit-key marks of layers whose colour encodes a column


@dataclass
class Entry:
    """One item: a mark (``mark`` drawn in ``color`` over a ``w`` x ``h`` px box) and a label."""

    channel: str | None       # "color", "size", "shape", or None (the unit key)
    value: str                # data-value: the category, or the number a size entry stands for
    label: str
    mark: object = None       # a marks.Mark, None for a colour-bar tick
    color: str | None = None
    w: float = SWATCH
    h: float = SWATCH


@dataclass
class Section:
    title: str
    entries: list = field(default_factory=list)
    bar: tuple | None = None  # numeric colour: (lo, hi), a gradient; entries without a mark are
    #                           its ticks, those with one swatches under it ("missing")
    more: int = 0             # categories left out after the entries ("... and 9,990 more")


def capped(sec: Section, most: int = MOST_ENTRIES) -> Section:
    """``sec`` with its first ``most`` entries; the rest counted in ``sec.more``."""
    if len(sec.entries) > most:
        sec.more = len(sec.entries) - most
        sec.entries = sec.entries[:most]
    return sec


def clip(text, limit: int = LABEL_CHARS) -> str:
    text = str(text)
    return text if len(text) <= limit else text[:limit - 1] + "\u2026"


def _swatch(mark, long_side: float = SWATCH) -> tuple[float, float]:
    a = mark.aspect
    return (long_side, long_side / a) if a >= 1 else (long_side * a, long_side)


def round_values(lo: float, hi: float, most: int = 4, positive: bool = True) -> list[float]:
    """2 to ``most`` round numbers in [lo, hi] (1, 2, 2.5 or 5 times a power of ten),
    spread across the range (only those > 0 when ``positive``: sizes); the range's ends
    rounded to 2 significant digits if the range is too narrow for round steps."""
    if not hi > lo:
        return [float(f"{lo:.2g}")]
    top = int(math.floor(math.log10(hi - lo))) + 1
    steps = [m * 10.0 ** (e - 1) for e in range(top, top - 4, -1) for m in (5, 2.5, 2, 1)]
    for fewest in (3, 2):   # three or four values read best; two if no round step gives more
        for step in steps:
            ticks = np.arange(math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9) + 1) * step
            ticks = ticks[ticks > 0] if positive else ticks
            if fewest <= len(ticks) <= most:
                return [float(f"{t:.6g}") for t in ticks]
    inner = [float(f"{v:.2g}") for v in (lo, hi)]
    return sorted({min(max(v, lo), hi) for v in inner})


def _number(v: float) -> str:
    return f"{v:.6g}"


# date tick steps, fine to coarse: (unit, count); "s", "min", "h", "D" are fixed lengths
DATE_STEPS = (*[("s", k) for k in (1, 5, 15, 30)], *[("min", k) for k in (1, 5, 15, 30)],
              *[("h", k) for k in (1, 3, 6, 12)], *[("D", k) for k in (1, 2, 7, 14)],
              *[("M", k) for k in (1, 3, 6)],
              *[("Y", k) for k in (1, 2, 5, 10, 20, 25, 50, 100, 200, 500, 1000)])
SECONDS = {"s": 1, "min": 60, "h": 3600, "D": 86400}


def _date_steps(lo: float, hi: float, unit: str, count: int, most: int) -> list[float] | None:
    """Times (s since 1970, UTC) in [lo, hi] at whole multiples of ``count`` ``unit``s; None
    when there are more than ``most``."""
    if unit in SECONDS:
        step = SECONDS[unit] * count
        first, last = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
        return None if last - first + 1 > most else [k * float(step) for k in range(first, last + 1)]
    start, end = pd.Timestamp(lo, unit="s"), pd.Timestamp(hi, unit="s")
    every = count * (12 if unit == "Y" else 1)   # in months
    month = start.year * 12 + start.month - 1
    month += start > pd.Timestamp(year=start.year, month=start.month, day=1)
    month += -month % every
    if (end.year * 12 + end.month - 1 - month) // every + 1 > most:
        return None
    out = []
    while (t := pd.Timestamp(year=month // 12, month=month % 12 + 1, day=1)) <= end:
        out.append(t.value / 1e9)
        month += every
    return out


def _date_label(t: pd.Timestamp, unit: str, span: float) -> str:
    if unit == "Y":
        return f"{t:%Y}"
    if unit == "M":
        return f"{t:%b %Y}"
    if unit == "D":
        return f"{t.day} {t:%b %Y}"
    if unit == "s":
        return f"{t:%H:%M:%S}"
    return f"{t:%H:%M}" if span < 86400 else f"{t.day} {t:%b} {t:%H:%M}"


def date_ticks(lo: float, hi: float, most: int = 4) -> list[tuple[float, str]]:
    """``[(time, label), ...]``: 2 to ``most`` times in [lo, hi] (s since 1970, UTC) at the
    finest round step that gives no more (whole seconds ... years), labelled at that
    step's unit ("1970", "Jan 2024", "3 Jan 2024", "14:30"); one round time when no step
    gives two that few, the start when none is in the range."""
    single = None
    for unit, count in DATE_STEPS:
        times = _date_steps(lo, hi, unit, count, most)
        if times is not None and len(times) >= 2:
            return [(t, _date_label(pd.Timestamp(t, unit="s"), unit, hi - lo)) for t in times]
        if times and single is None:
            single = [(times[0], _date_label(pd.Timestamp(times[0], unit="s"), unit, hi - lo))]
    if single is not None:
        return single
    t = pd.Timestamp(lo, unit="s")
    return [(lo, f"{t.day} {t:%b %Y %H:%M:%S}")]


def spaced_ticks(lo: float, hi: float, temporal: bool, length: float, most: int = 5,
                 font: float = FONT, where=None) -> list[tuple[float, str]]:
    """``[(value, label), ...]`` of a scale ``length`` px long over [lo, hi]: the most ticks
    (at most ``most``) whose labels, centred on their ticks at ``font`` px, stay
    ``TICK_GAP`` px apart. ``where(value)``: the fraction of the length a value is at
    (default linear)."""
    where = where or (lambda v: 0.5 if hi <= lo else (v - lo) / (hi - lo))
    for count in range(most, 1, -1):
        ticks = (date_ticks(lo, hi, count) if temporal else
                 [(v, _number(v)) for v in round_values(lo, hi, count, positive=False)])
        if apart(ticks, length, font, where):
            return ticks
    return ticks[:1]


def apart(ticks, length: float, font: float, where) -> bool:
    """True when the labels of ``ticks`` (centred on ``where(value) * length``) keep
    ``TICK_GAP`` px between them."""
    at = sorted((where(v) * length, text_width(label, font)) for v, label in ticks)
    return all(x2 - x1 >= (w1 + w2) / 2 + TICK_GAP for (x1, w1), (x2, w2) in zip(at, at[1:]))


def neutral(layer, units, i) -> str | None:
    """The colour a layer's size and key marks are drawn in: grey when colour encodes a
    column (no category is meant), else the layer's own colour."""
    if layer.encodings["color"] is not None and not is_css_color(layer.encodings["color"]):
        return NEUTRAL
    return next((c for c, li in zip(units.colors, units.layer) if li == i), None)


def _rows_label(layer) -> str:
    rows = layer.rows
    if rows is None:
        return ""
    if "column" in rows:   # a by= layer is named by its value: the column alone says the rest
        if str(rows["value"]) == layer.name:
            return f" ({clip(rows['column'], 20)})"
        return f" ({clip(rows['column'], 20)} = {clip(rows['value'], 20)})"
    return " (chosen rows)"


def sections(df: pd.DataFrame, layers, units, boxes: np.ndarray, room: float = np.inf) -> list[Section]:
    """The legend of ``layers`` over ``units`` (design.units.Units). ``boxes``: ``(N, 2)`` drawn
    box width and height per unit, canvas px (from the placements); ``room``: the height a
    size legend's marks may take together before it shows only its two end values."""
    rows = df.loc[units.rows]
    out = []
    out.extend(_color_sections(rows, layers, units))
    out.extend(_shape_sections(rows, layers, units))
    out.extend(_size_sections(df, rows, layers, units, boxes, room))
    out.append(_unit_key(df, rows, layers, units, boxes))
    return out


def _color_sections(rows, layers, units) -> list[Section]:
    out = []
    columns = []
    for layer in layers:
        c = layer.encodings["color"]
        if isinstance(c, str) and c in rows.columns and c not in columns:
            columns.append(c)
    for c in columns:
        users = [i for i, layer in enumerate(layers) if layer.encodings["color"] == c]
        if all(layers[i].encodings["shape"] == c for i in users):
            continue   # the shape section draws these categories in their colours
        # a category's colour on the layer's mark; a plain disc when the layer draws several
        mark = layers[users[0]].mark if len(layers[users[0]].marks) == 1 else _disc()
        series = rows[c][np.isin(units.layer, users)]
        if is_continuous(series):
            v = continuous_values(series)
            v = v[np.isfinite(v)]
            lo, hi = float(v.min()), float(v.max())
            sec = Section(f"Color: {clip(c)}", bar=(lo, hi))
            sec.entries = [Entry("color", _number(t), label) for t, label in
                           spaced_ticks(lo, hi, is_temporal(series), BAR[0])]
            if series.isna().any():   # drawn grey, as a text column's missing values are
                sec.entries.append(Entry("color", MISSING, MISSING, mark, MISSING_COLOR,
                                         *_swatch(mark)))
        else:
            palette = palette_for(series)
            sec = Section(f"Color: {clip(c)}")
            sec.entries = [Entry("color", str(value), clip(value), mark, color, *_swatch(mark))
                           for value, color in palette.items()]
            capped(sec)
        out.append(sec)
    return out


def _disc():
    return Mark.shape("circle")


def _shape_sections(rows, layers, units) -> list[Section]:
    """One section per set of layers that draw the same categories with the same marks
    under ``shape=`` (each category drawn with its mark, in the category's colour when
    colour encodes the same column, else the layer's key colour)."""
    found = []   # (column, {category: (mark, colour)}, [layer indices])
    for i, layer in enumerate(layers):
        c = layer.encodings["shape"]
        if not (isinstance(c, str) and c in rows.columns):
            continue
        mine = np.flatnonzero(units.layer == i)
        first = {}   # category -> its first unit: that unit's mark is the category's mark
        for k, value in zip(mine, rows[c].to_numpy()[mine]):
            first.setdefault(value, k)
        same_colour = layer.encodings["color"] == c
        drawn = {value: (layer.marks[units.mark[k]],
                         units.colors[k] if same_colour else neutral(layer, units, i))
                 for value, k in first.items()}
        for column, seen, users in found:
            if column == c and all(seen.get(v, d) == d for v, d in drawn.items()):
                seen.update(drawn)
                users.append(i)
                break
        else:
            found.append((c, drawn, [i]))
    out = []
    for c, drawn, users in found:
        sec = Section(f"Shape: {clip(c)}" + _layers_note(layers, users))
        for value in sorted_categories(pd.Series(list(drawn))):
            mark, color = drawn[value]
            sec.entries.append(Entry("shape", str(value), clip(value), mark, color, *_swatch(mark)))
        out.append(capped(sec))
    return out


def _layers_note(layers, users) -> str:
    """`` (layer a)`` or `` (layers a, b)`` when a section holds some of several layers."""
    if len(users) == len(layers):
        return ""
    names = [clip(layers[i].name, 20) for i in users]
    return f" (layer{'s' if len(names) > 1 else ''} {', '.join(names)})"


def _size_sections(df, rows, layers, units, boxes, room) -> list[Section]:
    """One section per size column; layers sharing a column and its area per value share it."""
    out = []
    by_column: dict = {}
    for i, layer in enumerate(layers):
        c = layer.encodings["size"]
        if isinstance(c, str) and c in rows.columns and layer.size_range is not None:
            out.append(_linear_size_section(df, rows, layers, units, boxes, i, room))
        elif isinstance(c, str) and c in rows.columns:
            mine = units.layer == i
            values = rows[c].to_numpy(dtype=float)[mine]
            # silhouette area per unit of value: the same for layers whose sizes are shared
            silhouette = boxes[mine, 0] * boxes[mine, 1] * units.fill_fraction[mine]
            per_value = float(np.median(silhouette / values))
            by_column.setdefault(c, []).append((i, per_value, values))
    for c, found in by_column.items():
        groups = []
        for item in found:
            for g in groups:
                if abs(g[0][1] - item[1]) <= 0.01 * g[0][1]:
                    g.append(item)
                    break
            else:
                groups.append([item])
        for g in groups:
            note = _layers_note(layers, [i for i, _, _ in g])
            i, per_value, _ = g[0]
            mark, color = layers[i].mark, neutral(layers[i], units, i)
            values = np.concatenate([v for _, _, v in g])
            sec = Section(f"Size: {clip(c)} (area){note}")
            for v in round_values(float(values.min()), float(values.max())):
                box_area = per_value * v / mark.fill_fraction
                h = math.sqrt(box_area / mark.aspect)
                sec.entries.append(Entry("size", _number(v), _number(v), mark, color, h * mark.aspect, h))
            if sum(e.h for e in sec.entries) > room:   # big marks: the ends of the range only
                sec.entries = [sec.entries[0], sec.entries[-1]]
            out.append(sec)
    return out


def drawn_range(df, rows, layer, units, boxes, i: int, channel: str):
    """``(px_per_extent, (min_px, max_px))`` of layer ``i``'s ``<channel>_range`` as drawn:
    the scale's factor from the range's px to the placed marks' px (the box's long side for
    size, its width or height), and the drawn extents of the column's smallest and largest
    values."""
    span, column = getattr(layer, f"{channel}_range"), layer.encodings[channel]
    mine = units.layer == i
    values = rows[column].to_numpy(dtype=float)[mine]
    lo, hi = _value_range(df[column])   # the scale spans the whole column, as in the layout
    side = {"size": boxes[mine].max(axis=1), "width": boxes[mine, 0],
            "height": boxes[mine, 1]}[channel]
    k = float(np.median(side / linear_extent(values, span, lo, hi)))
    return k, (k * span[0], k * span[1])


def _value_range(series) -> tuple[float, float]:
    """(min, max) of the finite, positive values of a numeric column."""
    v = series.to_numpy(dtype=float, na_value=np.nan)
    v = v[np.isfinite(v) & (v > 0)]
    return float(v.min()), float(v.max())


def _linear_size_section(df, rows, layers, units, boxes, i: int, room) -> Section:
    """The size legend of a layer with a ``size_range``: marks whose long side follows the
    linear scale as drawn, titled with its drawn px range and "not area-true"."""
    layer = layers[i]
    c, span = layer.encodings["size"], layer.size_range
    k, (lo_px, hi_px) = drawn_range(df, rows, layer, units, boxes, i, "size")
    lo, hi = _value_range(df[c])
    mark, color = layer.mark, neutral(layer, units, i)
    sec = Section(f"Size: {clip(c)} (linear {lo_px:.3g}-{hi_px:.3g} px, not area-true)"
                  f"{_layers_note(layers, [i])}")
    for v in round_values(lo, hi):
        long = k * float(linear_extent(v, span, lo, hi))
        w, h = (long, long / mark.aspect) if mark.aspect >= 1 else (long * mark.aspect, long)
        sec.entries.append(Entry("size", _number(v), _number(v), mark, color, w, h))
    if sum(e.h for e in sec.entries) > room:
        sec.entries = [sec.entries[0], sec.entries[-1]]
    return sec


def _range_note(df, rows, layer, units, boxes, i: int, channel: str) -> str:
    """`` (linear a-b px)`` for a channel with a range, as drawn; else ``""``."""
    if getattr(layer, f"{channel}_range", None) is None:
        return ""
    _, (lo_px, hi_px) = drawn_range(df, rows, layer, units, boxes, i, channel)
    return f" (linear {lo_px:.3g}-{hi_px:.3g} px, not data-true)"


def _unit_key(df, rows, layers, units, boxes) -> Section:
    # the total only over several layers: one layer's entry already counts its rows
    total = f" ({len(units.rows)} rows)" if len(layers) > 1 else ""
    keys = {_stands_for(layer) for layer in layers}
    tallied = any(layer.count is not None or layer.per is not None for layer in layers)
    if tallied:   # one mark for k units: the key says k, and of what
        total = f" ({units.amount.sum():,.6g} units)" if len(layers) > 1 else ""
    sec = Section(f"{next(iter(keys))}{total}" if len(keys) == 1 else "Marks")
    for i, layer in enumerate(layers):
        count = int((units.layer == i).sum())
        color = neutral(layer, units, i)
        # channels that have no section of their own (color, shape and size do)
        bound = [f"{k}: {clip(v, 20)}{_range_note(df, rows, layer, units, boxes, i, k)}"
                 for k, v in layer.encodings.items()
                 if isinstance(v, str) and k not in ("color", "shape", "size")]
        # one layer: its name (an internal "layer-1") says nothing the title does not
        named = f"{clip(layer.name, 30)}{_rows_label(layer)}: " if len(layers) > 1 else ""
        label = f"{named}{count} rows"
        if tallied:
            label = (f"{named}{count} marks for {units.amount[units.layer == i].sum():,.6g} "
                     f"{_unit_name(layer)}" + (f" ({_stands_for(layer)})" if len(keys) > 1 else ""))
        if bound:
            label += " \u00b7 " + ", ".join(bound)
        sec.entries.append(Entry(None, layer.name[:200], label, layer.mark, color,
                                 *_swatch(layer.mark)))
    return sec


def _unit_name(layer) -> str:
    """What a layer's units are: rows, or the ``count=`` column's units."""
    return "rows" if layer.count is None else clip(layer.count, 30)


def _stands_for(layer) -> str:
    """``"1 mark = k rows"`` (or ``= k <count column>``): what one of the layer's marks is."""
    k = 1 if layer.per is None else layer.per
    name = "row" if layer.count is None and k == 1 else _unit_name(layer)
    return f"1 mark = {k:,} {name}"
