"""Marks by name from the Font Awesome Free icon set (the ``fontawesomefree`` package).

Names: ``"fa:NAME"`` takes the solid style when it exists, else regular, else
brands; ``"fa:solid/NAME"``, ``"fa:regular/NAME"`` and ``"fa:brands/NAME"``
pick the style. NAME is the icon's Font Awesome name, e.g. ``apple-whole``.
Install the set with ``pip install "unitopia-widget[icons]"``. The icons are
CC BY 4.0 (Font Awesome Free); a chart drawn with them carries their artwork.
"""
from __future__ import annotations

import difflib
import functools
import os

PREFIX = "fa:"
STYLES = ("solid", "regular", "brands")
MAX_MATCHES = 30


def is_icon_name(spec) -> bool:
    """Whether ``spec`` is a string naming an icon (``"fa:..."``)."""
    return isinstance(spec, str) and spec.startswith(PREFIX)


@functools.lru_cache(maxsize=1)
def _folder() -> str:
    try:
        import fontawesomefree
    except ImportError:
        raise ValueError("icon marks (\"fa:...\") need the fontawesomefree package: "
                         "pip install \"unitopia-widget[icons]\"") from None
    return os.path.join(os.path.dirname(fontawesomefree.__file__), "static", "fontawesomefree", "svgs")


@functools.lru_cache(maxsize=1)
def _styles() -> dict[str, frozenset]:
    """style -> the icon names it has."""
    return {s: frozenset(f[:-4] for f in os.listdir(os.path.join(_folder(), s)) if f.endswith(".svg"))
            for s in STYLES}


@functools.lru_cache(maxsize=1)
def all_names() -> tuple[str, ...]:
    """Every icon name: ``fa:NAME`` once per icon, plus ``fa:STYLE/NAME`` for the
    styles the short name does not pick (e.g. ``fa:regular/star``)."""
    styles, seen, out = _styles(), set(), []
    for style in STYLES:
        for name in sorted(styles[style]):
            out.append(f"{PREFIX}{style}/{name}" if name in seen else PREFIX + name)
            seen.add(name)
    return tuple(sorted(out))


def resolve(spec: str) -> tuple[str, str]:
    """``(style, name)`` of an icon name; ValueError listing the closest names."""
    body = spec[len(PREFIX):]
    style, _, name = body.rpartition("/")
    styles = _styles()
    if style:
        if style in styles and name in styles[style]:
            return style, name
        if style not in styles:
            raise ValueError(f"icon {spec!r}: unknown style {style!r}; use fa:NAME or "
                             f"fa:STYLE/NAME with STYLE one of {', '.join(STYLES)}")
    else:
        for s in STYLES:
            if name in styles[s]:
                return s, name
    close = search(spec, 5, substrings=False)
    hint = f"; the closest names are {', '.join(close)}" if close else ""
    raise ValueError(f"no Font Awesome icon named {spec!r}{hint}")


def read_svg(spec: str) -> bytes:
    """The SVG file of an icon name (see ``resolve``)."""
    style, name = resolve(spec)
    with open(os.path.join(_folder(), style, name + ".svg"), "rb") as fp:
        return fp.read()


def search(query: str, limit: int = MAX_MATCHES, substrings: bool = True) -> list[str]:
    """Up to ``limit`` icon names closest to ``query``: names starting with it, then
    names containing it (shortest first), then similar spellings."""
    q = str(query).strip().lower()
    q = q[len(PREFIX):] if q.startswith(PREFIX) else q
    names = all_names()
    short = {n: n[len(PREFIX):].rpartition("/")[2] for n in names}
    hits = []
    if substrings and q:
        bare = q.rpartition("/")[2]
        hits = sorted((n for n in names if bare in short[n]),
                      key=lambda n: (not short[n].startswith(bare), len(n), n))
    close = difflib.get_close_matches(q, [n[len(PREFIX):] for n in names], n=limit, cutoff=0.5)
    for n in (PREFIX + c for c in close):
        if n not in hits:
            hits.append(n)
    return hits[:limit]
