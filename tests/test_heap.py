"""The host heap through a layout (``layout/heap.py``): freed scratch blocks are reused, not
faulted in afresh each iteration, and handed back to the system when the layout ends."""
from __future__ import annotations

import contextlib
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.layout import engine
from unitopia_widget.layout.step import heap

pytestmark = pytest.mark.skipif(heap._LIBC is None, reason="the heap is tuned on glibc only")

# Iterations that each make and free 42 MiB in blocks of 12 and 3 MiB, as a solve makes
# its slabs and samples: the page faults of the iterations after the first, and the resident
# memory inside ``held()`` and after it. The module is loaded from its file, in a fresh
# process whose glibc has not been tuned.
PROBE = """
import importlib.util, resource, sys
import numpy as np
spec = importlib.util.spec_from_file_location("heap", sys.argv[1])
heap = importlib.util.module_from_spec(spec)
spec.loader.exec_module(heap)

def resident():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()

def faults():
    counts = []
    for _ in range(8):
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        blocks = [np.ones(mib << 18, np.float32) for mib in (12, 3, 12, 3, 12)]
        del blocks
        counts.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
    return sum(counts[1:])

if sys.argv[2] == "held":
    with heap.held():
        n, inside = faults(), resident()
    print(n, inside, resident())
else:
    print(faults(), 0, resident())
"""


def probe(mode: str) -> list[int]:
    out = subprocess.run([sys.executable, "-c", PROBE, heap.__file__, mode],
                         capture_output=True, text=True, check=True).stdout
    return [int(v) for v in out.split()]


def test_held_reuses_freed_blocks_and_hands_them_back_after():
    plain, _, _ = probe("plain")
    faults, inside, after = probe("held")
    assert plain > 1000                   # glibc alone faults blocks in afresh every iteration
    assert faults * 20 < plain            # held: the first iteration's blocks are reused
    assert inside - after > 30 << 20      # and go back to the system when the layout ends


def test_a_layout_runs_inside_held(monkeypatch):
    seen = []

    @contextlib.contextmanager
    def recording():
        seen.append("enter")
        yield
        seen.append("exit")

    monkeypatch.setattr(engine, "held", recording)
    df = pd.DataFrame({"v": np.linspace(1.0, 2.0, 12)})
    chart = uw.Chart(df, mark="circle", size="v", canvas=(200, 150), seed=0, iterations=20,
                     container=uw.Container.ellipse(100, 75, 90, 65), boundary="closed")
    chart.layout(on_progress=lambda *a, **k: seen.append("step"))
    assert seen[0] == "enter" and seen[-1] == "exit" and "step" in seen[1:-1]
