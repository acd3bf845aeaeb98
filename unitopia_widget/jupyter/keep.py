"""A widget's design kept beside its notebook, so a re-executed notebook keeps its sketch.

``default_path()`` is ``<notebook-stem>.unitopia.json`` in the notebook's folder: the
notebook is the kernel's session (``JPY_SESSION_NAME``, which Jupyter Server sets, or
the user namespace's ``__session__`` / VS Code's ``__vsc_ipynb_file__``); relative names
are taken in the kernel's working folder, which Jupyter starts in the notebook's own.
"""
from __future__ import annotations

import hashlib
import os
import pathlib
import warnings

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


class DesignFile:
    """The design file one widget keeps current, and the file as this widget last read or
    wrote it, so an edit made there by another writer (a second widget or kernel on the
    same file) is noticed rather than overwritten."""

    def __init__(self, path):
        self.path = pathlib.Path(path)
        self._stat = None     # (inode, mtime ns, size) when last read or written
        self._digest = None   # sha256 of the bytes then; None: not read or written yet

    def _state(self) -> tuple:
        """``(stat key, sha256)`` of the file now; ``(None, None)`` when it is missing. The
        bytes are hashed only when the stat key differs from the one last seen."""
        try:
            st = os.stat(self.path)
        except FileNotFoundError:
            return None, None
        key = (st.st_ino, st.st_mtime_ns, st.st_size)
        if key == self._stat:
            return key, self._digest
        return key, hashlib.sha256(self.path.read_bytes()).hexdigest()

    def seen(self) -> "DesignFile":
        """Take the file as it is now as read by this widget (after loading it)."""
        self._stat, self._digest = self._state()
        return self

    def changed(self) -> bool:
        """True when another writer changed the file since this widget last read or wrote
        it (a file that is gone again has nothing to lose)."""
        key, digest = self._state()
        if digest is not None and digest == self._digest:
            self._stat = key
        return digest is not None and digest != self._digest

    def write(self, design: dict) -> None:
        """Write ``design`` to the file (whole or not at all) and remember it."""
        data = write_json(self.path, design)
        self._digest = hashlib.sha256(data).hexdigest()
        self._stat = self._state()[0]

    def conflict(self) -> str:
        """Why the file was not written, and the two ways on."""
        return (f"design file {str(self.path)!r} changed since this widget last read or wrote "
                f"it (another widget or kernel keeps it current too), so this widget's design "
                f"was not written there; keep this widget's design in it with "
                f"w.save_design(force=True), or take the file's with "
                f"w = uw.UnitoPia.load({str(self.path)!r}, df)")


class KeptDesign:
    """``UnitoPia``'s design files: ``load``, ``from_design``, ``save_design``,
    ``design_path`` and ``to_code``; needs ``_chart`` and ``_design_file`` (a
    ``DesignFile`` or None)."""

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
        return None if self._design_file is None else self._design_file.path

    def save_design(self, path=None, force: bool = False) -> pathlib.Path:
        """Write the design to ``path`` (default: ``design_path``, else beside the notebook as
        ``<notebook-stem>.unitopia.json``) and keep that file current from now on
        (``design_path``); a re-executed ``w = uw.UnitoPia.load(path, df)`` then restores it.
        Returns the path. When another widget or kernel changed ``design_path`` since this
        widget last read or wrote it, edits are not written there (a warning says so) and
        this call raises RuntimeError; ``force=True`` overwrites the file with this
        widget's design."""
        kept = self._design_file
        target = (self.design_path or default_path()) if path is None else pathlib.Path(path)
        file = kept if kept is not None and kept.path == target else DesignFile(target)
        if file is kept and not force and file.changed():
            raise RuntimeError(file.conflict())
        file.write(self._chart.design())
        self._design_file = file
        return target

    def _keep_design(self) -> None:
        """Write the design to ``design_path`` after an edit, unless another writer changed
        the file meanwhile: then warn and leave the file as it is."""
        file = self._design_file
        if file is None:
            return
        if file.changed():
            warnings.warn(file.conflict(), RuntimeWarning, stacklevel=4)
            return
        file.write(self.design)

    @classmethod
    def from_design(cls, df: pd.DataFrame, design: dict, **kwargs) -> "UnitoPia":
        """A widget for ``df`` with ``design`` (a design JSON dict, as ``w.design``)."""
        kwargs.setdefault("canvas", design.get("canvas", (800, 500)))
        path = kwargs.pop("design_path", None)
        w = cls(df, **kwargs)
        w._chart.apply_design(design)
        w._design_file = None if path is None else DesignFile(path).seen()
        return w

    def to_code(self, df_name: str = "df") -> str:
        """Python source that rebuilds the current design, sketched containers and marks
        included (as their stroke lists and polygons), for the DataFrame named ``df_name``."""
        return design_code(self._chart.design(), "uw.UnitoPia", df_name, var="w")
