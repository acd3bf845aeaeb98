"""The README's commands work as written (the quick start on fewer rows and iterations, to
stay quick), its set-up words match the scripts, and it stays one screen or two."""
from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

import unitopia_widget as uw

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"


def section(title: str, path: Path = README, level: str = "##") -> str:
    text = path.read_text()
    start = text.index(f"\n{level} {title}\n")
    end = text.find(f"\n{level} ", start + 1)
    return text[start:end if end > 0 else None]


def test_quick_start_runs_with_the_shipped_data(tmp_path, monkeypatch):
    blocks = re.findall(r"```python\n(.*?)```", section("Quick start"), re.S)
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


def test_the_pile_chart_runs_on_the_penguins(tmp_path, monkeypatch, one_thread):
    blocks = re.findall(r"```python\n(.*?)```", section("Piles by category"), re.S)
    assert "load_penguins()" in blocks[0] and "by=\"species\"" in blocks[0]
    monkeypatch.chdir(tmp_path)
    scope: dict = {"uw": uw}
    with pytest.warns(UserWarning, match="dropna=True"):
        exec(blocks[0], scope)
    w = scope["w"]
    assert w.piles == "columns" and [layer.name for layer in w.layers] == ["Adelie", "Chinstrap", "Gentoo"]
    assert w.to_svg().count('class="pile-label"') == 3
    assert (tmp_path / "penguins.png").read_bytes()[:4] == b"\x89PNG"
    assert (ROOT / "docs" / "piles.png").exists(), "the picture the README shows"


@pytest.mark.parametrize("path", [README, DOCS / "getting-started.md"], ids=["README", "docs"])
def test_install_commands_need_no_root_node_or_chromium(path):
    commands = re.findall(r"```bash\n(.*?)```", section("Install", path), re.S)[0]
    assert "python -m venv .venv && . .venv/bin/activate" in commands
    assert 'pip install -c constraints.txt -e ".[icons]"' in commands
    assert not re.search(r"\b(sudo|apt-get|npm|node|chromium|install\.sh)\b", commands)
    assert (Path(uw.__file__).parent / "static" / "widget.js").exists(), "the built front end ships"


@pytest.mark.parametrize("path", [README, DOCS / "getting-started.md"], ids=["README", "docs"])
def test_install_names_every_extra_there_is(path):
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    install = section("Install", path)
    assert {name for name in extras if f"`{name}`" in install} == set(extras)
    assert "constraints.txt" in install and "newest" in install, "what the constraints file is for"


@pytest.mark.parametrize("command", ["bash scripts/install.sh", "bash scripts/test.sh",
                                     "bash scripts/test.sh --quick", "bash scripts/test-latest.sh",
                                     "bash scripts/lock.sh --upgrade"])
def test_developers_set_up_has_its_own_section(command):
    assert command in section("Developing (a Debian machine with Node 20+; installs Chromium, needs root)")
    assert (ROOT / command.split()[1]).exists()


def test_the_developing_section_says_what_install_sh_installs():
    pip_line = re.search(r"^python -m pip install .*$", (ROOT / "scripts/install.sh").read_text(), re.M)
    command = pip_line.group(0).replace(" -q", "")
    assert command in section("Developing (a Debian machine with Node 20+; installs Chromium, needs root)")


def test_the_readme_fits_on_a_screen_or_two_and_its_links_lead_somewhere():
    text = README.read_text()
    assert len(text.splitlines()) <= 150
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", text)
    local = [link for link in links if "://" not in link]
    assert len(local) >= 10, "the README links into the docs"
    assert [link for link in local if not (ROOT / link).exists()] == []


def test_designs_you_can_rebuild_run_as_written(tmp_path, monkeypatch):
    """The save/load/to_code block and the design_path block, on a small laid-out widget."""
    text = section("Designs you can rebuild", DOCS / "guide" / "stories-and-exports.md")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 2 and "design_path=" in blocks[1]
    monkeypatch.chdir(tmp_path)
    df = uw.demo_data(n=12)
    scope = {"uw": uw, "df": df, "w": uw.UnitoPia(df, mark="star", size="Duration", color="Task")}
    for block in blocks:
        exec(block, scope)
    assert (tmp_path / "design.json").exists() and (tmp_path / "jar.unitopia.json").exists()
    assert uw.UnitoPia.load("jar.unitopia.json", df).design == scope["w"].design


def test_the_axis_chart_runs_on_the_real_table(tmp_path, monkeypatch):
    pytest.importorskip("vega_datasets")
    block = re.findall(r"```python\n(.*?)```", section("Axes beside the marks"), re.S)[0]
    assert "data.cars()" in block and "axes=True" in block
    monkeypatch.chdir(tmp_path)
    scope = {"uw": uw}
    code = block.replace("w.run(wait=True)", "w.layer(0).set(iterations=40)\nw.run(wait=True)")
    with pytest.warns(UserWarning, match="dropna=True: dropped 6 of 406 rows"):
        exec(code, scope)
    assert scope["w"].status == "done" and (tmp_path / "cars.png").stat().st_size > 10_000
    assert scope["w"].to_svg(axes=True).count('<g class="axis"') == 2
