"""A laid-out chart copied for one test to change, so that tests share one layout."""
from unitopia_widget.chart import Chart


def laid_copy(base: Chart) -> Chart:
    """A chart of ``base``'s design and rows holding its last run (layout, units, snapshot,
    origin and inputs): runs on the copy start warm from it, and ``base`` stays as it was
    (each run replaces these fields, never changes them in place)."""
    other = Chart.from_design(base.df, base.design())
    for name in ("laid", "_units", "_snapshot", "_origin", "_ran"):
        setattr(other, name, getattr(base, name))
    return other
