"""A widget's design kept beside its notebook, so a re-executed notebook keeps its sketch.

``default_path()`` is ``<notebook-stem>.unitopia.json`` in the notebook's folder: the
notebook is the kernel's session (``JPY_SESSION_NAME``, which Jupyter Server sets, or
the user namespace's ``__session__`` / VS Code's ``__vsc_ipynb_file__``); relative names
are taken in the kernel's working folder, which Jupyter starts in the notebook's own.
"""
from __future__ import annotations

import os
import pathlib

import pandas as pd

from ..design.files import design_code, load_design
from ..output.files import write_json

SUFFIX = ".unitopia.json"
FALLBACK = "design"   # the stem when no notebook is known (a script, a plain IPython)


def notebook_path() -> pathlib.Path | None:
    """The running notebook's path, or None outside a notebook."""
    names = [os.environ.get("JPY_SESSION_NAME")]
    try:
        from IPython import get_ipython
        shell = get_ipython()
    except ImportError:
        shell = None
    if shell is not None:
        names += [shell.user_ns.get("__vsc_ipynb_file__"), shell.user_ns.get("__session__")]
    for name in names:
        if isinstance(name, str) and name.endswith(".ipynb"):
            path = pathlib.Path(name)
            return path if path.is_absolute() and path.parent.is_dir() else \
                pathlib.Path.cwd() / path.name
    return None


def default_path() -> pathlib.Path:
    """``<notebook-stem>.unitopia.json`` beside the notebook (``design.unitopia.json`` in
    the working folder outside one)."""
    notebook = notebook_path()
    if notebook is None:
        return pathlib.Path.cwd() / (FALLBACK + SUFFIX)
    return notebook.with_name(notebook.name[:-len(".ipynb")] + SUFFIX)


class KeptDesign:
    """``UnitoPia``'s design files: ``load``, ``from_design``, ``save_design``,
    ``design_path`` and ``to_code``; needs ``_chart`` and ``_design_path``."""

    @classmethod
    def load(cls, path, df: pd.DataFrame, **kwargs) -> "UnitoPia":
        """A widget for ``df`` with the design saved at ``path``; edits are written back to
        ``path`` (``design_path``; pass ``design_path=None`` to keep the file as it is), so
        a re-executed ``w = UnitoPia.load(path, df)`` restores what was sketched."""
        kwargs.setdefault("design_path", path)
        return cls.from_design(df, load_design(path), **kwargs)

    @property
    def design_path(self):
        """The design file every edit is written to (``pathlib.Path``), or None."""
        return self._design_path

    def save_design(self, path=None) -> pathlib.Path:
        """Write the design beside the notebook (default ``<notebook-stem>.unitopia.json``) or
        to ``path``, and keep that file current from now on (``design_path``); a re-executed
        ``w = uw.UnitoPia.load(path, df)`` then restores it. Returns the path."""
        self._design_path = default_path() if path is None else pathlib.Path(path)
        write_json(self._design_path, self._chart.design())
        return self._design_path

    @classmethod
    def from_design(cls, df: pd.DataFrame, design: dict, **kwargs) -> "UnitoPia":
        """A widget for ``df`` with ``design`` (a design JSON dict, as ``w.design``)."""
        kwargs.setdefault("canvas", design.get("canvas", (800, 500)))
        path = kwargs.pop("design_path", None)
        w = cls(df, **kwargs)
        w._chart.apply_design(design)
        w._design_path = None if path is None else pathlib.Path(path)
        return w

    def to_code(self, df_name: str = "df") -> str:
        """Python source that rebuilds the current design, sketched containers and marks
        included (as their stroke lists and polygons), for the DataFrame named ``df_name``."""
        return design_code(self._chart.design(), "uw.UnitoPia", df_name, var="w")
