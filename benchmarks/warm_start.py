"""Warm starts and pins on a closed 1,000-mark layout (issue 22).

    PYTHONPATH=$PWD python benchmarks/warm_start.py [N] [--device cpu|cuda]

Discs with areas uniform on [1, 10] fill the circular container of ``discs.py`` (closed
boundary, no force). Measured, each from the fresh layout:
* again: the same chart run a second time, nothing changed (max centre change, px);
* add: 5% more rows (``set_data``), then a run: the median displacement of the old units
  over the median mark radius, and the exact overlap;
* remove: 5% of the rows dropped, then a run: the density (disc area / container area)
  against a fresh layout of the same rows;
* pins: 1% of the rows pinned at other rows' places, then a run: the largest distance of a
  pinned centre from its pin, and the deepest overlap of a pinned disc (share of the radii).
Every run's seconds, on the machine as it is (say how busy it was).
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np
import pandas as pd

import discs
import unitopia_widget as uw

CONTAINER = uw.Container.ellipse(discs.CX, discs.CY, discs.R, discs.R)


def frame(n: int, start: int = 0, seed: int = 0) -> pd.DataFrame:
    return pd.DataFrame({"v": discs.values(n, "10x", seed)}, index=range(start, start + n))


def chart(df: pd.DataFrame, device) -> uw.Chart:
    return uw.Chart(df, size="v", container=CONTAINER, canvas=(discs.W, discs.H), device=device)


def timed(fn):
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def metrics(table: pd.DataFrame) -> dict:
    return discs.circle_metrics(table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2)


def moved(before: pd.DataFrame, after: pd.DataFrame) -> np.ndarray:
    m = before.merge(after, on=["layer", "row"], suffixes=("", "_2"))
    return np.hypot(m.x - m.x_2, m.y - m.y_2).to_numpy()


def worst_pin_overlap(table: pd.DataFrame, rows) -> float:
    """The deepest overlap of a pinned disc with any other, as a share of the two radii (0: none)."""
    xy, r = table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2
    worst = 0.0
    for k in np.nonzero(table["row"].isin(rows).to_numpy())[0]:
        gap = (np.hypot(*(xy - xy[k]).T) - r - r[k]) / (r + r[k])
        gap[k] = np.inf
        worst = max(worst, -float(gap.min()))
    return worst


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("n", nargs="?", type=int, default=1000)
    ap.add_argument("--device", default="cpu")
    args = ap.parse_args()
    n, extra = args.n, max(1, round(0.05 * args.n))
    base_df = frame(n)
    c = chart(base_df, args.device)
    base, t_fresh = timed(c.layout)
    radius = float(np.median(base["width"]) / 2)
    print(f"fresh: {t_fresh:.2f} s, {c.result.iterations} iterations, {metrics(base)}")

    again, t = timed(c.layout)
    same = float(np.abs(again[["x", "y"]].to_numpy() - base[["x", "y"]].to_numpy()).max())
    print(f"again: {t:.2f} s, max centre change {same:.3g} px")

    c.set_data(pd.concat([base_df, frame(extra, start=n, seed=1)]))
    added, t = timed(c.layout)
    d = moved(base, added)
    m = metrics(added)
    print(f"add {extra}: {t:.2f} s, {c.result.iterations} iterations, median displacement "
          f"{np.median(d):.2f} px = {np.median(d) / radius:.2f} median radii (p90 "
          f"{np.percentile(d, 90) / radius:.2f}), overlap {m['overlap_%']:.3f}%, "
          f"outside {m['outside_%']:.3f}%")

    c = chart(base_df, args.device)   # from the fresh layout again
    c.layout()
    keep = base_df.drop(index=base_df.index[::20][:extra])
    c.set_data(keep)
    removed, t = timed(c.layout)
    fresh_removed, t_ref = timed(chart(keep, args.device).layout)
    m, ref = metrics(removed), metrics(fresh_removed)
    print(f"remove {n - len(keep)}: {t:.2f} s, {c.result.iterations} iterations, density {m['density']:.3f} (fresh layout of the "
          f"same rows {ref['density']:.3f}, {t_ref:.2f} s), overlap {m['overlap_%']:.3f}%, "
          f"median displacement {np.median(moved(base, removed)) / radius:.2f} median radii")

    c = chart(base_df, args.device)
    c.layout()
    count = max(1, n // 100)
    rows = base_df.index[:count]
    spots = base.set_index("row").loc[base_df.index[n // 2:n // 2 + count], ["x", "y"]].to_numpy()
    c.pin(list(rows), x=spots[:, 0], y=spots[:, 1])
    pinned, t = timed(c.layout)
    held = pinned.set_index("row").loc[rows, ["x", "y"]].to_numpy()
    off = float(np.hypot(*(held - spots).T).max())
    print(f"pins {count}: {t:.2f} s, {c.result.iterations} iterations, max distance from pin "
          f"{off:.3g} px, deepest overlap of a pinned disc {worst_pin_overlap(pinned, rows):.3f} of "
          f"the radii (of any disc: {worst_pin_overlap(pinned, pinned.row):.3f}), overall overlap "
          f"{metrics(pinned)['overlap_%']:.3f}%")


if __name__ == "__main__":
    main()
