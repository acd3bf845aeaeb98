"""One mark for k units on a large table (issue 50, part 4), measured.

A million rows of transactions (a payment kind of four, skewed 50/30/15/5 %), drawn with
``per=100`` coloured by kind: the seconds the rows take to bind (``Chart(...)``, which
groups them with pandas, and ``bind`` alone), the marks they make, and the seconds the
layout takes, as a grid of squares in a rectangle (``arrange="grid"``: the ISOTYPE chart)
and, with ``--free``, packed freely (the default arrangement; 23 to 37 s at 10,000 marks on
the shared 2-core Xeon).
Also the refusal of 25,000 rows without ``per=``, timed, and the per= it names.

    OMP_NUM_THREADS=2 python benchmarks/per_million.py [--rows 1000000] [--per 100] [--free]
"""
from __future__ import annotations

import argparse
import os
import time

import numpy as np
import pandas as pd

import unitopia_widget as uw
from unitopia_widget.layout.prepare.bind import bind


def transactions(rows: int) -> pd.DataFrame:
    rng = np.random.default_rng(0)
    kinds = rng.choice(["card", "cash", "mobile", "voucher"], rows, p=[0.5, 0.3, 0.15, 0.05])
    return pd.DataFrame({"kind": kinds, "amount": rng.gamma(2.0, 20.0, rows)})


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--per", type=float, default=100)
    parser.add_argument("--free", action="store_true", help="also lay out packed freely")
    args = parser.parse_args()
    per = int(args.per) if float(args.per).is_integer() else args.per
    df = transactions(args.rows)
    print(f"load {os.getloadavg()[0]:.1f}, {os.cpu_count()} CPUs, rows {args.rows:,}, per={per}")
    box = uw.Container.rect(10, 10, 780, 480)
    chart, construct = timed(lambda: uw.Chart(df, color="kind", per=per, mark="square",
                                              arrange="grid", container=box))
    units, alone = timed(lambda: bind(chart.df, chart.layers))
    counts = pd.Series(chart.df.loc[units.rows, "kind"]).value_counts().to_dict()
    print(f"bind: Chart(...) {construct:.2f} s, bind alone {alone:.2f} s; {len(units.rows):,} "
          f"marks {counts}")
    _, grid = timed(chart.layout)
    print(f"layout, arrange='grid': {grid:.1f} s, {chart.result.iterations} iterations")
    if args.free:
        free = uw.Chart(df, color="kind", per=per, mark="square")
        _, packed = timed(free.layout)
        print(f"layout, arrange='free': {packed:.1f} s, {free.result.iterations} iterations")
    t0 = time.perf_counter()
    try:
        uw.Chart(df.iloc[:25_000], mark="square")
    except ValueError as exc:
        print(f"25,000 rows without per=: refused in {time.perf_counter() - t0:.2f} s: {exc}")
    print(f"load {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
