"""Browser tests of mark sets, the shape channel, several marks per layer and the
selection keys, against the fake model (which plays the kernel where a test needs it)."""

from __future__ import annotations

import pytest
from test_frontend import ROOT, STAGE, click, layer, mount, next_paint, pixel, push_layout, save_count, to_page

pytestmark = pytest.mark.browser

CIRCLE = {"kind": "shape", "name": "circle"}
ICONS = ["fa:apple-whole", "fa:apple-alt", "fa:pineapple", "fa:banana", "fa:star"]


def kinds(page) -> list[str]:
    return [m.get("name", m["kind"]) for m in layer(page)["marks"]]


def test_mark_set_add_from_shape_upload_and_icon_name_then_reorder_and_remove(page, tmp_path):
    mount(page)
    page.evaluate("fake.playPython({icons: %r})" % ICONS)
    page.select_option('[data-setting="mark-shape"]', "star")
    assert layer(page)["marks"] == [CIRCLE, {"kind": "shape", "name": "star"}]
    assert "mark" not in layer(page), "version 2 designs hold the list only"
    svg = tmp_path / "leaf.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><circle cx="5" cy="5" r="4"/></svg>')
    page.set_input_files('[data-role="mark-upload"]', str(svg))
    page.wait_for_function("fake.get('design').layers[0].marks.length === 3")
    # An icon by name: the query goes to the kernel; its names are listed; a click adds one.
    page.fill('[data-role="icon-query"]', "apple")
    page.wait_for_selector('[data-icon="fa:apple-whole"]')
    assert {"type": "icons", "query": "apple"} in page.evaluate("fake.sent")
    assert page.locator("[data-icon]").all_inner_texts() == ["fa:apple-whole", "fa:apple-alt", "fa:pineapple"]
    # A reply to an older query does not replace the list.
    page.evaluate("fake.message({type: 'icons', query: 'ban', names: ['fa:banana']})")
    assert page.locator("[data-icon]").count() == 3
    page.click('[data-icon="fa:apple-whole"]')
    assert layer(page)["marks"][3] == {"kind": "icon", "name": "fa:apple-whole"}
    assert page.locator("[data-icon]").count() == 0
    assert kinds(page) == ["circle", "star", "svg", "fa:apple-whole"]
    # Each mark shows the kernel's rendering of it (`marks` entries with "mark": k).
    page.wait_for_function("document.querySelectorAll('.ut-mark-list img').length === 4")
    shown = page.evaluate("[...document.querySelectorAll('.ut-mark-list [data-mark] img')].map((i) => i.src)")
    assert shown == page.evaluate("[0, 1, 2, 3].map((k) => fake.get('marks').find((m) => m.mark === k).src)")
    assert len(set(shown)) == 4
    saves = save_count(page)
    page.click('[data-mark="3"] [data-mark-action="up"]')
    assert kinds(page) == ["circle", "star", "fa:apple-whole", "svg"]
    page.click('[data-mark="0"] [data-mark-action="down"]')
    assert kinds(page) == ["star", "circle", "fa:apple-whole", "svg"]
    page.click('[data-mark="1"] [data-mark-action="remove"]')
    assert kinds(page) == ["star", "fa:apple-whole", "svg"]
    assert save_count(page) == saves + 3, "one design replacement per edit"
    page.click('[data-mark="0"] [data-mark-action="remove"]')
    page.click('[data-mark="0"] [data-mark-action="remove"]')
    assert kinds(page) == ["svg"]
    assert page.locator('[data-mark="0"] [data-mark-action="remove"]').is_disabled(), "a layer keeps one mark"


def test_each_mark_names_the_category_it_draws(page):
    mount(page)
    page.evaluate("""() => { const d = fake.get('design');
        d.layers[0].marks = [{kind: 'shape', name: 'circle'}, {kind: 'icon', name: 'fa:bug'}];
        d.layers[0].mark_keys = ['feature', 'bug']; d.layers[0].encodings.shape = 'Task';
        fake.push('design', JSON.parse(JSON.stringify(d))); }""")
    assert page.locator(".ut-mark-label").all_inner_texts() == ["circle = feature", "fa:bug = bug"]
    page.click('[data-mark="1"] [data-mark-action="up"]')
    assert layer(page)["mark_keys"] == ["bug", "feature"]
    assert page.locator(".ut-mark-label").all_inner_texts() == ["fa:bug = bug", "circle = feature"]


def test_an_icon_query_with_no_match_says_so(page):
    mount(page)
    page.evaluate("fake.playPython({icons: %r})" % ICONS)
    page.fill('[data-role="icon-query"]', "aple")
    page.wait_for_selector('[data-role="icon-results"] .ut-hint')
    assert "No icon matches" in page.locator('[data-role="icon-results"]').inner_text()


def test_shape_channel_and_no_channel_unbinds_another(page):
    mount(page)
    page.locator('[data-field="Task"]').drag_to(page.locator('[data-channel="shape"]'))
    assert layer(page)["encodings"]["shape"] == "Task"
    page.locator('[data-field="Duration"]').drag_to(page.locator('[data-channel="size"]'))
    page.locator('[data-field="Duration"]').drag_to(page.locator('[data-channel="width"]'))
    enc = layer(page)["encodings"]
    assert (enc["size"], enc["width"], enc["shape"]) == ("Duration", "Duration", "Task"), "width never clears size"
    # The kernel refuses a combination it cannot draw: its error shows.
    page.evaluate("fake.push('error', 'size= and width= cannot both be bound'); fake.push('status', 'error')")
    assert page.locator('[role="alert"]').inner_text() == "size= and width= cannot both be bound"


def test_several_marks_in_one_layer_are_drawn_hovered_and_selected(page):
    red = "unitopia.svgMark('square', '#e01010')"
    blue = "unitopia.svgMark('square', '#1010e0')"
    mount(page, marks=[])
    page.evaluate(f"fake.push('marks', [{{layer: 'layer-1', mark: 0, src: {red}, aspect: 1}}, "
                  f"{{layer: 'layer-1', mark: 1, src: {blue}, aspect: 1}}])")
    rows = [[200, 250, 0, 1], [400, 250, 0, 1], [600, 250, 0, 1]]
    push_layout(page, rows, units=[[0, 0, 40, 40], [0, 1, 40, 40], [0, 0, 40, 40]], titles=["a", "b", "c"])
    page.wait_for_function(
        """() => { const c = document.querySelectorAll('[data-role="stage"] canvas')[1], k = c.width / 800;
                   const px = (x) => c.getContext('2d').getImageData(x * k, 250 * k, 1, 1).data;
                   return px(200)[0] > 180 && px(400)[2] > 180 && px(600)[0] > 180; }"""
    )
    r, g, b, a = pixel(page, 400, 250)
    assert b > 180 and r < 80 and a > 200, "unit 1 drawn with its own mark (marks entry 1)"
    page.locator(STAGE).hover()
    page.mouse.move(*to_page(page, 405, 255))
    tip = page.locator('[role="tooltip"]')
    tip.wait_for(state="visible")
    assert tip.inner_text() == "b"
    click(page, 400, 250)
    assert page.evaluate("fake.get('selected_units')") == [1]


@pytest.mark.parametrize("key", ["Shift", "Control", "Meta"])
def test_modifier_click_toggles_a_unit_in_the_selection(page, key):
    mount(page)
    push_layout(page, [[100 + 60 * i, 250, 0, 1] for i in range(5)])
    click(page, 100, 250)
    page.keyboard.down(key)
    click(page, 220, 250)
    click(page, 340, 250)
    assert page.evaluate("fake.get('selected_units')") == [0, 2, 4]
    click(page, 220, 250)  # again: out of the selection
    page.keyboard.up(key)
    assert page.evaluate("fake.get('selected_units')") == [0, 4]
    click(page, 160, 250)  # a plain click selects that one only
    assert page.evaluate("fake.get('selected_units')") == [1]
    next_paint(page)
    assert page.locator(ROOT).get_attribute("data-status") == "done"
