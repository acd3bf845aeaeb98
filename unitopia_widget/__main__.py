"""Command line: ``python -m unitopia_widget demo -o demo.svg``.

``demo`` lays out the built-in example (stars settling in a jar, sized by a
small made-up dataset of task durations) and writes it as SVG, PNG or design
JSON, with a progress bar on stderr. ``explain design.json --data rows.csv`` lays
out a saved design on its data and prints which phases and rules of the solver's
schedule apply to it, with the iterations each acted on, and which rules do not apply.
"""
from __future__ import annotations

import argparse
import sys
import time

import pandas as pd

from .chart import Chart
from .design.files import load_design
from .demo import demo_chart
from .layout.rules import PHASES, SCHEDULE


def _bar(stream):
    started = time.monotonic()
    shown = [0.0]

    def show(iteration, loss, stats):
        now = time.monotonic()
        if now - shown[0] < 0.1:
            return
        shown[0] = now
        width = 30
        done = min(iteration / 600, 1.0)
        stream.write(f"\r[{'#' * int(done * width):<{width}}] iteration {iteration:4d}  "
                     f"overlap {100 * stats.get('overlap', 0):.2f}%  "
                     f"{time.monotonic() - started:5.1f}s")
        stream.flush()
    return show


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m unitopia_widget",
                                     description="unitopia-widget command line")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="render the built-in example (stars in a jar)")
    demo.add_argument("-o", "--output", default="demo.svg", help="output .svg, .png or .json")
    demo.add_argument("--seed", type=int, default=0)
    explain = sub.add_parser("explain", help="lay out a design and print the schedule it ran")
    explain.add_argument("design", help="a design .json (saved by chart.save)")
    explain.add_argument("--data", required=True, help="the chart's rows, a .csv with a header")
    args = parser.parse_args(argv)
    if args.command == "explain":
        return _explain(args.design, args.data)
    chart = demo_chart(seed=args.seed)
    chart.layout(on_progress=_bar(sys.stderr))
    sys.stderr.write("\n")
    chart.save(args.output)
    r = chart.result
    print(f"wrote {args.output}: {len(chart.placements)} marks, {r.iterations} iterations, "
          f"{r.seconds:.1f} s, overlap {100 * r.stats['overlap']:.2f}%")
    return 0


def _explain(design_path: str, data_path: str) -> int:
    """Lay out the design at ``design_path`` on the rows of ``data_path``; print the
    schedule: each phase's iterations, then those of each rule that applies to the layout
    (0: it never acted), then the rules that do not apply."""
    design = load_design(design_path)
    chart = Chart(pd.read_csv(data_path), canvas=design.get("canvas", (800, 500)))
    chart.apply_design(design)
    chart.layout()
    r = chart.result
    print(f"{design_path}: {len(chart.placements)} marks, {r.iterations} iterations, "
          f"{r.seconds:.1f} s, overlap {100 * r.stats['overlap']:.2f}%")
    for phase in PHASES:
        if phase not in r.phases:
            continue
        print(f"{phase:<14}{r.phases[phase]:6d}")
        for rule in SCHEDULE:
            if rule.phase == phase and rule.name in r.rules:
                every = "  (every patience window)" if rule.window else ""
                print(f"  {rule.name:<12}{r.phases.get(f'{phase}.{rule.name}', 0):6d}{every}")
    idle = [rule.name for rule in SCHEDULE if rule.name not in r.rules]
    if idle:
        print(f"not applying: {', '.join(idle)}")
    return 0

if __name__ == "__main__":
    sys.exit(main())
