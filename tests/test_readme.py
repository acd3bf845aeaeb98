"""The README's quick start runs as written (on fewer rows and iterations, to stay quick)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import unitopia_widget as uw

README = Path(__file__).resolve().parents[1] / "README.md"


def section(title: str) -> str:
    text = README.read_text()
    start = text.index(f"\n## {title}\n")
    end = text.find("\n## ", start + 1)
    return text[start:end if end > 0 else None]


def test_quick_start_runs_with_the_shipped_data(tmp_path, monkeypatch):
    quick = section("Quick start").split("### Designs you can rebuild")[0]   # tested below
    blocks = re.findall(r"```python\n(.*?)```", quick, re.S)
    assert blocks and "uw.demo_data()" in blocks[0], "the quick start uses data the package ships"
    small = uw.demo_data(n=24)
    monkeypatch.setattr(uw, "demo_data", lambda: small)
    monkeypatch.chdir(tmp_path)
    scope: dict = {}
    exec(blocks[0], scope)
    scope["w"].layer(0).set(iterations=40)
    for block in blocks[1:]:
        exec(block, scope)
    assert scope["w"].status == "done"
    assert (tmp_path / "chart.svg").read_text().lstrip().startswith(("<svg", "<?xml"))


def test_install_commands_need_no_root_node_or_chromium():
    install = section("Install (a user: Python 3.10+, no root, no Node, no Chromium)")
    commands = re.findall(r"```bash\n(.*?)```", install, re.S)[0]
    assert "python -m venv .venv && . .venv/bin/activate" in commands
    assert "pip install -c constraints.txt -e ." in commands
    assert not re.search(r"\b(sudo|apt-get|npm|node|chromium|install\.sh)\b", commands)
    assert (Path(uw.__file__).parent / "static" / "widget.js").exists(), "the built front end ships"


@pytest.mark.parametrize("command", ["bash scripts/install.sh", "bash scripts/test.sh"])
def test_developers_set_up_has_its_own_section(command):
    assert command in section("Developing (a Debian machine with Node 20+; installs Chromium, needs root)")


def test_designs_you_can_rebuild_run_as_written(tmp_path, monkeypatch):
    """The save/load/to_code block and the design_path block, on a small laid-out widget."""
    text = section("Quick start")
    start = text.index("### Designs you can rebuild")
    blocks = re.findall(r"```python\n(.*?)```", text[start:text.find("\n### ", start + 1)], re.S)
    assert len(blocks) == 2 and "design_path=" in blocks[1]
    monkeypatch.chdir(tmp_path)
    df = uw.demo_data(n=12)
    scope = {"uw": uw, "df": df, "w": uw.UnitoPia(df, mark="star", size="Duration", color="Task")}
    for block in blocks:
        exec(block, scope)
    assert (tmp_path / "design.json").exists() and (tmp_path / "jar.unitopia.json").exists()
    assert uw.UnitoPia.load("jar.unitopia.json", df).design == scope["w"].design
