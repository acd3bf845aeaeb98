"""The built-in example: stars settling in a jar, one star per task, area = duration."""
from __future__ import annotations

import io

import numpy as np
import pandas as pd
import resvg_py
from PIL import Image

from .chart import Chart
from .design.containers import Container
from .design.forces import PointForce

JAR = ("M 300 70 L 500 70 L 500 110 C 500 130 480 135 480 150 C 600 190 610 260 610 330 "
       "C 610 430 560 470 400 470 C 240 470 190 430 190 330 C 190 260 200 190 320 150 "
       "C 320 135 300 130 300 110 Z")


def demo_data(n: int = 120, seed: int = 7) -> pd.DataFrame:
    """A small made-up dataset: tasks of four kinds with durations in hours."""
    rng = np.random.default_rng(seed)
    task = rng.choice(["Reading", "Writing", "Coding", "Meeting"], n, p=[0.2, 0.25, 0.35, 0.2])
    duration = np.round(rng.gamma(2.0, 1.2, n) + 0.25, 2)
    return pd.DataFrame({"Task": task, "Duration": duration})


def jar_picture() -> Image.Image:
    """The jar drawn as a background picture, 800 x 500."""
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="800" height="500">'
           f'<rect width="800" height="500" fill="#fbf8f1"/>'
           f'<path d="{JAR}" fill="#eef4f7" stroke="#5b6b75" stroke-width="5" '
           f'stroke-linejoin="round"/></svg>')
    return Image.open(io.BytesIO(bytes(resvg_py.svg_to_bytes(svg_string=svg)))).convert("RGBA")


def demo_chart(seed: int = 0, chart_cls=Chart, **kwargs):
    """Stars settling in a jar: a jar-shaped path container, a point force at its
    bottom, an open boundary (the stars fill 30% of the jar, as much as their spiky
    footprints pack), the jar as background."""
    return chart_cls(demo_data(), mark="star", size="Duration", color="Task",
                     container=Container.path(JAR), forces=[PointForce(400, 470)],
                     boundary="open", fill=0.3, background=jar_picture(),
                     canvas=(800, 500), seed=seed, **kwargs)
