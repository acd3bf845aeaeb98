"""PNG export at the supported scale (issue 19: any chart in at most 10 s and 1.5 GB).

Two charts, placed on a grid without a solve (the export is what is timed):
20,000 units of a 51-element SVG icon (resvg alone refuses them: its node limit),
and 10,000 categories bound to ``color=`` (a legend of many entries). Times
``Chart.save("x.png")`` (2x) and reports the process's peak memory.
Usage: ``python benchmarks/png_export.py [icons|categories]``.
"""
from __future__ import annotations

import os
import resource
import sys
import tempfile
import time
from types import SimpleNamespace

import numpy as np
import pandas as pd

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.prepare.bind import bind

ICON = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 22 22"><g fill="#333">'
        + "".join(f'<circle cx="{2 + i % 10 * 2}" cy="{2 + i // 10 * 4}" r="0.8"/>' for i in range(50))
        + "</g></svg>")


def chart(case: str) -> uw.Chart:
    if case == "icons":
        c = uw.Chart(pd.DataFrame({"v": np.ones(20_000)}), mark=uw.Mark.svg(ICON), canvas=(1600, 1000))
    else:
        c = uw.Chart(pd.DataFrame({"cat": [f"c{i}" for i in range(10_000)]}), mark="circle",
                     color="cat", canvas=(1600, 1000))
    units = bind(c.df, c.layers)
    n, (w, h) = len(units.rows), c.canvas
    cols = int(np.ceil(np.sqrt(n * w / h)))
    cell, k = w / cols, np.arange(n)
    scale = 0.45 * cell / units.half_w.max()
    result = SimpleNamespace(center=np.stack([(k % cols + 0.5) * cell, (k // cols + 0.5) * cell], 1),
                             angle=np.zeros(n), unit_scale=np.full(n, scale), scale=scale,
                             cancelled=False)
    c._units = units
    c.laid = engine.Layout(placements=engine.placements(units, c.layers, result), units=units,
                           scale=scale, canvas=c.canvas, frames=None, result=result)
    return c


def main(cases=("icons", "categories")) -> None:
    for case in cases:
        c = chart(case)
        with tempfile.TemporaryDirectory() as tmp:
            t = time.perf_counter()
            c.save(os.path.join(tmp, "x.png"))
            took = time.perf_counter() - t
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"{case}: {len(c.placements)} units, save png {took:.2f} s, peak memory {peak:.0f} MB")


if __name__ == "__main__":
    import warnings
    warnings.simplefilter("ignore")
    main(sys.argv[1:] or ("icons", "categories"))
