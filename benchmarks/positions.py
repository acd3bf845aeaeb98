"""Position channels and the grid arrangement (issue 22, parts 3 and 4), measured.

For x= bound to a numeric column (500 marks by default) in a hand-drawn blob, closed
and open, normal and skewed data on linear and log scales: the Spearman correlation of
value and x, the overlap of the discs (summed lens area over their area), the share of
discs inside the container, iterations and seconds. For arrange="grid" in the same kind
of blob: the spread of centre heights within a row over a mark's height, whether any
two squares overlap, the share inside and the density (mark boxes over the container).

    OMP_NUM_THREADS=1 python benchmarks/positions.py [--marks 500]
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np
import pandas as pd
from scipy.stats import spearmanr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import unitopia_widget as uw  # noqa: E402
from test_arrange import rows_of  # noqa: E402
from test_positions import blob, disc_overlap, inside_share  # noqa: E402

CANVAS = (800, 500)


def swarm(n: int, data: str, scale: str, boundary: str) -> dict:
    rng = np.random.default_rng(1)
    v = rng.normal(0, 1, n) if data == "normal" else rng.lognormal(0, 0.8, n)
    df = pd.DataFrame({"v": v})
    container = uw.Container.polygon(blob())
    chart = uw.Chart(df, mark="circle", x="v", x_scale=scale, container=container,
                     boundary=boundary, canvas=CANVAS)
    t0 = time.perf_counter()
    table = chart.layout()
    return {"design": f"x= {data}, {scale}, {boundary}", "marks": n,
            "spearman": spearmanr(df.loc[table["row"], "v"], table["x"]).correlation,
            "overlap": disc_overlap(table), "inside": inside_share(container, table),
            "iterations": chart.result.iterations, "seconds": time.perf_counter() - t0}


def waffle(n: int, boundary: str) -> dict:
    rng = np.random.default_rng(5)
    df = pd.DataFrame({"k": rng.choice(list("abc"), n)})
    container = uw.Container.polygon(blob(3))
    chart = uw.Chart(df, mark="square", color="k", order="k", arrange="grid", margin=0.1,
                     container=container, boundary=boundary, canvas=CANVAS)
    t0 = time.perf_counter()
    table = chart.layout()
    h = float(table["height"].mean())
    spread = max(float(np.ptp(table["y"].to_numpy()[row])) for row in rows_of(table)) / h
    c, w = table[["x", "y"]].to_numpy(), table["width"].to_numpy()
    dx = np.abs(c[:, None, 0] - c[None, :, 0]) - w[:, None] / 2 - w[None, :] / 2
    dy = np.abs(c[:, None, 1] - c[None, :, 1]) - h
    hit = (dx < -1e-6) & (dy < -1e-6)
    np.fill_diagonal(hit, False)
    return {"design": f"grid, {boundary}", "marks": n, "row spread / h": spread,
            "overlapping pairs": int(hit.sum() // 2),
            "inside": inside_share(container, table.assign(width=table["width"] * math.sqrt(2))),
            "density": float((table["width"] * table["height"]).sum()) / container.area(CANVAS),
            "iterations": chart.result.iterations, "seconds": time.perf_counter() - t0}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--marks", type=int, default=500)
    n = ap.parse_args(argv).marks
    rows = [swarm(n, d, s, b) for d, s in (("normal", "linear"), ("lognormal", "log"),
                                           ("lognormal", "linear")) for b in ("closed", "open")]
    print(pd.DataFrame(rows).to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print(pd.DataFrame([waffle(n, b) for b in ("closed", "open")]).to_string(
        index=False, float_format=lambda v: f"{v:.4g}"))


if __name__ == "__main__":
    main()
