"""Edits answered against a fresh layout (issue 49).

    PYTHONPATH=$PWD python benchmarks/edits.py [--n 1000] [--boundary closed|open]

The Table 1 disc set-up (``discs.py``: sizes uniform on [1, 10] in area, the circular
container; closed: the marks fill it, no force; open: a point force at its bottom, the
marks cover ``discs.FILL`` of it). One fresh layout, then each edit from that layout, on
a copy of the chart with its last run (as a user makes one edit and runs):

* again: Run with nothing changed;
* pin: the middle row pinned 30 px from its place, towards the container's centre;
* add: 5% more rows (``set_data``); remove: 5% of the rows dropped;
* margin: the layer's margin set to 0.05; force (open only): the point force moved 10 px.

For each: the seconds, how the run answered (``reflow``: the marks the change reaches;
``full``: the full warm run; ``kept``: the last layout itself), the share of the marks
kept from the fresh layout that moved more than a tenth of the median radius, the exact
overlap and outside (``discs.circle_metrics``); for the pin also the median displacement
of the marks more than 5 radii from the pin, in radii. The fresh layout's seconds are
the reference. Timings are the machine's as it is: report its load (``uptime``).
"""
from __future__ import annotations

import argparse
import time

import numpy as np
import pandas as pd

import discs
import unitopia_widget as uw

CONTAINER = uw.Container.ellipse(discs.CX, discs.CY, discs.R, discs.R)


def rows(n: int, start: int = 0, seed: int = 0) -> pd.DataFrame:
    return pd.DataFrame({"v": discs.values(n, "10x", seed)}, index=range(start, start + n))


def chart(df: pd.DataFrame, closed: bool) -> uw.Chart:
    return uw.Chart(df, size="v", container=CONTAINER, canvas=(discs.W, discs.H), device="cpu",
                    boundary="closed" if closed else "open", fill=None if closed else discs.FILL,
                    forces=[] if closed else [uw.PointForce(discs.FX, discs.FY)])


def copy(laid: uw.Chart, closed: bool) -> uw.Chart:
    """A chart like ``laid`` with its last run, for one edit."""
    other = chart(laid.df, closed)
    for name in ("laid", "_units", "_snapshot", "_origin", "_ran", "_pins"):
        setattr(other, name, getattr(laid, name))
    return other


def answered(c: uw.Chart, before) -> str:
    if c.laid is before:
        return "kept"
    return "reflow" if "reflow" in c.result.phases else "full"


def measure(name: str, c: uw.Chart, base: pd.DataFrame, radius: float) -> dict:
    before = c.laid
    t = time.perf_counter()
    table = c.layout()
    seconds = time.perf_counter() - t
    m = base.merge(table, on=["layer", "row"], suffixes=("", "_2"))
    moved = np.hypot(m.x - m.x_2, m.y - m.y_2).to_numpy()
    q = discs.circle_metrics(table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2)
    out = {"edit": name, "seconds": seconds, "answer": answered(c, before),
           "moved": float((moved > 0.1 * radius).mean()), "overlap_%": q["overlap_%"],
           "outside_%": q["outside_%"]}
    print(f"  {name:7s} {seconds:7.3f} s  {out['answer']:6s} moved {out['moved']:6.1%}  "
          f"overlap {q['overlap_%']:.3f}%  outside {q['outside_%']:.3f}%", flush=True)
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--boundary", choices=["closed", "open"], default="closed")
    args = ap.parse_args()
    n, closed = args.n, args.boundary == "closed"
    extra = max(1, round(0.05 * n))
    df = rows(n)
    c = chart(df, closed)
    t = time.perf_counter()
    base = c.layout()
    fresh = time.perf_counter() - t
    radius = float(np.median(base["width"]) / 2)
    q = discs.circle_metrics(base[["x", "y"]].to_numpy(), base["width"].to_numpy() / 2)
    print(f"{n} marks, {args.boundary}: fresh {fresh:.2f} s, {c.result.iterations} iterations, "
          f"overlap {q['overlap_%']:.3f}%", flush=True)

    measure("again", copy(c, closed), base, radius)

    e = copy(c, closed)
    row = base.iloc[n // 2]
    way = np.array([discs.CX - row.x, discs.CY - row.y])
    to = np.array([row.x, row.y]) + 30 * way / max(float(np.hypot(*way)), 1e-9)
    e.pin([row.row], x=to[0], y=to[1])
    # measured after the run: the marks far from the pin, their median displacement in radii
    far = np.hypot(base.x - to[0], base.y - to[1]).to_numpy() > 5 * radius
    measure("pin", e, base, radius)
    shift = np.hypot(e.placements.x - base.x, e.placements.y - base.y).to_numpy()
    print(f"          pin: far marks' median displacement {np.median(shift[far]) / radius:.4f} radii")

    e = copy(c, closed)
    e.set_data(pd.concat([df, rows(extra, start=n, seed=1)]))
    measure("add", e, base, radius)

    e = copy(c, closed)
    e.set_data(df.drop(index=df.index[::20][:extra]))
    measure("remove", e, base, radius)

    e = copy(c, closed)
    e.layer(0).set(margin=0.05)
    measure("margin", e, base, radius)

    if not closed:
        e = copy(c, closed)
        e.layer(0).set(forces=[uw.PointForce(discs.FX + 10, discs.FY)])
        measure("force", e, base, radius)


if __name__ == "__main__":
    main()
