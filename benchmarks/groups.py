"""Joint packing of a mark group against the same layout with one mark.

N units with lognormal sizes (sigma 0.5) fill an ellipse (closed boundary) on
a 600 x 400 canvas, drawn with 1, 2, 6 or 14 marks (``shape=`` a category
column; Font Awesome icons, SVG icons with <style> classes and several
colours, built-in shapes). The one-mark runs use the first mark of the set.
Reports CPU seconds of the whole layout (process time, one thread: on a
shared, loaded machine wall time mostly measures the other jobs), iterations,
CPU ms per iteration (the iteration counts differ from run to run, the cost of
one iteration is what the number of marks changes) and the overlap / outside share
of the ink measured from the exported SVG (every unit rendered alone by resvg,
covered where alpha > 0.5, at 2x).

    python benchmarks/groups.py            # N = 150 and 400 (run from the repository root)
    python benchmarks/groups.py 300        # some sizes
"""
from __future__ import annotations

import argparse
import os
import platform
import sys
import time

import numpy as np
import pandas as pd
import torch

import unitopia_widget as uw

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
from ink import ink_metrics  # noqa: E402  (the tests' independent measure)

DATA = "tests/data/marks/"
MARKS = ["fa:apple-whole", "fa:fish", DATA + "class_styled.svg", "fa:bicycle", DATA + "rect_2to1.svg",
         "star", "fa:lemon", "fa:carrot", "fa:dove", "fa:feather", "fa:regular/star",
         DATA + "multicolor.svg", "heart", "drop"]
W, H, ELLIPSE = 600, 400, (300, 200, 260, 170)


def run(n: int, k: int, seed: int = 1) -> dict:
    rng = np.random.default_rng(seed)
    df = pd.DataFrame({"v": rng.lognormal(0, 0.5, n), "kind": [f"k{i % k:02d}" for i in range(n)]})
    chart = uw.Chart(df, mark=MARKS[:k], size="v", shape="kind", container=uw.Container.ellipse(*ELLIPSE),
                     canvas=(W, H))
    started, wall = time.process_time(), time.perf_counter()
    chart.layout()
    seconds, wall = time.process_time() - started, time.perf_counter() - wall
    m = ink_metrics(chart.to_svg(), chart.canvas, ELLIPSE)
    it = chart.result.iterations
    return {"N": n, "marks": k, "seconds": seconds, "wall": wall, "iterations": it,
            "ms_per_it": 1000 * seconds / it,
            "overlap_%": 100 * m["overlap"], "outside_%": 100 * m["outside"]}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sizes", nargs="*", type=int, default=[150, 400])
    a = ap.parse_args(argv)
    torch.set_num_threads(1)
    print(f"# {platform.processor() or platform.machine()}, torch {torch.__version__}, one thread",
          file=sys.stderr)
    run(40, 2)   # warm up: the first layout of a process pays for lazy imports
    print("| N | marks | CPU s | wall s | iterations | CPU ms / iteration | vs 1 mark (per it.) | "
          "overlap % | outside % |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in a.sizes:
        base = None
        for k in (1, 2, 6, 14):
            r = run(n, k)
            base = base or r["ms_per_it"]
            print(f"| {n} | {k} | {r['seconds']:.1f} | {r['wall']:.1f} | {r['iterations']} | "
                  f"{r['ms_per_it']:.1f} | "
                  f"{r['ms_per_it'] / base:.2f}x | {r['overlap_%']:.2f} | {r['outside_%']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
