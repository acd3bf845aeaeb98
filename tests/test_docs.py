"""The README's pictures are current: ``docs/demo.png`` shows what the demo draws now."""
from __future__ import annotations

import importlib.util
from pathlib import Path

from PIL import Image

DOCS = Path(__file__).resolve().parents[1] / "docs"


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
