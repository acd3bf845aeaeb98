"""The package as a user installs it: the wheel (built through the sdist, so both are complete)
goes without ``-e`` into a fresh venv with the icons extra, at the lock's versions; then the
README's quick start and ``python -m unitopia_widget demo`` run there, outside the repository.

Nothing of this tree or of the test environment is importable in that venv, so a module, a
front-end file or a data file missing from the wheel fails here. uv installs from its cache
(hard links), so the venv costs seconds after the first run.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
uv = pytest.importorskip("uv", reason="the wheel test needs uv (the test extra)").find_uv_bin()


def pip_find_links() -> list[str]:
    """The local wheel folders pip is configured with (torch==2.13.0 is the CPU wheel there);
    uv reads no pip configuration."""
    out = subprocess.run([sys.executable, "-m", "pip", "config", "list"],
                         capture_output=True, text=True, check=True).stdout
    folders = {f for value in re.findall(r"find-links='(.*)'$", out, re.M) for f in value.split()}
    return sorted(f for f in folders if os.path.isdir(f))


def quick_start() -> str:
    """The README's quick start (up to its first subsection) as one script, on 24 rows and
    40 iterations."""
    text = (ROOT / "README.md").read_text()
    start = text.index("\n## Quick start\n")
    end = min(i for i in (text.find("\n## ", start + 1), text.find("\n### ", start)) if i > 0)
    blocks = re.findall(r"```python\n(.*?)```", text[start:end], re.S)
    return ("import unitopia_widget as uw\n"
            "small = uw.demo_data(n=24)\nuw.demo_data = lambda: small\n"
            + blocks[0] + "w.layer(0).set(iterations=40)\n" + "".join(blocks[1:])
            + "assert w.status == 'done', w.status\n")


CHECKS = """
import sys
from pathlib import Path
import unitopia_widget as uw
package = Path(uw.__file__).parent
assert Path(sys.prefix) in package.parents, package
assert (package / "static" / "widget.js").exists(), "the built front end is in the wheel"
assert uw.Mark.icon("fa:apple-whole") is not None, "the icons extra"
print(package)
"""


@pytest.fixture(scope="module")
def venv(tmp_path_factory):
    """A fresh venv with the wheel and its icons extra installed from the lock."""
    tmp = tmp_path_factory.mktemp("wheel")
    subprocess.run([uv, "build", "-q", "--out-dir", str(tmp / "dist"), str(ROOT)], check=True)
    wheel, = (tmp / "dist").glob("unitopia_widget-*.whl")
    subprocess.run([uv, "venv", "-q", "--python", sys.executable, str(tmp / "venv")], check=True)
    python = tmp / "venv" / "bin" / "python"
    links = [arg for folder in pip_find_links() for arg in ("--find-links", folder)]
    subprocess.run([uv, "pip", "install", "-q", "--python", str(python), "-c",
                    str(ROOT / "constraints.txt"), *links, f"{wheel}[icons]"], check=True)
    return python


def run_outside(python: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    return subprocess.run([str(python), *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=600)


def test_the_wheel_holds_the_front_end_and_takes_the_icons_extra(venv, tmp_path):
    done = run_outside(venv, "-c", CHECKS, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "site-packages" in done.stdout


def test_the_readme_quick_start_runs_from_the_installed_wheel(venv, tmp_path):
    done = run_outside(venv, "-c", quick_start(), cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "chart.svg").read_text().lstrip().startswith(("<svg", "<?xml"))


def test_the_demo_command_runs_from_the_installed_wheel(venv, tmp_path):
    done = run_outside(venv, "-m", "unitopia_widget", "demo", "-o", "demo.svg", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("wrote demo.svg: 120 marks")
    assert (tmp_path / "demo.svg").stat().st_size > 0
