"""The documentation: the site builds offline with warnings as errors, every public name has a
reference page and docstrings, the guide's examples run, and ``docs/demo.png`` shows what the
demo draws now."""
from __future__ import annotations

import importlib.util
import inspect
import os
import re
import subprocess
import sys
import warnings
from pathlib import Path

import pytest
from PIL import Image

import unitopia_widget as uw

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def make_demo():
    spec = importlib.util.spec_from_file_location("make_demo", DOCS / "make_demo.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_demo_picture_shows_the_demo_as_it_is_now():
    """The fingerprint stored in docs/demo.png (design, data and background of the demo
    when the picture was made) is the demo's now: no layout needed to tell."""
    script = make_demo()
    stored = Image.open(DOCS / "demo.png").text.get(script.KEY)
    assert stored == script.fingerprint(script.demo_chart()), \
        "docs/demo.png no longer shows what the demo draws: run python docs/make_demo.py"


def test_the_fingerprint_changes_with_what_the_demo_draws():
    script = make_demo()
    chart = script.demo_chart()
    before = script.fingerprint(chart)
    chart.layer(0).set(mark="circle")
    assert script.fingerprint(chart) != before
    chart = script.demo_chart()
    chart.df = chart.df.assign(Duration=chart.df.Duration * 2)
    assert script.fingerprint(chart) != before


def test_every_public_name_has_a_reference_page_in_the_nav():
    nav = (ROOT / "mkdocs.yml").read_text()
    for name in uw.__all__:
        page = DOCS / "reference" / f"{name}.md"
        assert page.exists() and f"::: unitopia_widget.{name}\n" in page.read_text(), name
        assert f"reference/{name}.md" in nav, name


def undocumented(obj) -> list[str]:
    """The public methods and properties a class defines itself that have no docstring."""
    missing = []
    for key, value in vars(obj).items():
        if key.startswith("_"):
            continue
        if isinstance(value, property):
            doc = value.__doc__
        elif isinstance(value, (staticmethod, classmethod)) or inspect.isfunction(value):
            doc = getattr(value, "__func__", value).__doc__
        else:
            continue
        if not (doc or "").strip():
            missing.append(key)
    return missing


@pytest.mark.parametrize("name", uw.__all__)
def test_every_public_name_and_its_methods_have_docstrings(name):
    obj = getattr(uw, name)
    assert (inspect.getdoc(obj) or "").strip(), name
    assert not inspect.isclass(obj) or undocumented(obj) == []


def test_the_site_builds_offline_with_warnings_as_errors(tmp_path):
    """A broken link or anchor, a page left out of the nav or a name the reference cannot
    find fails the build (``strict`` and ``validation`` in mkdocs.yml)."""
    pytest.importorskip("mkdocstrings_handlers.python", reason="the docs extra builds the site")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q",
                           "-d", str(tmp_path / "site")], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    page = (tmp_path / "site" / "reference" / "Container" / "index.html").read_text()
    assert "unitopia_widget.Container.image" in page, "the reference shows the methods"


GUIDE = [page for page in sorted((DOCS / "guide").glob("*.md")) + [DOCS / "getting-started.md"]
         if "```python" in page.read_text()]


@pytest.mark.parametrize("page", GUIDE, ids=[p.stem for p in GUIDE])
def test_the_guide_examples_run_in_order(page, tmp_path, monkeypatch, one_thread):
    """Each page's Python blocks, in order, on at most 16 rows, starting from the ``df``
    and ``w`` the quick start leaves."""
    blocks = re.findall(r"```python\n(.*?)```", page.read_text(), re.S)
    real = uw.demo_data
    monkeypatch.setattr(uw, "demo_data", lambda n=120, seed=7: real(n=min(n, 16), seed=seed))
    monkeypatch.chdir(tmp_path)
    df = uw.demo_data()
    scope = {"uw": uw, "df": df, "w": uw.UnitoPia(df, mark="star", size="Duration", color="Task")}
    for block in blocks:
        exec(block, scope)


def test_the_demo_lays_out_without_a_warning():
    """The package's own demo asks for nothing its marks cannot do (issue 46)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        make_demo().demo_chart(iterations=20).layout()
