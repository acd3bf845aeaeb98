"""resvg's renders of mark silhouettes, kept on disk across processes.

A layout renders each vector mark's silhouette a few times (its fill fraction, its ink
share, its sprite pyramid); a process keeps them in memory (``Mark.silhouette``), but every
new process (a fresh kernel, a script, a benchmark) started the resvg worker and rendered
them again: 0.2 s of a 1,000-mark layout's 1.8 s. Here the PNG bytes resvg returned are
kept in a cache folder, named by the SHA-256 of the SVG text, the style sheet, the resvg
version and ``FORMAT``, so a kept render is byte for byte the one resvg would return.

The folder: ``$UNITOPIA_CACHE_DIR`` when set (set empty: nothing is kept), else
``$XDG_CACHE_HOME/unitopia-widget/renders`` or ``~/.cache/unitopia-widget/renders``. A
render that cannot be read or written (a read-only home, a file being replaced) is simply
rendered again; files are written whole (a temporary file, then renamed).
"""
from __future__ import annotations

import functools
import hashlib
import importlib.metadata
import os
import tempfile
from pathlib import Path

FORMAT = 1   # raise when what is kept, or how it is named, changes


def directory() -> Path | None:
    """The cache folder, or None when ``$UNITOPIA_CACHE_DIR`` is set empty."""
    chosen = os.environ.get("UNITOPIA_CACHE_DIR")
    if chosen is not None:
        return Path(chosen) if chosen else None
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "unitopia-widget" / "renders"


@functools.lru_cache(maxsize=1)
def _resvg() -> str:
    return importlib.metadata.version("resvg-py")


def name(svg: str, style_sheet: str | None) -> str:
    """The file name of a render of ``svg`` with ``style_sheet``."""
    text = "\0".join([str(FORMAT), _resvg(), style_sheet or "", svg])
    return hashlib.sha256(text.encode()).hexdigest() + ".png"


def load(file: str) -> bytes | None:
    """The kept render ``file`` (``name``'s), or None."""
    folder = directory()
    if folder is None:
        return None
    try:
        return (folder / file).read_bytes()
    except OSError:
        return None


def store(file: str, png: bytes) -> None:
    """Keep ``png`` as ``file`` (``name``'s), where the folder can be written."""
    folder = directory()
    if folder is None:
        return
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder, suffix=".part", delete=False) as out:
            out.write(png)
        os.replace(out.name, folder / file)
    except OSError:
        return
