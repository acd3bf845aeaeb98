"""The corpus scoreboard: every generated design laid out, exported and measured.

    python benchmarks/scoreboard.py [--quick] [--seed S] [--n N] [--seeds 0-4]
                                    [--save out.json] [--against before.json] [--png DIR]
    python benchmarks/scoreboard.py --show benchmarks/corpus-baseline.json [--against other.json]

Per design (``corpus/generate.py`` draws them from ``--seed``): overlap and ink outside
(% of the ink, from the SVG), empty share (% of the closed containers farther than one
median mark radius from any ink), fill reached / asked (open containers; the one furthest
below its ask), join (the largest mark that splits its container into large pieces, as a
multiple of the median mark: a mark across a narrow join; 0 when none), strata in order
(share of the blocked layers' marks beyond the layer they rest on), |rho| of mark area
against position (distance from the force point, depth along a directional force, or
distance from the container's centre), pull (how far the forces gathered the marks: 1
against the far wall or at the point), layout seconds, the solver's iterations (a layout at
or past its layers' ``iterations=`` budget never came to rest by its own criteria) and the
number of warnings. Then the totals and the ten worst designs by ``badness`` (each term is
1 at the issue's bound: 1% overlap, 0.5% outside, 10% empty beyond 10%, 20% of the asked
fill missing with no warning, 10% of strata out of order, 30 s).
``--seeds 0-4`` lays each design out with those layout seeds and reports the spread
(max - min) of every measure: the noise a change must beat. ``--against`` prints each
design's change from a saved board (matched by id and seed).
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from corpus import generate, run  # noqa: E402

QUICK = ("k2-thin-push", "k5-twins", "m001", "m005", "m007", "m011", "m017", "m019", "m038", "m043",
         "m044", "m046", "m047", "m048", "m053")
MEASURES = ("overlap", "outside", "empty", "fill", "join", "strata", "rho", "pull", "seconds",
            "iterations")
PERCENT = {"overlap", "outside", "empty", "fill"}


def quick_slice(specs):
    """The quick slice: the designs whose ids are in ``QUICK``, picked from the seed-0 board
    of main at 2ae03fe as fast ones (under 6 s each on a busy 2-core CPU) that cover the
    containers, marks, forces, strata and both boundaries."""
    return [s for s in specs if s.id in QUICK]


def badness(r: dict) -> float:
    if "error" in r:
        return math.inf
    terms = [r["overlap"] / 0.01, r["outside"] / 0.005, max(0.0, (r["empty"] or 0) - 0.1) / 0.1,
             max(0.0, r["seconds"] - 30) / 30]
    if r["fill"] is not None and not r["warnings"]:
        terms.append(max(0.0, 1 - r["fill"] / r["fill_asked"]) / 0.2)
    if r["strata"] is not None:
        terms.append((1 - r["strata"]) / 0.1)
    return float(sum(terms))


def fmt(name: str, v) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return ""
    if name in PERCENT:
        return f"{100 * v:.2f}"
    if name == "iterations":
        return f"{v:.0f}"
    return f"{v:.1f}" if name == "seconds" else f"{v:.2f}"


HEADER = ("| design | container | mark | data | force | L | bnd | n | overlap % | outside % | "
          "empty % | fill % / asked | join x | strata | abs rho | pull | s | it | warn |")


RULE = "|---|---|---|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"


def line(r: dict) -> str:
    if "error" in r:
        return f"| {r['id']} | failed: {r['error'][:120]} |" + " |" * 17
    t = r["tags"]
    fill = "" if r["fill"] is None else f"{100 * r['fill']:.0f} / {100 * r['fill_asked']:.0f}"
    return (f"| {r['id']} | {t.get('container', '')} | {t.get('mark', '')} | {t.get('data', '')} | "
            f"{t.get('force', '')} | {t.get('layers', 1)} | {t.get('boundary', '')} | "
            f"{r['units']} | "
            f"{fmt('overlap', r['overlap'])} | {fmt('outside', r['outside'])} | "
            f"{fmt('empty', r['empty'])} | {fill} | {fmt('join', r.get('join'))} | "
            f"{fmt('strata', r['strata'])} | "
            f"{fmt('rho', r['rho'])} | {fmt('pull', r['pull'])} | {fmt('seconds', r['seconds'])} | "
            f"{fmt('iterations', r.get('iterations'))} | {len(r['warnings'])} |")


def totals(records: list) -> list[str]:
    ok = [r for r in records if "error" not in r]
    col = lambda k: np.array([r[k] for r in ok if r[k] is not None], float)  # noqa: E731
    out = [f"designs: {len(records)} ({len(records) - len(ok)} failed); layout seconds: "
           f"{col('seconds').sum():.0f} in all, median {np.median(col('seconds')):.1f}, "
           f"max {col('seconds').max():.1f}, over 30 s: {int((col('seconds') > 30).sum())}"]
    counted = [r for r in ok if r.get("iterations") is not None]
    if counted:
        spent = sum(1 for r in counted if r["iterations"] >= r["budget"])
        out.append(f"iterations: median {np.median([r['iterations'] for r in counted]):.0f}; "
                   f"the whole budget spent (never at rest): {spent} of {len(counted)}")
    for k, bound in (("overlap", 0.01), ("outside", 0.005), ("empty", 0.10)):
        v = col(k)
        if len(v):
            out.append(f"{k}: mean {100 * v.mean():.2f}%, median {100 * np.median(v):.2f}%, "
                       f"max {100 * v.max():.2f}%, over {100 * bound:g}%: {int((v > bound).sum())} "
                       f"of {len(v)}")
    opened = [r for r in ok if r["fill"] is not None] or [{"fill": 1.0, "fill_asked": 1.0,
                                                             "warnings": []}]
    short = [r for r in opened if r["fill"] < 0.8 * r["fill_asked"]]
    reached = np.median([r["fill"] / r["fill_asked"] for r in opened])
    out.append(f"fill (open): reached / asked median {reached:.2f}; "
               f"under 80% of the ask: {len(short)} of {len(opened)} "
               f"({sum(1 for r in short if not r['warnings'])} with no warning)")
    joined = list(dict.fromkeys(r["id"] for r in ok if (r.get("join") or 0) >= 2))
    out.append(f"a mark of at least 2 median marks across a narrow join: {len(joined)} designs "
               f"({', '.join(joined[:8])}{', ...' if len(joined) > 8 else ''})")
    s, rho = col("strata"), col("rho")
    if len(s):
        out.append(f"strata in order: mean {s.mean():.2f}, under 0.9: {int((s < 0.9).sum())} "
                   f"of {len(s)}")
    if len(rho):
        out.append(f"abs rho of size against position: mean {rho.mean():.2f}, "
                   f"median {np.median(rho):.2f}")
    return out


def worst(records: list, k: int = 10) -> list[dict]:
    return sorted(records, key=badness, reverse=True)[:k]


def spread(records: list) -> list[str]:
    """Per design the spread (max - min) of each measure over its layout seeds, and the
    median spread over designs: the noise a change must beat."""
    by_id = {}
    for r in records:
        if "error" not in r:
            by_id.setdefault(r["id"], []).append(r)
    rows, noise = [], {k: [] for k in MEASURES}
    rows.append("| design | seeds | " + " | ".join(f"{k} spread" for k in MEASURES) + " |")
    rows.append("|---|---:|" + "---:|" * len(MEASURES))
    for name, rs in by_id.items():
        cells = []
        for k in MEASURES:
            v = [r[k] for r in rs if r.get(k) is not None]
            d = max(v) - min(v) if len(v) > 1 else None
            if d is not None:
                noise[k].append(d)
            cells.append(fmt(k, d))
        rows.append(f"| {name} | {len(rs)} | " + " | ".join(cells) + " |")
    rows.append("median spread: " + ", ".join(
        f"{k} {fmt(k, float(np.median(v)))}{'%' if k in PERCENT else ''}"
        for k, v in noise.items() if v))
    return rows


def against(records: list, before: list) -> list[str]:
    """Per design, each measure before -> after (matched by id and seed)."""
    old = {(r["id"], r["seed"]): r for r in before}
    out = ["| design | " + " | ".join(MEASURES) + " | badness |",
           "|---|" + "---|" * (len(MEASURES) + 1)]
    for r in records:
        b = old.get((r["id"], r["seed"]))
        if b is None or "error" in r or "error" in b:
            out.append(f"| {r['id']} | {'new' if b is None else 'failed before or after'} |")
            continue
        cells = []
        for k in MEASURES:
            if r.get(k) is None or b.get(k) is None:
                cells.append("")
                continue
            d = r[k] - b[k]
            sign = "+" if d >= 0 else "-"
            cells.append(f"{fmt(k, b[k])} -> {fmt(k, r[k])} ({sign}{fmt(k, abs(d))})")
        out.append(f"| {r['id']} | " + " | ".join(cells)
                   + f" | {badness(b):.1f} -> {badness(r):.1f} |")
    return out


def parse_seeds(text: str) -> list[int]:
    lo, _, hi = text.partition("-")
    try:
        return list(range(int(lo), int(hi or lo) + 1))
    except ValueError:
        raise SystemExit(f"--seeds must be a seed or a range such as 0-4, got {text!r}") from None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help=f"only the quick slice ({len(QUICK)} designs)")
    ap.add_argument("--seed", type=int, default=0, help="the corpus seed (which designs)")
    ap.add_argument("--n", type=int, default=120, help="designs in the corpus (default 120)")
    ap.add_argument("--only", nargs="*", help="design ids to run")
    ap.add_argument("--seeds", default="0", help="layout seeds, e.g. 0-4 to measure the noise")
    ap.add_argument("--threads", type=int, help="torch threads (default: torch's)")
    ap.add_argument("--save", help="write the per-design records to this JSON file")
    ap.add_argument("--against", help="a saved board to compare with, design by design")
    ap.add_argument("--png", help="also save each chart as DIR/<id>-<seed>.png")
    ap.add_argument("--show", help="print a saved board (its designs, totals, worst ten) and stop")
    a = ap.parse_args(argv)
    if a.show:
        with open(a.show) as f:
            report(json.load(f)["designs"], a.against)
        return
    if a.threads:
        import torch
        torch.set_num_threads(a.threads)
    specs = generate.corpus(a.seed, a.n)
    if a.quick:
        specs = quick_slice(specs)
    if a.only:
        specs = [s for s in specs if s.id in a.only]
    folder = tempfile.mkdtemp(prefix="uw-corpus-")
    if a.png:
        os.makedirs(a.png, exist_ok=True)
    records, t0 = [], time.perf_counter()
    print(HEADER)
    print(RULE)
    for spec in specs:
        for seed in parse_seeds(a.seeds):
            png = os.path.join(a.png, f"{spec.id}-{seed}.png") if a.png else None
            r = run.run(spec, folder, seed, png)
            records.append(r)
            print(line(r), flush=True)
    print(f"\nwall time {time.perf_counter() - t0:.0f} s")
    if a.save:
        meta = {"seed": a.seed, "n": a.n, "seeds": a.seeds, "quick": a.quick, "only": a.only,
                "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes"),
                "machine": f"{platform.machine()}, {os.cpu_count()} cores",
                "python": platform.python_version()}
        with open(a.save, "w") as f:
            json.dump({"meta": meta, "designs": [{k: v for k, v in r.items() if k != "traceback"}
                                                 for r in records]}, f, indent=1)
    report(records, a.against, table=False)


def report(records: list, before: str | None, table: bool = True) -> None:
    """Print the board of ``records``: the designs (``table``), totals, worst ten, the
    spread over layout seeds (when there are several), and the change from ``before``."""
    if table:
        print(HEADER)
        print(RULE)
        print("\n".join(line(r) for r in records))
    print("\n## Totals\n")
    print("\n".join("- " + t for t in totals(records)))
    print("\n## Worst ten (badness: 1 = at the issue's bound on one measure)\n")
    print(HEADER.replace("| warn |", "| warn | badness |"))
    print(RULE + "---:|")
    for r in worst(records):
        print(line(r) + f" {badness(r):.1f} |")
    if len({r["seed"] for r in records}) > 1:
        print("\n## Spread over layout seeds\n")
        print("\n".join(spread(records)))
    if before:
        with open(before) as f:
            print("\n## Against " + before + "\n")
            print("\n".join(against(records, json.load(f)["designs"])))


if __name__ == "__main__":
    main()
