"""The page settings a design saves: ``PageOptions`` (design JSON top-level keys ``"title"``,
``"caption"``, ``"legend": {"visible", "position"}``) and the checks of their values. The
page drawn from them is ``output.page``."""
from __future__ import annotations

from numbers import Real

POSITIONS = ("right", "bottom", "left", "top")
TITLE_CHARS, CAPTION_CHARS = 200, 2000


class PageOptions:
    """Title, caption and legend settings of one chart."""

    def __init__(self, title=None, caption=None, legend=True):
        self.title = check_text("title", title, TITLE_CHARS)
        self.caption = check_text("caption", caption, CAPTION_CHARS)
        self.legend = legend_spec(legend)

    def to_json(self) -> dict:
        return {"title": self.title, "caption": self.caption, "legend": dict(self.legend)}

    @classmethod
    def from_json(cls, d: dict) -> "PageOptions":
        return cls(d.get("title"), d.get("caption"),
                   d.get("legend") if d.get("legend") is not None else True)


def legend_spec(value) -> dict:
    """``{"visible": bool, "position": ...}`` from True/False, a position, or that dict."""
    if isinstance(value, dict):
        unknown = set(value) - {"visible", "position"}
        if unknown or not isinstance(value.get("visible", True), bool):
            raise ValueError(f"legend must be True, False, a position or {{\"visible\": bool, "
                             f"\"position\": ...}}; got {value!r:.80}")
        return {"visible": value.get("visible", True),
                "position": check_position(value.get("position", "right"))}
    if isinstance(value, bool):
        return {"visible": value, "position": "right"}
    try:
        return {"visible": True, "position": check_position(value)}
    except ValueError:
        raise ValueError(f"legend must be True, False, None, 'right', 'bottom', 'left', 'top' or "
                         f"[x, y]; got {value!r:.60}") from None


def check_text(name: str, value, limit: int):
    """None or a str of at most ``limit`` characters, else a clear error."""
    if value is None:
        return None
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string or None, got {type(value).__name__}")
    if len(value) > limit:
        raise ValueError(f"{name} is {len(value)} characters long; at most {limit} are drawn. "
                         f"Shorten it")
    return value or None


def check_position(value):
    """'right', 'bottom', 'left', 'top' or [x, y] (the legend's top-left corner, canvas px)."""
    if isinstance(value, str) and value in POSITIONS:
        return value
    if (isinstance(value, (list, tuple)) and len(value) == 2
            and all(isinstance(v, Real) and not isinstance(v, bool) and abs(v) < 1e5 for v in value)):
        return [float(value[0]), float(value[1])]
    raise ValueError(f"legend position must be one of {', '.join(map(repr, POSITIONS))} or "
                     f"[x, y] in canvas px; got {value!r:.60}")
