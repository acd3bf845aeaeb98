"""Browser tests of the widget as a place to work: the stage takes the cell's width,
panels fold, the live legend is legible, title and caption show live; text keeps WCAG AA
contrast under a light and a JupyterLab Dark theme; the editing guides hide over
finished marks unless an editing tool is active or the Guides toggle is on."""

from __future__ import annotations

import re

import pytest
from test_frontend import ROOT, STAGE, click, drag, mount, next_paint, push_layout, tool
from test_legend_status import LEGEND, push_legend

from unitopia_widget.output.legend import FONT
from unitopia_widget.output.legend_draw import TEXT

pytestmark = pytest.mark.browser

# JupyterLab Dark's values of the variables the widget reads (theme-dark-extension).
JUPYTERLAB_DARK = {
    "--jp-ui-font-color1": "rgba(255, 255, 255, 0.87)",
    "--jp-ui-font-color2": "rgba(255, 255, 255, 0.54)",
    "--jp-layout-color1": "#111111",
    "--jp-layout-color2": "#212121",
    "--jp-border-color1": "#616161",
    "--jp-brand-color1": "#1976d2",
}


@pytest.mark.parametrize("width", [1400, 900])
def test_the_stage_takes_the_cell_width_and_the_legend_stays_legible(page, width):
    page.set_viewport_size({"width": width, "height": 1000})
    mount(page, design={**page.evaluate("unitopia.defaultState().design"), "title": "Tasks", "caption": "by duration"})
    push_legend(page, 120, 80)
    page.locator(LEGEND).wait_for(state="visible")
    next_paint(page)
    out = page.locator(ROOT).bounding_box()
    stage = page.locator(STAGE).bounding_box()
    assert stage["width"] >= 0.6 * out["width"], f"stage {stage['width']:.0f} px of {out['width']:.0f}"
    assert stage["height"] == pytest.approx(stage["width"] * 500 / 800, abs=1.5), "keeps the canvas's aspect ratio"
    legend = page.locator(LEGEND).bounding_box()
    assert legend["width"] * FONT / 120 >= 11, "legend text of at least 11 px"
    assert page.locator('[data-role="title"]').inner_text() == "Tasks"
    assert page.locator('[data-role="caption"]').inner_text() == "by duration"
    page.evaluate("fake.push('design', {...fake.get('design'), title: 'Hours'})")
    assert page.locator('[data-role="title"]').inner_text() == "Hours", "the title follows the design live"


def test_panels_fold_and_hide(page):
    mount(page)
    layers = page.locator(".ut-layers")
    assert page.locator(".ut-layer-list").is_visible()
    layers.locator('[data-action="fold"]').click()
    assert page.locator(".ut-layer-list").is_hidden() and layers.locator("h3").is_visible()
    assert layers.locator('[data-action="fold"]').get_attribute("aria-expanded") == "false"
    before = page.locator(STAGE).bounding_box()["width"]
    page.click('[data-action="toggle-panels"]')
    assert page.locator(".ut-side").is_hidden()
    next_paint(page)
    next_paint(page)
    assert page.locator(STAGE).bounding_box()["width"] > before, "the stage takes the panels' room"


CONTRAST = """(sel) => {
  const rgba = (s) => {  // rgb(a) in 0..255, or color(srgb r g b / a) in 0..1 (color-mix)
    const k = s.startsWith('color(srgb') ? 255 : 1;
    const m = s.replace('color(srgb', '').match(/[\\d.]+/g).map(Number);
    return [m[0] * k, m[1] * k, m[2] * k, m.length > 3 ? m[3] : 1];
  };
  const over = (top, under) => top.slice(0, 3).map((c, i) => c * top[3] + under[i] * (1 - top[3])).concat(1);
  const lum = (c) => { const f = (v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; };
    return 0.2126 * f(c[0]) + 0.7152 * f(c[1]) + 0.0722 * f(c[2]); };
  const background = (el) => {  // the backgrounds from the page down to el, composited
    const chain = [];
    for (let e = el; e; e = e.parentElement) chain.push(rgba(getComputedStyle(e).backgroundColor));
    return chain.reverse().reduce((under, top) => over(top, under), [255, 255, 255, 1]);
  };
  return [...document.querySelectorAll(sel)].filter((el) => el.offsetParent && !el.disabled && el.getAttribute('aria-disabled') !== 'true')
    .map((el) => {
      const bg = background(el);
      const fg = over(rgba(el.dataset.ink || getComputedStyle(el).color), bg);
      const [a, b] = [lum(fg), lum(bg)].sort((x, y) => y - x);
      return [el.className + (el.dataset.tool || el.dataset.action || ''), (a + 0.05) / (b + 0.05)];
    });
}"""


@pytest.mark.parametrize("theme", ["light", "jupyterlab-dark"])
def test_text_contrast_in_light_and_dark_themes(page, theme):
    if theme != "light":
        page.evaluate("(vars) => { const app = document.getElementById('app');"
                      " for (const [k, v] of Object.entries(vars)) app.style.setProperty(k, v);"
                      " document.body.style.background = vars['--jp-layout-color1']; }", JUPYTERLAB_DARK)
    mount(page)
    page.click('[data-action="add-layer"]')
    push_legend(page)
    page.locator(LEGEND).wait_for(state="visible")
    # the legend is the export's image: its text colour is the export's, on the legend's background
    ink = re.search(r'fill="(#[0-9a-fA-F]{3,6})"', TEXT).group(1)
    ink = "#" + "".join(c * 2 for c in ink[1:]) if len(ink) == 4 else ink
    page.evaluate("(ink) => { document.querySelector(\"img[data-role='legend']\").dataset.ink ="
                  " `rgb(${parseInt(ink.slice(1, 3), 16)}, ${parseInt(ink.slice(3, 5), 16)}, ${parseInt(ink.slice(5, 7), 16)})`; }", ink)
    tool(page, "container-rect")  # one pressed tool button
    sel = f"{LEGEND}, .ut-layer-name, .ut-toolbar .ut-btn, .ut-top > .ut-btn, .ut-panel h3"
    ratios = page.evaluate(CONTRAST, sel)
    assert len(ratios) >= 15
    low = [(name, round(r, 2)) for name, r in ratios if r < 4.5]
    assert not low, f"under WCAG AA (4.5:1) in the {theme} theme: {low}"


OVER_INK = """() => {
  const c = document.querySelectorAll('[data-role="stage"] canvas')[2];
  const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  let n = 0;
  for (let i = 3; i < d.length; i += 4) n += d[i] > 0;
  return n;
}"""


def test_guides_hide_over_finished_marks_unless_editing(page):
    mount(page)
    tool(page, "container-rect")
    drag(page, [(100, 100), (500, 400)])
    tool(page, "emitter-grid")
    click(page, 300, 250)
    tool(page, "force-point")
    click(page, 450, 150)
    tool(page, "force-direction")
    drag(page, [(200, 300), (300, 300)])
    tool(page, "select")
    page.keyboard.press("Escape")
    next_paint(page)
    assert page.evaluate(OVER_INK) > 0, "before a run the guides show"
    push_layout(page, [[300, 250, 0, 1]])
    next_paint(page)
    assert page.evaluate(OVER_INK) == 0, "after Run, with Select, no hatching, arrow or force dot"
    page.click('[data-action="toggle-guides"]')
    next_paint(page)
    assert page.evaluate(OVER_INK) > 0, "the Guides toggle shows them"
    page.click('[data-action="toggle-guides"]')
    tool(page, "force-point")
    next_paint(page)
    assert page.evaluate(OVER_INK) > 0, "an editing tool shows them"
