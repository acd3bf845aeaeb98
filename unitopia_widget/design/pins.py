"""Pins: marks placed by hand, kept where they are put.

A pin holds one unit (a row drawn by a layer) at a canvas position and angle. The
layout does not move a pinned mark (neither the optimiser, the legalising rounds nor
the relocation moves); it is an obstacle for every layer in its container. A pinned
mark keeps its size encoding: it is scaled with the other marks of its layer by the
global scale, around its pinned centre. Pins are saved in the design JSON as
``"pins": [{"layer", "row", "x", "y", "angle"}]`` (x, y canvas px; angle degrees).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Integral, Real

import numpy as np

from .validate import check_finite, short


@dataclass(frozen=True)
class Pin:
    """One pinned unit: ``layer`` name, ``row`` index label, centre ``x, y`` canvas px,
    ``angle`` degrees (clockwise on screen)."""

    layer: str
    row: object
    x: float
    y: float
    angle: float = 0.0

    @property
    def key(self) -> tuple:
        return (self.layer, self.row)

    def to_json(self) -> dict:
        return {"layer": self.layer, "row": json_label(self.row), "x": self.x, "y": self.y,
                "angle": self.angle}

    @classmethod
    def from_json(cls, d) -> "Pin":
        if not isinstance(d, dict) or not {"layer", "row", "x", "y"} <= set(d):
            raise ValueError(f"design: each pin must be an object with \"layer\", \"row\", "
                             f"\"x\", \"y\" (and \"angle\"), got {d!r:.80}")
        if not isinstance(d["layer"], str):
            raise ValueError(f"design: a pin's layer must be a layer name, got {d['layer']!r:.60}")
        owner = f"design pin of row {d['row']!r:.40}"
        return cls(d["layer"], d["row"], check_finite(owner, "x", d["x"]),
                   check_finite(owner, "y", d["y"]), check_finite(owner, "angle", d.get("angle", 0.0)))


def json_label(label):
    """An index label as JSON can hold it (numpy scalars as Python ones)."""
    return label.item() if isinstance(label, np.generic) else label


def check_pin(pin: Pin, layer, canvas) -> None:
    """A ValueError unless ``pin``'s centre lies inside ``layer``'s container on ``canvas``."""
    rho = min(1.0, 600.0 / max(canvas))
    cover = layer.region.coverage(canvas, rho)
    i, j = int(math.floor(pin.y * rho)), int(math.floor(pin.x * rho))
    inside = 0 <= i < cover.shape[0] and 0 <= j < cover.shape[1] and cover[i, j] >= 0.5
    if not inside:
        raise ValueError(f"pin of row {pin.row!r:.40} at ({pin.x:.1f}, {pin.y:.1f}) is outside "
                         f"the container of layer {short(layer.name)}; pin it inside "
                         f"{layer.region!r:.80}")


def pin_values(name: str, value, count: int):
    """``value`` for ``count`` pins: None, one number, or ``count`` numbers; else a ValueError
    naming ``name``. Returns a list of floats (None where not given)."""
    if value is None:
        return [None] * count
    if isinstance(value, Real) and not isinstance(value, bool):
        return [check_finite("pin", name, value)] * count
    values = list(np.asarray(value, dtype=object).reshape(-1))
    if len(values) != count:
        raise ValueError(f"pin: {name} has {len(values)} values for {count} rows; give one "
                         f"number or one per row")
    return [check_finite("pin", name, v) for v in values]


def row_labels(rows) -> list:
    """The index labels ``rows`` names: one label, a list of them, or a DataFrame/Series
    (its index, e.g. ``w.selected``)."""
    if hasattr(rows, "index") and hasattr(rows, "iloc"):
        return list(rows.index)
    if isinstance(rows, (str, bytes, Integral, Real, tuple)) or np.isscalar(rows):
        return [rows]
    return list(rows)
