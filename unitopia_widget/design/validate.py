"""Argument checks shared by the public constructors: messages name the culprit."""
from __future__ import annotations

import difflib
import math
from numbers import Real


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
