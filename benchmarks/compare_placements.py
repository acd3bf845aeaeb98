"""Placements to the digit: save them from one tree, compare another tree's to them.

Lays out the real designs (``designs.py``) and the Table 1 set-ups (``table1.py``:
the circle with a point force, equal and heavy-tailed sizes, open, and equal sizes
closed) and saves every numeric column of each placements table, or reports the
largest absolute difference per design against a saved file. A refactor that
changes no layout reports 0 everywhere.

    PYTHONPATH=$PWD python benchmarks/compare_placements.py --save before.npz [--quick]
    PYTHONPATH=$PWD python benchmarks/compare_placements.py --against before.npz [--quick]
"""
from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import designs   # noqa: E402
import discs     # noqa: E402

QUICK = ["bubbles", "hair", "flowers", "seesaw", "rects", "table1-200-equal", "table1-200-closed"]


def table1(n: int, sizes: str, closed: bool):
    """The Table 1 chart (``table1._layout``), laid out; its placements table."""
    import unitopia_widget as uw
    df = pd.DataFrame({"value": discs.values(n, sizes, 0)})
    chart = uw.Chart(df, mark="circle", size="value", canvas=(discs.W, discs.H), seed=0,
                     container=uw.Container.ellipse(discs.CX, discs.CY, discs.R, discs.R),
                     forces=[] if closed else [uw.PointForce(discs.FX, discs.FY)],
                     boundary="closed" if closed else "open", fill=None if closed else discs.FILL,
                     iterations=1000)
    chart.layout()
    return chart.placements


def design(name: str):
    """A design of ``designs.py``, laid out; its placements table."""
    w, _ = designs.build(name)
    w.run(wait=True)
    return w.placements


def cases() -> dict:
    """Name -> a function laying the case out and returning its placements table."""
    out = {name: (lambda name=name: design(name)) for name in designs.DESIGNS}
    for n in (200, 1000, 5000):
        for sizes in ("equal", "heavy"):
            out[f"table1-{n}-{sizes}"] = lambda n=n, sizes=sizes: table1(n, sizes, False)
        out[f"table1-{n}-closed"] = lambda n=n: table1(n, "equal", True)
    return out


def numeric(table: pd.DataFrame) -> np.ndarray:
    """``(N, C)`` float64: the table's numeric columns, in order."""
    return table.select_dtypes("number").to_numpy(dtype=np.float64)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("names", nargs="*", help="cases to run (default: all, or the --quick ones)")
    ap.add_argument("--quick", action="store_true", help=f"only {', '.join(QUICK)}")
    io = ap.add_mutually_exclusive_group(required=True)
    io.add_argument("--save", help="write the placements to this .npz")
    io.add_argument("--against", help="compare the placements to this .npz")
    a = ap.parse_args(argv)
    every = cases()
    names = a.names or (QUICK if a.quick else list(every))
    unknown = [n for n in names if n not in every]
    if unknown:
        ap.error(f"unknown case(s) {unknown}; known: {', '.join(every)}")
    saved = dict(np.load(a.against)) if a.against else {}
    got, worst = {}, 0.0
    for name in names:
        t0 = time.perf_counter()
        values = numeric(every[name]())
        seconds = time.perf_counter() - t0
        got[name] = values
        if a.save:
            np.savez(a.save, **got)   # after each case: a run cut short keeps what it made
            print(f"{name}: saved {values.shape}, {seconds:.1f} s", flush=True)
        elif name not in saved:
            print(f"{name}: not in {a.against}", flush=True)
        elif saved[name].shape != values.shape:
            print(f"{name}: shape {values.shape} != saved {saved[name].shape}", flush=True)
            worst = np.inf
        else:
            diff = float(np.nanmax(np.abs(values - saved[name]))) if values.size else 0.0
            same_nan = bool((np.isnan(values) == np.isnan(saved[name])).all())
            worst = max(worst, diff if same_nan else np.inf)
            print(f"{name}: max abs difference {diff:.3g}{'' if same_nan else ', NaNs differ'}"
                  f", {seconds:.1f} s", flush=True)
    if a.against:
        print(f"largest difference {worst:.3g}")
        return 0 if worst == 0 else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
