"""Strata cases of issue 18, part 3: a grid-emitted layer on a packed pile (down, around a
point), a packed layer on a layer poured from a curve, and two point piles grown into one
another (50, 70, 90 px apart). Prints per case the strata measure, the mean height of each
layer (lower first: mean y negated under a downward force, the mean distance from the point
otherwise), the overlap (``tests/ink.py`` on the bare SVG), seconds and iterations, and
writes each PNG into ``--out``.

Strata measure: the share of the upper layer below the lower layer's upper envelope (down) or
inside its radial envelope (point); for the piles, per upper layer, the share of marks with
the lower layer's ink within one of its largest radii outward along their pull.

    PYTHONPATH=$PWD python benchmarks/strata_cases.py [--out DIR]
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np
import pandas as pd
import torch

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import unitopia_widget as uw   # noqa: E402
from envelope import below_envelope   # noqa: E402
from ink import ink_metrics    # noqa: E402

BINS = 360   # angle bins of the radial envelope


def lognormal(n: int, spread: float, seed: int) -> np.ndarray:
    """n lognormal values rescaled so that max / min is exactly ``spread``."""
    logs = np.log(np.random.default_rng(seed).lognormal(0.0, 1.0, n))
    return np.exp((logs - logs.min()) / np.ptp(logs) * math.log(spread))


def inside(table, lower: str, upper: str, point) -> float:
    """Share of ``upper``'s centres inside the radial envelope of ``lower``'s discs."""
    ray = (np.arange(BINS) + 0.5) / BINS * 2 * math.pi
    top = np.zeros(BINS)
    for x, y, w in table[table["layer"] == lower][["x", "y", "width"]].to_numpy():
        d, a = math.hypot(x - point[0], y - point[1]), math.atan2(y - point[1], x - point[0])
        off = d * np.sin(ray - a)
        far = d * np.cos(ray - a) + np.sqrt(np.maximum((w / 2) ** 2 - off ** 2, 0.0))
        top = np.where((np.abs(off) <= w / 2) & (far > 0), np.maximum(top, far), top)
    up = table[table["layer"] == upper]
    dx, dy = up["x"].to_numpy() - point[0], up["y"].to_numpy() - point[1]
    b = np.minimum((np.arctan2(dy, dx) % (2 * math.pi) / (2 * math.pi) * BINS).astype(int), BINS - 1)
    return float(np.mean(np.hypot(dx, dy) < top[b]))


def covered(table, lower: str, upper: str, points: np.ndarray) -> float:
    """Share of ``upper``'s marks with ``lower``'s ink within one of its largest radii
    outward along their pull (from the nearest of ``points (K, 2)``): in a gap between them."""
    low = table[table["layer"] == lower]
    c, r = low[["x", "y"]].to_numpy(), low["width"].to_numpy() / 2
    xy = table[table["layer"] == upper][["x", "y"]].to_numpy()
    own = np.argmin([np.hypot(*(xy - p).T) for p in points], axis=0)
    hits = 0
    for q, k in zip(xy, own):
        e = (q - points[k]) / max(float(np.hypot(*(q - points[k]))), 1e-9)
        s = q[None] + np.arange(0.0, r.max(), 1.0)[:, None] * e
        hits += bool((np.hypot(s[:, None, 0] - c[None, :, 0], s[:, None, 1] - c[None, :, 1]) < r).any())
    return hits / len(xy)


def cases():
    """(name, chart, strata measure (table -> value), height (layer's rows -> float))."""
    box = dict(canvas=(400, 300), boundary="open", container=uw.Container.rect(10, 10, 380, 280))
    for pull in ("down", "point"):
        k = np.repeat([0, 1], [30, 60])
        df = pd.DataFrame({"k": k, "v": np.where(k == 0, lognormal(90, 6, 1), 0.5)})
        force = uw.DirectionalForce(90) if pull == "down" else uw.PointForce(200, 150)
        chart = uw.Chart(df, size="v", by="k", color="k", forces=[force], iterations=300, **box)
        chart.layer("1").set(emitter=uw.GridEmitter(), blocks=["0"])
        if pull == "down":
            yield "grid-down", chart, lambda t: below_envelope(t, "0", "1"), lambda g: -g["y"].mean()
        else:
            yield ("grid-point", chart, lambda t: inside(t, "0", "1", (200, 150)),
                   lambda g: np.hypot(g["x"] - 200, g["y"] - 150).mean())
    k = np.repeat([0, 1], [16, 32])
    df = pd.DataFrame({"k": k, "v": lognormal(48, 6, 1) * np.where(k == 0, 1.0, 0.4)})
    chart = uw.Chart(df, size="v", by="k", color="k", fill=0.2, forces=[uw.DirectionalForce(90)],
                     iterations=1000, **box)
    chart.layer("0").set(emitter=uw.CurveEmitter([(40, 30), (150, 20), (250, 40), (360, 30)]))
    chart.layer("1").set(blocks=["0"])
    yield "packed-on-poured", chart, lambda t: below_envelope(t, "0", "1"), lambda g: -g["y"].mean()
    for gap in (50, 70, 90):
        points = np.array([(200 - gap / 2, 100.0), (200 + gap / 2, 100.0)])
        k = np.repeat(np.arange(3), [12, 36, 108])
        df = pd.DataFrame({"k": k, "v": lognormal(len(k), 4, 3) * 16.0 ** (-k / 2)})
        chart = uw.Chart(df, size="v", by="k", color="k", canvas=(400, 200), boundary="open",
                         fill=0.35, container=uw.Container.rect(5, 5, 390, 190),
                         forces=[uw.PointForce(*p) for p in points], iterations=300)
        for j in (1, 2):
            chart.layer(str(j)).set(blocks=[str(j - 1)])
        yield (f"piles-{gap}", chart,
               lambda t, points=points: [round(covered(t, str(j - 1), str(j), points), 3) for j in (1, 2)],
               lambda g, points=points: np.min([np.hypot(g["x"] - x, g["y"] - y) for x, y in points],
                                               axis=0).mean())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=".", help="folder for the PNGs")
    args = ap.parse_args()
    torch.set_num_threads(1)
    for name, chart, strata, height in cases():
        start = time.time()
        table = chart.layout()
        seconds = time.time() - start
        overlap = ink_metrics(chart.to_svg(legend=False), chart.canvas, k=1)["overlap"]
        mean = {layer: round(float(height(rows)), 1) for layer, rows in table.groupby("layer")}
        value = strata(table)
        print(f"{name}: strata {value if isinstance(value, list) else round(value, 3)} mean {mean} "
              f"overlap {overlap:.2%} {seconds:.1f} s {chart.result.iterations} it", flush=True)
        with open(os.path.join(args.out, f"{name}.png"), "wb") as f:
            f.write(chart.to_png(2.0, legend=False))


if __name__ == "__main__":
    main()
