"""Tests for unitopia_widget.output.html: the one-file page renders in Chromium with the
network off, shows every unit with its tooltip, replays the settling, and runs no
script from user content."""
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.design.scene import Mark

DATA = Path(__file__).parent / "data" / "marks"
HOSTILE = '<img src=x onerror="alert(1)"></script><script>alert(2)</script>'

pytestmark = pytest.mark.usefixtures("one_thread")


@pytest.fixture(scope="module")
def page_file(tmp_path_factory):
    rng = np.random.default_rng(1)
    df = pd.DataFrame({"v": rng.uniform(1, 4, 12), "g": ["a", "b", HOSTILE] * 4},
                      index=[f"r{i}" for i in range(11)] + [HOSTILE])
    chart = uw.Chart(df, mark=Mark.svg((DATA / "hostile.svg").read_text()), size="v", color="g",
                     rotate=True, iterations=30, canvas=(300, 200), title="Hostile <b>title</b>")
    chart.layout()
    path = tmp_path_factory.mktemp("html") / "chart.html"
    chart.save(path)
    return path, chart


@pytest.mark.browser
def test_page_renders_offline_with_tooltips_and_replays(browser, page_file):
    path, chart = page_file
    context = browser.new_context(offline=True)
    page = context.new_page()
    requests, dialogs = [], []
    page.on("request", lambda r: requests.append(r.url))
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    page.goto(path.as_uri())
    page.wait_for_selector("#chart svg g.unit")
    titles = page.eval_on_selector_all("#chart g.unit", "gs => gs.map(g => g.querySelector('title')"
                                                        ".textContent)")
    assert len(titles) == len(chart.placements) and all(t.strip() for t in titles)
    assert any("onerror" in t for t in titles)          # the hostile text is shown as text
    assert page.eval_on_selector_all("#chart g.unit", "gs => gs.every(g => g.getBBox().width > 0)")
    assert page.locator("#chart text.title").text_content() == "Hostile <b>title</b>"
    final = page.eval_on_selector_all("#chart g.unit", "gs => gs.map(g => g.getAttribute('transform'))")
    page.fill("#scrub", "0")
    page.dispatch_event("#scrub", "input")
    start = page.eval_on_selector_all("#chart g.unit", "gs => gs.map(g => g.getAttribute('transform'))")
    assert start != final
    page.click("#play")
    for _ in range(100):   # the page's policy forbids eval, so poll from here
        page.wait_for_timeout(100)
        if page.text_content("#play") == "Play":
            break
    end = page.eval_on_selector_all("#chart g.unit", "gs => gs.map(g => g.getAttribute('transform'))")
    assert end != start and page.input_value("#scrub") == page.get_attribute("#scrub", "max")
    assert page.evaluate("document.scripts.length") == 2   # the page's data and its own script
    assert not dialogs and requests == [path.as_uri()]
    context.close()


def test_page_holds_no_user_markup_outside_the_svg_data(page_file):
    text = page_file[0].read_text()
    head, data = text.split('id="chart-data">')
    assert "onerror" not in head and "<script>alert" not in data and "</script><script>alert" not in text
