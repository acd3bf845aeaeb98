"""``Story``: slides of unit charts in which every unit keeps its identity.

``Story([w1, w2, w3], titles=[...])`` takes laid-out ``UnitoPia`` widgets or ``Chart``
objects over the same rows, or overlapping ones matched by DataFrame index; a
transition moves each unit from its place in one slide to its place in the next
(``output.transition``). A story shows as a widget in the notebook (previous, next, a
transition speed) and saves as one HTML page, a film (GIF, WebP, MP4, WebM) or its
design JSON (the slides' designs, in order).
"""
from __future__ import annotations

import os
from numbers import Real

import numpy as np
import pandas as pd

from .chart import Chart
from .design.bounds import MAX_SLIDES, check_length
from .design.files import read_json
from .output import animation, story_film, story_page, transition
from .output.files import atomic_write, write_json
from .design.page import TITLE_CHARS, check_text

STORY_SCHEMA = "unitopia-story"
STORY_VERSION = 1
HOLD = 1.5   # seconds a slide shows in a film


def _seconds(value, name: str = "seconds") -> float:
    """A transition's length: a number of seconds in (0, 10]."""
    if isinstance(value, bool) or not isinstance(value, Real) or not 0 < value <= 10:
        raise ValueError(f"{name} must be a number of seconds in (0, 10], got {value!r:.40}")
    return float(value)


def _rows(df, rows: list, slide: int):
    """The rows of ``df`` labelled ``rows`` (slide ``slide``'s), else a ValueError naming the missing."""
    if not isinstance(df, pd.DataFrame):
        raise TypeError(f"df must be a pandas DataFrame or a list of them, one per slide, got "
                        f"{type(df).__name__}")
    missing = pd.Index(rows).difference(df.index)
    if len(missing):
        raise ValueError(f"df lacks {len(missing)} of the {len(rows)} rows of story slides[{slide}] "
                         f"(for one, {missing[0]!r:.60}); pass the DataFrame the story was made from")
    return df.loc[rows]


class Story:
    """Slides of unit charts with animated transitions: ``Story([w1, w2, w3], titles=[...])``.

    ``slides``: ``UnitoPia`` widgets or ``Chart`` objects with the same canvas; a unit is
    one DataFrame row (matched by index label across slides); ``titles``: one per slide
    (default: each chart's title); ``seconds``: the length of a transition."""

    def __init__(self, slides, titles=None, seconds: float = 1.0):
        if isinstance(slides, (str, bytes, dict)) or not hasattr(slides, "__iter__"):
            raise TypeError(f"slides must be a list of charts (uw.UnitoPia or uw.Chart), got "
                            f"{type(slides).__name__}")
        slides = list(slides)
        check_length("slides", slides, MAX_SLIDES)
        if not slides:
            raise ValueError("slides is empty: a story needs at least one chart "
                             "(uw.UnitoPia or uw.Chart)")
        charts = []
        for i, item in enumerate(slides):
            chart = item if isinstance(item, Chart) else getattr(item, "_chart", None)
            if not isinstance(chart, Chart):
                raise TypeError(f"slides[{i}] is a {type(item).__name__}, not a chart: a story's "
                                f"slides are uw.UnitoPia widgets or uw.Chart objects")
            if charts and chart.canvas != charts[0].canvas:
                (w, h), (w0, h0) = chart.canvas, charts[0].canvas
                raise ValueError(f"slides[{i}] has a {w:g} x {h:g} canvas and slides[0] a "
                                 f"{w0:g} x {h0:g} one: every slide of a story needs the same canvas")
            charts.append(chart)
        if titles is None:
            titles = [c.title or "" for c in charts]
        elif isinstance(titles, str) or not hasattr(titles, "__len__"):
            raise TypeError(f"titles must be a list of strings, one per slide, got "
                            f"{type(titles).__name__}")
        elif len(titles) != len(charts):
            raise ValueError(f"titles has {len(titles)} entries for {len(charts)} slides; give "
                             f"one title per slide")
        self.titles = [check_text(f"titles[{i}]", t, TITLE_CHARS) or "" for i, t in enumerate(titles)]
        self.seconds = _seconds(seconds)
        self._items, self.charts = slides, charts
        self._widget = None

    def __len__(self) -> int:
        return len(self.charts)

    # --- layout ---------------------------------------------------------------
    def run(self) -> "Story":
        """Lay out every slide that has no layout yet (a loaded story has none)."""
        for item, chart in zip(self._items, self.charts):
            if chart.placements is None and hasattr(item, "run"):
                item.run(wait=True)   # a widget: its view shows the layout too
            elif chart.placements is None:
                chart.layout()
        return self

    def _slides(self) -> list[dict]:
        """Per slide: the chart, its sanitised SVG export, unit keys, states and marks."""
        out = []
        for i, chart in enumerate(self.charts):
            if chart.placements is None:
                raise RuntimeError(f"slides[{i}] has no layout yet: call story.run() (or run "
                                   f"the slide) first")
            table = chart.placements
            by_name = {layer.name: layer for layer in chart.layers}
            marks = [by_name[name].marks[k] for name, k in zip(table["layer"], table["mark"])]
            shapes = {}
            out.append({"chart": chart, "svg": chart.to_svg(title=self.titles[i]),
                        "keys": transition.unit_keys(table["row"].tolist()),
                        "states": transition.slide_states(table),
                        "shapes": [shapes.setdefault(id(m), m.svg_fragment("m", "#000000"))
                                   for m in marks],
                        "boxes": np.array([m.box_size for m in marks], dtype=float)})
        return out

    def plans(self, slides=None) -> list[transition.Plan]:
        """One ``transition.Plan`` per pair of consecutive slides."""
        slides = self._slides() if slides is None else slides
        return [transition.plan(a["keys"], b["keys"], a["states"], b["states"], a["shapes"],
                                b["shapes"]) for a, b in zip(slides, slides[1:])]

    def player(self) -> dict:
        """What the browser's player draws (``docs/protocol.md``, story widget)."""
        slides = self._slides()
        return {"view": list(story_film.union_view([s["svg"] for s in slides])),
                "seconds": self.seconds, "stagger": transition.STAGGER,
                "slides": [{"title": title, "svg": s["svg"],
                            "units": np.round(np.column_stack([s["states"], s["boxes"]]), 4).tolist()}
                           for title, s in zip(self.titles, slides)],
                "transitions": [p.to_json() for p in self.plans(slides)]}

    # --- files ------------------------------------------------------------------
    def save(self, path, fps=None, hold=None, seconds=None) -> None:
        """Write ``.html`` (one page: previous / next, arrow keys, tooltips, animated
        transitions), ``.json`` (the story's designs), or a film ``.gif``, ``.webp``,
        ``.mp4``, ``.webm``: each slide held ``hold`` s (default 1.5), each transition
        ``seconds`` (default the story's) at ``fps`` (default 20)."""
        path = os.fspath(path)
        ext = os.path.splitext(path)[1].lower()
        if (fps, hold, seconds) != (None, None, None) and ext not in animation.FORMATS:
            raise ValueError(f"save: fps, hold and seconds are for a film "
                             f"({', '.join(animation.FORMATS)}), not {ext!r}")
        if ext == ".json":
            write_json(path, self.to_json())
        elif ext == ".html":
            atomic_write(path, story_page.page(self.player(), next((t for t in self.titles if t),
                                                                   None)).encode())
        elif ext in animation.FORMATS:
            fps = animation.check_timing(fps, 1.0)[0]
            hold = HOLD if hold is None else _seconds(hold, "hold")
            seconds = self.seconds if seconds is None else _seconds(seconds)
            slides = self._slides()
            frames = story_film.render([(s["chart"], s["svg"], s["states"]) for s in slides],
                                       self.plans(slides), fps, hold, seconds)
            atomic_write(path, animation.write(path, frames, fps, story_film.palette(frames)))
        else:
            raise ValueError(f"save: a story is saved as .html, .json, .gif, .webp, .mp4 or "
                             f".webm; got {ext!r} in {path!r}")

    def to_json(self) -> dict:
        """``{"schema": "unitopia-story", "version", "seconds", "slides": [{"title", "rows",
        "design"}]}``: the slides in order, each its DataFrame's index labels and a design JSON."""
        return {"schema": STORY_SCHEMA, "version": STORY_VERSION, "seconds": self.seconds,
                "slides": [{"title": t, "rows": c.df.index.tolist(), "design": c.design()}
                           for t, c in zip(self.titles, self.charts)]}

    @classmethod
    def from_json(cls, d: dict, df, **kwargs) -> "Story":
        """A story with the slides of ``d`` (``to_json``), not laid out yet (call ``run()``).
        ``df``: one DataFrame, each slide taking the rows it was saved with, or a list of
        DataFrames, one per slide; ``kwargs`` as for ``Chart`` (device, tooltip, ...)."""
        if not isinstance(d, dict) or d.get("schema") != STORY_SCHEMA:
            raise ValueError(f"not a unitopia story: expected a JSON object with \"schema\": "
                             f"\"{STORY_SCHEMA}\"")
        version = d.get("version")
        if isinstance(version, bool) or not isinstance(version, int) or not 1 <= version <= STORY_VERSION:
            raise ValueError(f"story: version {version!r} is not one this unitopia-widget reads "
                             f"(1 to {STORY_VERSION})")
        slides = d.get("slides")
        if not isinstance(slides, list) or not slides or not all(
                isinstance(s, dict) and isinstance(s.get("rows"), list) and "design" in s for s in slides):
            raise ValueError("story: \"slides\" must be a non-empty list of {\"title\", \"rows\", "
                             "\"design\"} objects")
        check_length("story: slides", slides, MAX_SLIDES)
        if isinstance(df, (list, tuple)):
            if len(df) != len(slides):
                raise ValueError(f"df is a list of {len(df)} DataFrames for a story of "
                                 f"{len(slides)} slides; give one per slide, or one DataFrame")
            frames = list(df)
        else:
            frames = [_rows(df, s["rows"], i) for i, s in enumerate(slides)]
        charts = []
        for i, (s, frame) in enumerate(zip(slides, frames)):
            try:
                charts.append(Chart.from_design(frame, s["design"], **kwargs))
            except ValueError as exc:
                raise ValueError(f"story slides[{i}]: {exc}") from None
        return cls(charts, titles=[s.get("title") for s in slides], seconds=d.get("seconds", 1.0))

    @classmethod
    def load(cls, path, df, **kwargs) -> "Story":
        """The story saved at ``path`` (``save("story.json")``) over ``df`` (one DataFrame
        or one per slide, as for ``from_json``); call ``run()`` to lay it out."""
        return cls.from_json(read_json(path, "story"), df, **kwargs)

    # --- notebook -------------------------------------------------------------------
    def widget(self):
        """The story as a notebook widget (``jupyter.story.StoryWidget``), made once."""
        if self._widget is None:
            from .jupyter.story import StoryWidget
            self._widget = StoryWidget(self)
        return self._widget

    def __repr__(self) -> str:
        rows = ", ".join(str(len(c.df)) for c in self.charts)
        return f"<Story of {len(self)} slides ({rows} rows): {' / '.join(self.titles)}>"

    def _repr_mimebundle_(self, **kwargs):
        """The story widget, with a text/plain that says what the story is."""
        view = self.widget()._repr_mimebundle_(**kwargs)
        data, metadata = view if isinstance(view, tuple) else (view or {}, {})
        return {**data, "text/plain": repr(self)}, metadata
