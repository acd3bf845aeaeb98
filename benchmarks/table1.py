"""The paper's Table 1 set-up through the public API, against pymunk, each in a fresh process.

A circular container (radius 400) on a 1440 x 830 canvas, a point force at its
bottom (720, 815), open boundary, marks covering 60% of the container; sizes
equal, "10x" (areas uniform on 1 to 10) or "heavy" (lognormal, see
``discs.values``). Every (N, sizes) runs in a fresh Python process (this
script with ``--one``, printing one JSON line), the way a user meets it:

- ``import s``: ``import unitopia_widget`` (torch included; numpy, pandas and
  scipy are already loaded, as in a notebook);
- ``cold s``: the first layout in that process, from binding
  (``uw.Chart(...)``) to the placements table; ``warm s``: the same layout
  again in the same process; ``ms/iter``: warm seconds over iterations;
  ``peak MB``: growth of the peak RSS during the cold layout;
- quality of the cold layout, exactly from the placements (``discs.circle_metrics``):
  overlap and outside as a share of the mark area, and ``mean_y``, the mean
  centre height (the container's centre is at 415, its bottom at 815);
- ``pymunk``: the same discs settled by the physics engine in its own fresh
  process (``peers.py``: cold, then warm), its overlap, and ours / pymunk.
  ``--pymunk random`` (default) pours the discs in uniformly
  (``discs.random_start``: how a physics user starts it, and the issue's
  reference of 1.2 to 1.5 s at 1,000), ``--pymunk lattice`` starts it on the
  engine's own start (``discs.lattice_start``: pymunk's best case, the pile
  already made), ``--pymunk off`` leaves it out.

With ``--closed`` (closed boundary, no force: the scale grows until the
container is full) ``density`` replaces ``mean_y`` and pymunk is left out:
a physics engine has no counterpart of the growing scale.
Run it with the engine of the tree (the child processes import the engine this
process finds, which the header line names):

    PYTHONPATH=$PWD python benchmarks/table1.py            # all sizes, equal, 10x, heavy
    PYTHONPATH=$PWD python benchmarks/table1.py 200 1000   # some sizes
    PYTHONPATH=$PWD python benchmarks/table1.py --sizes 10x,heavy --pymunk random
    PYTHONPATH=$PWD python benchmarks/table1.py --closed --equal-only
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time

import pandas as pd

import discs

COLUMNS = [   # (header, key, format)
    ("N", "N", "{:,}"), ("sizes", "sizes", "{}"), ("import s", "import_s", "{:.2f}"),
    ("cold s", "cold_s", "{:.2f}"), ("warm s", "warm_s", "{:.2f}"),
    ("iterations", "iterations", "{}"), ("ms/iter", "ms_iter", "{:.1f}"),
    ("peak MB", "peak_MB", "{:.0f}"), ("overlap %", "overlap_%", "{:.3f}"),
    ("outside %", "outside_%", "{:.3f}"), ("mean_y", "mean_y", "{:.0f}"),
    ("pymunk cold s", "pymunk_cold_s", "{:.2f}"), ("pymunk warm s", "pymunk_warm_s", "{:.2f}"),
    ("pymunk steps", "pymunk_steps", "{}"), ("pymunk overlap %", "pymunk_overlap_%", "{:.3f}"),
    ("ours/pymunk cold", "ratio_cold", "{:.2f}"), ("ours/pymunk warm", "ratio_warm", "{:.2f}"),
]


def engine(n: int, sizes: str, closed: bool, seed: int = 0) -> dict:
    """Import the engine, then lay the same chart out twice; meant for a fresh process."""
    t0 = time.perf_counter()
    import unitopia_widget as uw
    import_s = time.perf_counter() - t0
    df = pd.DataFrame({"value": discs.values(n, sizes, seed)})
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    cold_s, chart = _layout(uw, df, closed, seed)
    peak = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - rss0) / 1024
    table, iterations = chart.placements, chart.result.iterations
    warm_s, again = _layout(uw, df, closed, seed)
    quality = discs.circle_metrics(table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2)
    import torch
    return {"torch": torch.__version__, "torch_threads": torch.get_num_threads(),
            "import_s": import_s, "cold_s": cold_s, "warm_s": warm_s, "iterations": iterations,
            "ms_iter": 1000 * warm_s / again.result.iterations, "peak_MB": peak, **quality}


def _layout(uw, df: pd.DataFrame, closed: bool, seed: int):
    """Seconds from binding to the placements table, and the chart."""
    t0 = time.perf_counter()
    chart = uw.Chart(df, mark="circle", size="value", canvas=(discs.W, discs.H), seed=seed,
                     container=uw.Container.ellipse(discs.CX, discs.CY, discs.R, discs.R),
                     forces=[] if closed else [uw.PointForce(discs.FX, discs.FY)],
                     boundary="closed" if closed else "open", fill=None if closed else discs.FILL,
                     iterations=1000)
    chart.layout()
    return time.perf_counter() - t0, chart


def pymunk(n: int, sizes: str, start: str, seed: int = 0) -> dict:
    """Settle the same discs with pymunk twice (cold, warm), from sizes to centres; meant
    for a fresh process."""
    import peers
    runs = []
    for _ in range(2):   # settle's own seconds: freeing the space (0.9 s at 5,000) is not timed
        t0 = time.perf_counter()
        r = discs.radii(discs.values(n, sizes, seed))
        at = discs.lattice_start(r) if start == "lattice" else discs.random_start(r, seed)
        prepare = time.perf_counter() - t0
        out = peers.settle(r, at)
        runs.append((prepare + out["seconds"], out))
    quality = discs.circle_metrics(runs[0][1]["center"], r)
    return {"pymunk_cold_s": runs[0][0], "pymunk_warm_s": runs[1][0],
            "pymunk_steps": runs[0][1]["steps"], "pymunk_overlap_%": quality["overlap_%"],
            "pymunk_outside_%": quality["outside_%"], "pymunk_mean_y": quality["mean_y"]}


def fresh(kind: str, n: int, sizes: str, closed: bool, start: str = "lattice") -> dict:
    """Run ``engine`` or ``pymunk`` in a fresh Python process; its JSON result. The child
    imports the ``unitopia_widget`` this process would (``_engine_path``)."""
    cmd = [sys.executable, os.path.abspath(__file__), str(n), "--one", kind, "--sizes", sizes,
           "--pymunk", start]
    path = [os.path.dirname(_engine_path()), os.environ.get("PYTHONPATH")]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in path if p)}
    done = subprocess.run(cmd + (["--closed"] if closed else []), capture_output=True, text=True,
                          env=env)
    if done.returncode:
        raise RuntimeError(f"{kind} N={n} sizes={sizes} failed:\n{done.stderr}")
    return json.loads(done.stdout.splitlines()[-1])


def row(n: int, sizes: str, closed: bool, peer: str) -> dict:
    """One table row: the engine, then (open layouts, ``peer`` a start, not ``"off"``)
    pymunk, each in its own process."""
    out = {"N": n, "sizes": discs.SIZES[sizes], **fresh("engine", n, sizes, closed)}
    if peer != "off" and not closed:
        out.update(fresh("pymunk", n, sizes, closed, peer))
        out["ratio_cold"] = out["cold_s"] / out["pymunk_cold_s"]
        out["ratio_warm"] = out["warm_s"] / out["pymunk_warm_s"]
    return out


def markdown(rows: list[dict], closed: bool) -> str:
    """The rows as one markdown table; columns no row has are left out."""
    cols = [("density", "density", "{:.3f}") if c[1] == "mean_y" and closed else c for c in COLUMNS]
    cols = [c for c in cols if any(c[1] in r for r in rows)]
    lines = ["| " + " | ".join(c[0] for c in cols) + " |",
             "|" + "|".join("---" if c[1] == "sizes" else "---:" for c in cols) + "|"]
    for r in rows:
        lines.append("| " + " | ".join(f.format(r[k]) if k in r else "" for _, k, f in cols) + " |")
    return "\n".join(lines)


def size_list(text: str) -> list[str]:
    """``"equal,10x"`` -> ``["equal", "10x"]``, each one of ``discs.SIZES``."""
    kinds = [k.strip() for k in text.split(",")]
    bad = [k for k in kinds if k not in discs.SIZES]
    if bad:
        raise argparse.ArgumentTypeError(f"--sizes {text!r}: {bad[0]!r} is not one of "
                                         f"{', '.join(discs.SIZES)}")
    return kinds


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sizes_n", nargs="*", type=int, default=[200, 400, 800, 1000, 2000, 5000],
                    metavar="N", help="numbers of marks")
    ap.add_argument("--closed", action="store_true", help="closed boundary, no force: packing")
    which = ap.add_mutually_exclusive_group()
    which.add_argument("--sizes", type=size_list, default=list(discs.SIZES),
                       help=f"comma-separated, of {', '.join(discs.SIZES)} (default: all)")
    which.add_argument("--equal-only", action="store_true", help="the same as --sizes equal")
    ap.add_argument("--pymunk", choices=["lattice", "random", "off"], default="random",
                    help="pymunk's start: poured in at random (default), the engine's lattice, or no pymunk")
    ap.add_argument("--one", choices=["engine", "pymunk"], help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    kinds = ["equal"] if args.equal_only else args.sizes
    if args.one:   # a child: one layout (or pymunk run), one JSON line
        n, kind = args.sizes_n[0], kinds[0]
        out = engine(n, kind, args.closed) if args.one == "engine" else pymunk(n, kind, args.pymunk)
        print(json.dumps(out))
        return
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, python "
          f"{platform.python_version()}, OMP_WAIT_POLICY={os.environ.get('OMP_WAIT_POLICY')}, "
          f"engine from {_engine_path()}, pymunk start: {args.pymunk}", flush=True)
    rows = []
    for kind in kinds:
        for n in args.sizes_n:
            rows.append(row(n, kind, args.closed, args.pymunk))
            print(json.dumps({k: round(v, 4) if isinstance(v, float) else v
                              for k, v in rows[-1].items()}), flush=True)
    print()
    print(markdown(rows, args.closed))


def _engine_path() -> str:
    """Where a child process imports ``unitopia_widget`` from (found, not imported)."""
    import importlib.util
    return os.path.dirname(importlib.util.find_spec("unitopia_widget").origin)


if __name__ == "__main__":
    sys.exit(main())
