"""Animation export speed: 1,000 marks, 100 frames, 800 x 500 (issue 21: at most 15 s).

Lays out 1,000 rotated stars in three colours once, then times ``Chart.save`` for
each format at 20 fps for 5 s (100 frames): sprite rendering, compositing and
encoding, the layout excluded. Usage: ``python benchmarks/animation.py [formats...]``.
"""
from __future__ import annotations

import os
import sys
import tempfile
import time

import numpy as np
import pandas as pd

import unitopia_widget as uw


def main(formats=(".gif", ".webp", ".mp4", ".webm")) -> None:
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"v": rng.uniform(1, 10, 1000), "g": rng.choice(["a", "b", "c"], 1000)})
    chart = uw.Chart(df, mark="star", size="v", color="g", rotate=True, canvas=(800, 500),
                     iterations=150, legend=False)
    t = time.perf_counter()
    chart.layout()
    print(f"layout {time.perf_counter() - t:.1f} s, {len(chart.frames)} frames kept")
    with tempfile.TemporaryDirectory() as folder:
        for ext in formats:
            path = os.path.join(folder, "settle" + ext)
            t = time.perf_counter()
            chart.save(path, fps=20, seconds=5)
            print(f"{ext:6s} 100 frames {time.perf_counter() - t:5.1f} s  "
                  f"{os.path.getsize(path) / 1e6:.1f} MB")


if __name__ == "__main__":
    main(tuple(sys.argv[1:]) or (".gif", ".webp", ".mp4", ".webm"))
