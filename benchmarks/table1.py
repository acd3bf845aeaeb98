"""The paper's Table 1 set-up, through the public API, on this machine.

A circular container on a 1440 x 830 canvas, a point force at its bottom,
open boundary, marks covering 60% of the container: equal circles, then
circles whose areas spread over a 10x range. Per N it reports total seconds,
iterations, ms per iteration, peak memory (RSS growth), and the quality,
measured exactly from the placements (circles are analytic): overlap and
outside as a share of the mark area, and the mean depth of the marks
(y of their centres; the force pulls them down, the container centre is at
y = 415).

    python benchmarks/table1.py            # all sizes
    python benchmarks/table1.py 200 1000   # some sizes
    python benchmarks/table1.py --closed   # closed boundary: packing density instead
"""
from __future__ import annotations

import argparse
import math
import platform
import resource
import sys
import time

import numpy as np
import pandas as pd
from scipy.spatial import cKDTree

import unitopia_widget as uw

W, H, CX, CY, R = 1440, 830, 720, 415, 400


def circle_metrics(table: pd.DataFrame) -> dict:
    """Exact overlap (pairwise lens areas) and outside share of equal-or-unequal discs."""
    c = table[["x", "y"]].to_numpy()
    r = table["width"].to_numpy() / 2
    area = float(np.sum(np.pi * r ** 2))
    tree = cKDTree(c)
    overlap = 0.0
    for i, j in tree.query_pairs(2 * r.max()):
        d = float(np.hypot(*(c[i] - c[j])))
        a, b = r[i], r[j]
        if d >= a + b:
            continue
        if d <= abs(a - b):
            overlap += math.pi * min(a, b) ** 2
            continue
        x1 = (d * d + a * a - b * b) / (2 * d * a)
        x2 = (d * d + b * b - a * a) / (2 * d * b)
        k = 0.5 * math.sqrt((-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b))
        overlap += a * a * math.acos(x1) + b * b * math.acos(x2) - k
    dist = np.hypot(c[:, 0] - CX, c[:, 1] - CY)
    outside = 0.0
    for di, ri in zip(dist, r):
        if di + ri > R:   # lens of the disc outside the container: disc area minus intersection
            outside += math.pi * ri * ri - _intersection(di, ri, R)
    return {"overlap_%": 100 * overlap / area, "outside_%": 100 * outside / area,
            "density": area / (math.pi * R * R), "mean_y": float(c[:, 1].mean())}


def _intersection(d, a, b):
    if d >= a + b:
        return 0.0
    if d <= abs(a - b):
        return math.pi * min(a, b) ** 2
    x1 = (d * d + a * a - b * b) / (2 * d * a)
    x2 = (d * d + b * b - a * a) / (2 * d * b)
    k = 0.5 * math.sqrt(max((-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b), 0.0))
    return a * a * math.acos(max(-1, min(1, x1))) + b * b * math.acos(max(-1, min(1, x2))) - k


def run(n: int, spread: bool, closed: bool, seed: int = 0) -> dict:
    rng = np.random.default_rng(seed)
    value = rng.uniform(1, 10, n) if spread else np.ones(n)
    df = pd.DataFrame({"value": value})
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t0 = time.perf_counter()
    chart = uw.Chart(df, mark="circle", size="value", canvas=(W, H), seed=seed,
                     container=uw.Container.ellipse(CX, CY, R, R),
                     forces=[] if closed else [uw.PointForce(CX, CY + R)],
                     boundary="closed" if closed else "open", fill=None if closed else 0.6,
                     iterations=1000)
    table = chart.layout()
    seconds = time.perf_counter() - t0
    rss = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - rss0) / 1024
    it = chart.result.iterations
    return {"N": n, "marks": "10x areas" if spread else "equal", "seconds": seconds,
            "iterations": it, "ms/iter": 1000 * seconds / it, "peak_MB": rss,
            **circle_metrics(table)}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sizes", nargs="*", type=int, default=[200, 400, 800, 1000, 2000, 5000])
    ap.add_argument("--closed", action="store_true", help="closed boundary, no force: packing")
    ap.add_argument("--equal-only", action="store_true")
    args = ap.parse_args(argv)
    import torch
    print(f"# {platform.processor() or platform.machine()}, {torch.get_num_threads()} torch "
          f"threads, torch {torch.__version__}, python {platform.python_version()}")
    run(20, False, False)   # warm-up: torch and resvg start-up is not part of a layout
    rows = []
    for spread in ([False] if args.equal_only else [False, True]):
        for n in args.sizes:
            rows.append(run(n, spread, args.closed))
            print(pd.DataFrame(rows[-1:]).to_string(index=False, float_format=lambda v: f"{v:.3f}"),
                  flush=True)
    print()
    print(pd.DataFrame(rows).to_markdown(index=False, floatfmt=".3f") if _has_tabulate()
          else pd.DataFrame(rows).to_string(index=False))


def _has_tabulate() -> bool:
    try:
        import tabulate  # noqa: F401
    except ImportError:
        return False
    return True


if __name__ == "__main__":
    sys.exit(main())
