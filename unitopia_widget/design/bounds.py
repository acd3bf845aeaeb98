"""Bounds on the lists and strings of a design (``docs/protocol.md``, "Bounds").

Each is far above what a drawn or coded design needs and far below what would hold the
layout for minutes: a layer's forces are summed every iteration over every mark (1,000
forces on 3 rows took 17.5 s), a container's vertices are rasterised and traced
(700,000 took 42 s). Checked before anything is built from the list, so a hostile design
is refused at once, with the field, its length and the bound.
"""
from __future__ import annotations

MAX_FORCES = 50                # forces in one layer (designs use one to a handful)
MAX_CONTAINER_POINTS = 20_000  # vertices of a polygon container, or of one cut's stroke
MAX_PATH_CHARS = 200_000       # characters of a path container's SVG path data
MAX_CUTS = 100                 # cuts in one container
MAX_EMITTER_POINTS = 3_001     # control points of a curve emitter (1,000 Bezier segments)
MAX_STROKES = 1_000            # strokes in a sketch mark
MAX_SKETCH_POINTS = 50_000     # points of a sketch mark, its strokes together
MAX_BLOCKS = 100               # layers one layer blocks on (a design holds at most 100 layers)
MAX_ROW_LABELS = 20_000        # index labels of a layer's rows (a chart draws at most 20,000 units)
MAX_UNITS = 20_000             # marks one chart lays out (per=k draws one mark for k units)
MAX_SLIDES = 100               # slides in a story
MAX_COLUMN_NAME = 1_000        # characters of a column name bound to a channel


def check_length(field: str, items, bound: int, what: str = "entries") -> None:
    """A ValueError naming ``field``, its length and ``bound`` when ``items`` (anything with
    a length; anything else is left to the field's own checks) holds more than ``bound``."""
    if hasattr(items, "__len__"):
        check_count(field, len(items), bound, what)


def check_count(field: str, count: int, bound: int, what: str = "entries") -> None:
    """A ValueError naming ``field``, ``count`` and ``bound`` when ``count > bound``."""
    if count > bound:
        raise ValueError(f"{field} has {count:,} {what}; at most {bound:,} are allowed "
                         f"(see 'Bounds' in docs/protocol.md)")


def sketch_strokes(strokes) -> list:
    """The strokes of a sketch mark as a list, within ``MAX_STROKES`` strokes and
    ``MAX_SKETCH_POINTS`` points together (a ValueError naming the bound past either)."""
    if not hasattr(strokes, "__iter__"):
        raise ValueError(f"sketch strokes must be a list of (k, 2) point lists, got "
                         f"{type(strokes).__name__}")
    strokes = list(strokes)
    check_length("sketch strokes", strokes, MAX_STROKES)
    check_count("sketch strokes", sum(len(s) for s in strokes if hasattr(s, "__len__")),
                MAX_SKETCH_POINTS, "points")
    return strokes
