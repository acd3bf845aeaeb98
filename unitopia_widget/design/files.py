"""A design on disk and as code: read and check a design file, write one as Python source."""
from __future__ import annotations

import json
import os
import pprint

from .scene import check_design_header


def design_code(design: dict, factory: str, df_name: str = "df", var: str = "chart") -> str:
    """Python source that sets ``var = factory.from_design(df_name, design)`` with the
    design written out as a Python literal (plain lists, dicts, numbers and text)."""
    if not df_name.isidentifier():
        raise ValueError(f"df_name must be a Python identifier, got {df_name!r:.60}")
    plain = json.loads(json.dumps(design))   # numpy scalars and tuples as Python literals
    literal = pprint.pformat(plain, indent=1, width=96, sort_dicts=False)
    return (f"import unitopia_widget as uw\n\ndesign = {literal}\n"
            f"{var} = {factory}.from_design({df_name}, design)\n")


def naming(error: OSError, what: str) -> OSError:
    """``error`` again (same class and errno) with its message prefixed by ``what``, so it
    names the path the user gave, not a temporary file."""
    message = f"{what}: {error.strerror or error}"
    return type(error)(message) if error.errno is None else type(error)(error.errno, message)


def read_json(path, what: str = "design"):
    """The JSON value in the file at ``path``; a file that is not JSON raises ValueError
    naming it as the ``what`` file, one that cannot be read an OSError naming it."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as e:
        raise ValueError(f"{what} file {os.fspath(path)!r} is not valid JSON: {e}") from None
    except OSError as e:   # a folder, /proc/self/mem, a vanished disk: name the path given
        raise naming(e, f"cannot read the {what} file {os.fspath(path)!r}") from None


def load_design(path) -> dict:
    """Read and check a design file; a corrupt or too-new file raises ValueError."""
    d = read_json(path)
    check_design_header(d)
    return d
