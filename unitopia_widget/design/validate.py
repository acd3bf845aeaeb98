"""Argument checks shared by the public constructors: messages name the culprit."""
from __future__ import annotations

import difflib
import math
from numbers import Real

import numpy as np


def check_finite(owner: str, name: str, value) -> float:
    """``value`` as a float, or a ValueError naming ``owner.name`` and the value."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{owner}: {name} must be a number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{owner}: {name} must be finite, got {value!r}")
    return value


def check_positive(owner: str, name: str, value, allow_zero: bool = False) -> float:
    """A finite number > 0 (>= 0 with ``allow_zero``)."""
    value = check_finite(owner, name, value)
    if value < 0 or (value == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{owner}: {name} must be {bound}, got {value:g}")
    return value


def check_choice(owner: str, name: str, value, choices) -> str:
    """``value`` if it is one of ``choices``, else a ValueError listing them."""
    if value not in choices:
        listed = ", ".join(repr(c) for c in choices)
        raise ValueError(f"{owner}: {name} must be one of {listed}; got {value!r}")
    return value


def closest(name: str, candidates) -> str:
    """' (did you mean 'x'?)' for the closest candidate, or ''."""
    match = difflib.get_close_matches(str(name), [str(c) for c in candidates], n=1, cutoff=0.5)
    return f" (did you mean {match[0]!r}?)" if match else ""


def short(value, limit: int = 60) -> str:
    """``repr(value)`` of a name or path quoted in an error, cut to ``limit`` characters
    with an ellipsis so a huge value cannot flood the message."""
    text = str(value) if isinstance(value, str) else repr(value)
    return repr(text if len(text) <= limit else text[:limit - 1] + "…")


MAX_COORD = 1e9  # canvas px: larger coordinates are rejected (they only lose precision)


def check_coord(owner: str, name: str, value) -> float:
    """``value`` as a float within ±``MAX_COORD`` canvas px."""
    value = check_finite(owner, name, value)
    if abs(value) > MAX_COORD:
        raise ValueError(f"{owner}: {name} must lie within ±{MAX_COORD:g} canvas px, got {value:g}")
    return value


def check_points(owner: str, name: str, points, min_count: int) -> np.ndarray:
    """``points`` as a finite float64 (k, 2) array with k >= min_count."""
    try:
        arr = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}: {name} must be a (k, 2) array of numbers, got {points!r:.60}") from None
    if arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < min_count:
        raise ValueError(f"{owner}: {name} must be a (k, 2) array with k >= {min_count}, "
                         f"got shape {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"{owner}: {name} must be finite, got {float(arr[~np.isfinite(arr)][0])!r}")
    if np.abs(arr).max() > MAX_COORD:
        raise ValueError(f"{owner}: {name} must lie within ±{MAX_COORD:g} canvas px, "
                         f"got {np.abs(arr).max():g}")
    return arr


def check_box(owner: str, box):
    """None or a validated ``(x, y, w, h)`` tuple of floats with w, h > 0."""
    if box is None:
        return None
    if not hasattr(box, "__len__") or len(box) != 4:
        raise ValueError(f"{owner}: box must be None or (x, y, w, h), got {box!r}")
    x, y = check_coord(owner, "box x", box[0]), check_coord(owner, "box y", box[1])
    return (x, y, check_positive(owner, "box w", box[2]), check_positive(owner, "box h", box[3]))


def check_canvas_size(owner: str, canvas_size) -> tuple[float, float]:
    """``canvas_size`` as a ``(width, height)`` tuple of floats > 0."""
    if not hasattr(canvas_size, "__len__") or len(canvas_size) != 2:
        raise ValueError(f"{owner}: canvas_size must be (width, height), got {canvas_size!r}")
    return (check_positive(owner, "canvas width", canvas_size[0]),
            check_positive(owner, "canvas height", canvas_size[1]))
