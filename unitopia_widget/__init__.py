"""unitopia-widget: pictorial unit visualization in Jupyter.

Every row of a DataFrame becomes a mark; marks are packed into containers,
placed by emitters and pulled by forces, by a differentiable rasterizer
(the contain-and-fill model of UnitoPia).
"""
import os

# PyTorch's OpenMP threads busy-wait by default; a notebook kernel shares its
# cores with the browser, so let idle threads sleep (must precede torch's import).
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

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
