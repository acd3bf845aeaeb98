"""Story film speed: three slides of 1,000 marks, 800 x 500, 20 fps (issue 21, stories).

Lays out the same 1,000 stars three times (one round container, one pile per colour, a
wide ellipse; 40 iterations each, the layout excluded from the timing), then times
``Story.save`` of a GIF and an MP4: each slide held 1 s, each transition 1 s or longer
when stars travel far (no star moves over 4% of the canvas's short side a frame), and the
HTML page. Usage: ``python benchmarks/story.py [formats...]``.
"""
from __future__ import annotations

import os
import sys
import tempfile
import time

import numpy as np
import pandas as pd

import unitopia_widget as uw


def main(formats=(".gif", ".mp4", ".html")) -> None:
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"v": rng.uniform(1, 10, 1000), "g": rng.choice(["a", "b", "c"], 1000)})
    look = dict(mark="star", size="v", color="g", canvas=(800, 500), iterations=40, legend=False)
    piles = uw.Chart(df, by="g", piles=None, **look)
    for i, layer in enumerate(piles.layers):
        layer.set(container=uw.Container.rect(20 + i * 260, 20, 240, 460))
    slides = [uw.Chart(df, container=uw.Container.ellipse(400, 250, 240, 240), **look), piles,
              uw.Chart(df, container=uw.Container.ellipse(400, 250, 390, 240), **look)]
    story = uw.Story(slides, seconds=1.0)
    t = time.perf_counter()
    story.run()
    print(f"layout of 3 slides {time.perf_counter() - t:.1f} s")
    with tempfile.TemporaryDirectory() as folder:
        for ext in formats:
            path = os.path.join(folder, "story" + ext)
            t = time.perf_counter()
            story.save(path, **({} if ext == ".html" else {"fps": 20, "hold": 1.0}))
            print(f"{ext:6s} {time.perf_counter() - t:5.1f} s  {os.path.getsize(path) / 1e6:.1f} MB")


if __name__ == "__main__":
    main(tuple(sys.argv[1:]) or (".gif", ".mp4", ".html"))
