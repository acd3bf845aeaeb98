"""Thin marks that cross: the hair design and rods turned freely, pairs of units whose ink overlaps.

Each design is laid out and measured as in ``designs.py`` (overlap, outside,
emptiness from the SVG export, by the independent checker), then every unit
of the SVG is rendered alone at 2x: a pair of units overlaps where both inks
(alpha > 0.5) share at least ``--least`` supersampled px. ``rods-*``: 120 rods
(4 x 60, heights lognormal) in a closed circle, ``rotate=True``, started in rows
along the container, from a grid emitter, or all turned 30 degrees.

    PYTHONPATH=$PWD python benchmarks/crossings.py [--tool measure_svg.py] [NAME ...]
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import tempfile

import numpy as np
import pandas as pd

import unitopia_widget as uw

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import designs  # noqa: E402

ROD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 60"><rect width="4" height="60"/></svg>'


def rods(**options):
    def design():
        df = pd.DataFrame({"len": np.random.default_rng(5).lognormal(0, 0.4, 120)})
        c = uw.Container.ellipse(400, 300, 250, 250)
        return dict(df=df, mark=uw.Mark.svg(ROD), height="len", rotate=True, container=c,
                    boundary="closed", **options), [c]
    return design


designs.DESIGNS.update({"rods-rows": rods(), "rods-grid": rods(emitter=uw.GridEmitter()),
                        "rods-30": rods(orientation=30)})
NAMES = ["hair", "rods-rows", "rods-grid", "rods-30"]


def overlapping_pairs(svg_path: str, tool, least: int, k: int = 2) -> tuple[int, int]:
    """(pairs of units whose inks share >= ``least`` px at ``k`` x, the largest such share)."""
    with open(svg_path) as f:
        text = f.read()
    w, h = tool.canvas_size(text)
    owner, shared = np.full((h * k, w * k), -1, np.int32), {}
    for n, (_, _, alpha) in enumerate(tool.units(text, None, k)):
        ink = alpha > 0.5
        hit = owner[ink]
        for other, count in zip(*np.unique(hit[hit >= 0], return_counts=True)):
            shared[(int(other), n)] = shared.get((int(other), n), 0) + int(count)
        owner[ink] = n
    big = [c for c in shared.values() if c >= least]
    return len(big), max(big, default=0)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("names", nargs="*", default=NAMES)
    ap.add_argument("--tool", default="/work/shared/tools/measure_svg.py")
    ap.add_argument("--out", default=os.path.join(tempfile.gettempdir(), "uw-crossings"))
    ap.add_argument("--least", type=int, default=4)
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    spec = importlib.util.spec_from_file_location("measure_svg", a.tool)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    print(f"| design | s | overlap % | outside % | empty % | overlapping pairs (>= {a.least} px at 2x) "
          "| largest pair, px at 2x |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in a.names:
        r = designs.measure(name, a.tool, a.out)
        count, largest = overlapping_pairs(os.path.join(a.out, f"{name}.svg"), tool, a.least)
        print(f"| {name} | {r['seconds']:.1f} | {100 * r['overlap']:.2f} | {100 * r['outside']:.2f} | "
              f"{100 * r['empty']:.2f} | {count} | {largest} |", flush=True)


if __name__ == "__main__":
    main()
