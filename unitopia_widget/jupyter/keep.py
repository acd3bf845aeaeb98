"""A widget's design kept beside its notebook, so a re-executed notebook keeps its sketch.

``default_path()`` is ``<notebook-stem>.unitopia.json`` in the notebook's folder: the
notebook is the kernel's session (``JPY_SESSION_NAME``, which Jupyter Server sets, or
the user namespace's ``__session__`` / VS Code's ``__vsc_ipynb_file__``); relative names
are taken in the kernel's working folder, which Jupyter starts in the notebook's own.
"""
from __future__ import annotations

import json
import os
import pathlib

from ..output.files import atomic_write

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


def write(path, design: dict) -> pathlib.Path:
    """Write ``design`` to ``path`` whole (a crash never leaves half a file); returns it."""
    path = pathlib.Path(path)
    atomic_write(os.fspath(path), json.dumps(design, indent=1).encode())
    return path
