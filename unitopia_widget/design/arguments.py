"""The ``Chart`` constructor's and the design file's top-level arguments, checked and read:
the canvas, seed, scales and background, ``mark=`` made Marks, and the rows spec of a
``by=`` layer. Each error names the argument, the value and what is accepted."""
from __future__ import annotations

from numbers import Integral

import numpy as np
import pandas as pd

from ..io.images import image_data_url, load_image
from .scene import MAX_MARKS, _mark, _mark_set, is_category_dict
from .validate import check_finite

SCALES = ("shared", "independent")


def rows_of(df: pd.DataFrame, by, value) -> dict:
    """The rows spec of the layer of ``df[by] == value``, JSON-safe for the design file:
    the value as a plain str/int/float/bool when that selects the same rows, else the index."""
    mask = (df[by] == value).to_numpy()
    plain = value.item() if isinstance(value, np.generic) else value
    if isinstance(plain, (str, int, float, bool)) and np.array_equal((df[by] == plain).to_numpy(), mask):
        return {"column": by, "value": plain}
    return {"index": df.index[mask].tolist()}


def check_scales(value, what: str = "scales") -> str:
    """``"shared"`` or ``"independent"``, else a ValueError naming the value."""
    if not isinstance(value, str) or value not in SCALES:
        raise ValueError(f"{what} must be 'shared' (one scale: sizes comparable across layers) "
                         f"or 'independent' (one per layer: each container fills), got {value!r}")
    return value


def check_seed(seed) -> int:
    """``seed`` as an int in torch's seed range."""
    if isinstance(seed, bool) or not isinstance(seed, Integral):
        raise TypeError(f"seed must be an integer, got {seed!r:.60}")
    if not -2 ** 63 <= seed < 2 ** 64:   # what torch.Generator.manual_seed takes
        raise ValueError(f"seed must be an integer in [-2**63, 2**64 - 1], got {seed!r:.60}")
    return int(seed)


def parse_marks(mark):
    """``mark=`` with every spec made a Mark (the same structure: one, a list or a dict)."""
    if is_category_dict(mark):
        return {k: parse_marks(v) for k, v in mark.items()}
    if isinstance(mark, (list, tuple)):
        if len(mark) > MAX_MARKS:
            _mark_set(mark)   # raises: too many marks
        return [parse_marks(m) if isinstance(m, (list, tuple, dict)) else _mark(m) for m in mark]
    return _mark(mark)


def pick_mark(mark, value, shape):
    """The ``mark=`` of the layer for by= ``value``: with ``shape=`` every layer takes the
    whole group; without, a ``{category: mark}`` dict picks the by= category's mark(s)."""
    if is_category_dict(mark) and shape is None:
        if value is None:
            raise ValueError("mark is a dict of category -> mark, which needs shape=<column> "
                             "(each row draws the mark of its category) or by=<column>")
        if value not in mark and str(value) not in mark:
            raise ValueError(f"mark: no mark for category {value!r}; the dict has "
                             f"{list(mark)}")
        return mark[value] if value in mark else mark[str(value)]
    return mark


def check_canvas(canvas) -> tuple[float, float]:
    """``canvas`` as (width, height) px, each in [16, 10000]."""
    if not hasattr(canvas, "__len__") or len(canvas) != 2:
        raise ValueError(f"canvas must be (width, height) in pixels, got {canvas!r}")
    w, h = (check_finite("canvas", n, v) for n, v in zip(("width", "height"), canvas))
    if not (16 <= w <= 10_000 and 16 <= h <= 10_000):
        raise ValueError(f"canvas must be between 16 and 10000 pixels a side, got {canvas!r}")
    return (w, h)


def read_background(source):
    """A background image (path, bytes, PIL image) as a data URL; None stays None."""
    if source is None:
        return None
    try:
        return image_data_url(load_image(source))
    except ValueError as exc:
        raise ValueError(f"background: {exc}") from None
