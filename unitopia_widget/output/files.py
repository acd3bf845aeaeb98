"""Files written whole or not at all: every export and design save goes through here."""
from __future__ import annotations

import json
import os
import tempfile

from ..design.files import naming


def atomic_write(path: str, data: bytes) -> None:
    """Write a temporary file beside ``path``, then rename it over ``path``.

    A symbolic link at ``path`` keeps its link: the file it points to is the one
    replaced. The file gets the permissions a plain ``open(path, "w")`` would (0666
    less the umask), not mkstemp's private 0600. An OSError (a missing folder, a
    read-only disk) names ``path``, not the temporary file."""
    try:
        _replace(os.path.realpath(path) if os.path.islink(path) else path, data)
    except OSError as e:
        raise naming(e, f"cannot write {os.fspath(path)!r}") from None


def _replace(path: str, data: bytes) -> None:
    folder = os.path.dirname(path)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".unitopia-", suffix=".tmp")
    umask = os.umask(0)
    os.umask(umask)
    os.fchmod(fd, 0o666 & ~umask)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_json(path, value) -> bytes:
    """Write ``value`` (a design, a story) to ``path`` as indented JSON, whole or not at all;
    returns the bytes written."""
    data = json.dumps(value, indent=1).encode()
    atomic_write(os.fspath(path), data)
    return data
