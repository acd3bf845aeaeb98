"""unitopia-widget: pictorial unit visualization in Jupyter.

Every row of a DataFrame becomes a mark; marks are packed into containers,
placed by emitters and pulled by forces, by a differentiable rasterizer
(the contain-and-fill model of UnitoPia).
"""
import os
import sys

# PyTorch's OpenMP threads wait for the next parallel op actively for a while, then sleep.
# A notebook kernel (Jupyter, marimo) shares its cores with the browser and runs layouts
# beside the threads that answer it: there idle threads sleep at once (a passive policy;
# JupyterLab, 1,000 marks: a run of 2.5 s took 6.2 s with threads that wait actively). A
# script's layout gains from the wait, its ops a fraction of a millisecond apart (Table 1,
# 1,000 discs, two threads: 0.42 -> 0.29 s): threads spin about 4 ms after the last op
# (libgomp's default is twice that), then sleep. Must precede torch's import; a policy the
# user set is kept.
if "OMP_WAIT_POLICY" not in os.environ:
    if {"ipykernel", "marimo"} & set(sys.modules):
        os.environ["OMP_WAIT_POLICY"] = "PASSIVE"
    else:
        os.environ.setdefault("GOMP_SPINCOUNT", "100000")

from .chart import Chart  # noqa: E402
from .design.containers import Container  # noqa: E402
from .design.emitters import CurveEmitter, GridEmitter  # noqa: E402
from .design.forces import DirectionalForce, PointForce  # noqa: E402
from .design.marks import Mark  # noqa: E402
from .design.scene import Layer  # noqa: E402
from .demo import demo_data  # noqa: E402
from .story import Story  # noqa: E402

__all__ = ["Chart", "Container", "CurveEmitter", "DirectionalForce", "GridEmitter", "Layer",
           "Mark", "PointForce", "Story", "UnitoPia", "demo_data"]
__version__ = "0.1.0"


def __getattr__(name):
    # the widget pulls in anywidget and ipywidgets: import it on first use only
    if name == "UnitoPia":
        from .jupyter.widget import UnitoPia
        return UnitoPia
    raise AttributeError(f"module 'unitopia_widget' has no attribute {name!r}")
