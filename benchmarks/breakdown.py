"""Where a layout's time goes: the first layout in a fresh process, phase by phase, and
an iteration, part by part. The Table 1 set-up (``discs.py``), one process per run.

    python benchmarks/breakdown.py                 # 200, 1,000 and 5,000 equal circles
    python benchmarks/breakdown.py 1000 --sizes 10x

Cold start: the imports (torch, then the package), binding (data to units),
building the problem (raster fields, starting positions, sprite pyramids)
and solving, measured in order in one fresh process. An iteration: the
solver's own functions under ``cProfile`` in a second layout of the same
process (cumulative seconds per call site, divided by the iterations):
rendering the samples, the loss forward, the backward pass, the Adam step,
keeping marks on the canvas, planning patch groups, reading the sums back,
and the rest of the loop (the controller, forces, Python).
"""
from __future__ import annotations

import argparse
import cProfile
import json
import pstats
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import discs  # noqa: E402

PARTS = {   # (file suffix, function) -> label
    ("raster.py", "render_samples"): "render samples",
    ("losses.py", "forward"): "loss forward",
    ("~", "<method 'run_backward' of 'torch._C._EngineBase' objects>"): "backward",
    ("optim.py", "step"): "Adam step",
    ("placement.py", "project"): "keep on canvas",
    ("raster.py", "plan_for"): "plan patch groups",
    ("transfer.py", "push"): "read sums back",
}


def child(n: int, sizes: str) -> dict:
    """One fresh process: cold phases, then the parts of an iteration."""
    t = {"start": time.perf_counter()}
    import torch  # noqa: F401
    t["torch"] = time.perf_counter()
    import unitopia_widget as uw
    from unitopia_widget.layout import engine
    from unitopia_widget.layout.prepare.bind import bind
    t["package"] = time.perf_counter()
    df = pd.DataFrame({"value": discs.values(n, sizes)})
    chart = _chart(uw, df)
    units = bind(df, chart.layers)
    t["bind"] = time.perf_counter()
    problem = engine.build_problem(units, chart.layers, chart.canvas, 0, "cpu")
    t["build"] = time.perf_counter()
    result = engine.solve(problem)
    t["solve"] = time.perf_counter()
    cold = {"import torch": t["torch"] - t["start"], "import package": t["package"] - t["torch"],
            "bind": t["bind"] - t["package"], "build problem": t["build"] - t["bind"],
            "solve": t["solve"] - t["build"], "iterations": result.iterations}
    profiler = cProfile.Profile()
    problem = engine.build_problem(bind(df, chart.layers), chart.layers, chart.canvas, 0, "cpu")
    profiler.enable()
    again = engine.solve(problem)
    profiler.disable()
    stats = pstats.Stats(profiler).stats
    parts, total = {}, 0.0
    for (path, _, name), (_, _, _, cumulative, _) in stats.items():
        for (suffix, function), label in PARTS.items():
            if name == function and path.endswith(suffix):
                parts[label] = parts.get(label, 0.0) + cumulative
        if name == "solve" and path.endswith("solver.py"):
            total = cumulative
    parts["rest of the loop"] = total - sum(parts.values())
    ms = {k: 1000 * v / again.iterations for k, v in parts.items()}
    return {"cold": cold, "ms_per_iteration": ms, "iteration_ms": 1000 * total / again.iterations}


def _chart(uw, df):
    return uw.Chart(df, mark="circle", size="value", canvas=(discs.W, discs.H), seed=0,
                    container=uw.Container.ellipse(discs.CX, discs.CY, discs.R, discs.R),
                    forces=[uw.PointForce(discs.FX, discs.FY)], boundary="open",
                    fill=discs.FILL, iterations=1000)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sizes_n", nargs="*", type=int, default=[200, 1000, 5000], metavar="N")
    ap.add_argument("--sizes", default="equal", choices=list(discs.SIZES))
    ap.add_argument("--one", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.one:
        print(json.dumps(child(args.sizes_n[0], args.sizes)))
        return
    rows = []
    for n in args.sizes_n:
        out = subprocess.run([sys.executable, __file__, str(n), "--sizes", args.sizes, "--one"],
                             capture_output=True, text=True, check=True)
        got = json.loads(out.stdout.strip().splitlines()[-1])
        rows.append({"N": n, **{f"{k} s": v for k, v in got["cold"].items() if k != "iterations"},
                     "iterations": got["cold"]["iterations"], "ms/iter": got["iteration_ms"],
                     **{f"{k} ms": v for k, v in got["ms_per_iteration"].items()}})
    print("| | " + " | ".join(f"N = {r['N']:,}" for r in rows) + " |")
    print("|---|" + "---:|" * len(rows))
    for key in [k for k in rows[0] if k != "N"]:
        print(f"| {key} | " + " | ".join(f"{r.get(key, 0):.3g}" for r in rows) + " |")


if __name__ == "__main__":
    main()
