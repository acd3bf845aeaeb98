"""Command line: ``python -m unitopia_widget demo -o demo.svg``.

``demo`` lays out the built-in example (stars settling in a jar, sized by a
small made-up dataset of task durations) and writes it as SVG, PNG or design
JSON, with a progress bar on stderr.
"""
from __future__ import annotations

import argparse
import sys
import time

from .demo import demo_chart


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
    args = parser.parse_args(argv)
    chart = demo_chart(seed=args.seed)
    chart.layout(on_progress=_bar(sys.stderr))
    sys.stderr.write("\n")
    chart.save(args.output)
    r = chart.result
    print(f"wrote {args.output}: {len(chart.placements)} marks, {r.iterations} iterations, "
          f"{r.seconds:.1f} s, overlap {100 * r.stats['overlap']:.2f}%")
    return 0


if __name__ == "__main__":
    sys.exit(main())
