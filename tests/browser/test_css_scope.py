"""A mark's CSS styles only the mark: an exported SVG beside page elements leaves theirs alone."""
from __future__ import annotations

import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.design.marks import Mark

pytestmark = pytest.mark.browser

CSS = ("@layer x { .jp-Cell { color: rgb(255, 0, 0) } } "
       "@container (min-width: 1px) { .jp-Cell { color: rgb(255, 0, 0) } } "
       "@scope (body) { .jp-Cell { color: rgb(255, 0, 0) } } "
       ".body { fill: #00ff00; & .jp-Cell { color: rgb(255, 0, 0) } } "
       ".jp-Cell { background-color: rgb(255, 0, 0) }")
ICON = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><style><![CDATA['
        + CSS + ']]></style><rect class="body" width="10" height="10"/></svg>')


def test_exported_svg_keeps_the_page_style(browser):
    chart = uw.Chart(pd.DataFrame({"v": [1.0, 2.0]}), mark=Mark.svg(ICON), iterations=20)
    chart.layout()
    page = browser.new_page()
    page.set_content('<div class="jp-Cell"><span class="jp-Cell">x</span></div>'
                     '<div style="container-type: inline-size">' + chart.to_svg() + '</div>')
    style = page.evaluate("""() => [...document.querySelectorAll('div > .jp-Cell, body > .jp-Cell')]
        .map(e => [getComputedStyle(e).color, getComputedStyle(e).backgroundColor])""")
    fill = page.evaluate("getComputedStyle(document.querySelector('svg rect[class$=\"-body\"]')).fill")
    page.close()
    assert style == [["rgb(0, 0, 0)", "rgba(0, 0, 0, 0)"]] * 2
    assert fill == "rgb(0, 255, 0)"
