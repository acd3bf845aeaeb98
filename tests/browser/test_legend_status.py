"""Browser tests of the legend beside the canvas and of an honest status line: stopped,
stale, a full bar when done, errors that stay until dismissed, Run with no kernel."""

from __future__ import annotations

import pytest
from test_frontend import ROOT, STAGE, drag, layer, mount, next_paint, push_layout, save_count, wait_red_at

pytestmark = pytest.mark.browser

LEGEND = "img[data-role='legend']"


def push_legend(page, w=120, h=80):
    page.evaluate(
        """([w, h]) => {
            const svg = `<svg xmlns="http://www.w3.org/2000/svg" width="${w}" height="${h}">` +
                        `<rect width="${w}" height="${h}" fill="#2a9d3a"/></svg>`;
            fake.push('legend_image', {src: 'data:image/svg+xml;base64,' + btoa(svg), width: w, height: h});
        }""",
        [w, h],
    )


def test_legend_is_shown_beside_the_canvas_dragged_and_hidden(page):
    mount(page)
    assert page.locator(LEGEND).is_hidden(), "no legend before the kernel sends one"
    push_legend(page)
    legend = page.locator(LEGEND)
    legend.wait_for(state="visible")
    # the stage gives the legend its room by a resize, a frame or two after the legend shows
    page.wait_for_function(
        """([stage, legend]) => {
            const s = document.querySelector(stage).getBoundingClientRect();
            return document.querySelector(legend).getBoundingClientRect().x >= s.x + s.width;
        }""", arg=[STAGE, LEGEND], timeout=5000)
    stage = page.locator(STAGE).bounding_box()
    box = legend.bounding_box()
    k = stage["width"] / 800
    assert box["x"] >= stage["x"] + stage["width"], "right of the canvas by default"
    assert box["width"] == pytest.approx(120, abs=1), "beside the canvas, drawn at its own size (legible)"
    assert page.locator(f"{ROOT} svg").count() == 0, "an image, never markup"
    # Drag it onto the canvas: one commit with its top-left corner in canvas px.
    saves = save_count(page)
    page.mouse.move(box["x"] + 10, box["y"] + 10)
    page.mouse.down()
    target = (stage["x"] + 300 * k + 10, stage["y"] + 200 * k + 10)
    page.mouse.move(stage["x"] + 500 * k, stage["y"] + 100 * k, steps=4)
    page.mouse.move(*target, steps=4)
    page.mouse.up()
    assert save_count(page) == saves + 1
    x, y = page.evaluate("fake.get('design').legend.position")
    assert (x, y) == (pytest.approx(300, abs=2), pytest.approx(200, abs=2))
    assert layer(page)["forces"] == [], "the drag is not a stroke of the current tool"
    next_paint(page)
    stage = page.locator(STAGE).bounding_box()  # on the canvas, it leaves the stage the row's width
    k = stage["width"] / 800
    moved = legend.bounding_box()
    assert (moved["x"], moved["y"]) == (pytest.approx(stage["x"] + 300 * k, abs=2), pytest.approx(stage["y"] + 200 * k, abs=2))
    assert moved["width"] == pytest.approx(120 * k, abs=1), "on the canvas, drawn at the chart's scale (canvas px)"
    # Dragged past the edge, it stays on the canvas.
    page.mouse.move(moved["x"] + 5, moved["y"] + 5)
    page.mouse.down()
    page.mouse.move(stage["x"] + 2000, stage["y"] + 2000, steps=3)
    page.mouse.up()
    assert page.evaluate("fake.get('design').legend.position") == [680, 420]
    # Hide and show.
    page.click('[data-action="toggle-legend"]')
    assert page.evaluate("fake.get('design').legend") == {"visible": False, "position": [680, 420]}
    assert legend.is_hidden()
    assert page.get_attribute('[data-action="toggle-legend"]', "aria-pressed") == "false"
    page.evaluate("fake.push('legend_image', {})")  # Python sends none while it is hidden
    assert page.get_attribute('[data-action="toggle-legend"]', "aria-disabled") == "false"
    page.click('[data-action="toggle-legend"]')
    assert page.evaluate("fake.get('design').legend.visible") is True
    push_legend(page)
    legend.wait_for(state="visible")


@pytest.mark.parametrize("side", ["left", "bottom", "top"])
def test_legend_position_names_a_side(page, side):
    mount(page)
    page.evaluate("s => { const d = fake.get('design'); d.legend = {visible: true, position: s}; fake.push('design', JSON.parse(JSON.stringify(d))); }", side)
    push_legend(page)
    page.locator(LEGEND).wait_for(state="visible")
    next_paint(page)
    s = page.locator(STAGE).bounding_box()
    b = page.locator(LEGEND).bounding_box()
    where = {"left": b["x"] + b["width"] <= s["x"], "bottom": b["y"] >= s["y"] + s["height"], "top": b["y"] + b["height"] <= s["y"]}
    assert where[side], (side, s, b)


def status_word(page) -> str:
    return page.locator(".ut-status-word").inner_text().lower()


def test_stopped_and_stale_status(page):
    mount(page)
    push_layout(page, [[200, 200, 0, 1]], status="stopped")
    root = page.locator(ROOT)
    assert root.get_attribute("data-status") == "stopped"
    assert status_word(page) == "stopped"
    page.evaluate("fake.push('status', 'done')")
    assert status_word(page) == "done"
    page.evaluate("fake.push('stale', true)")
    assert status_word(page) == "changed: run again"
    assert root.get_attribute("data-stale") == "true"
    assert root.get_attribute("data-status") == "done"
    page.evaluate("fake.push('status', 'running')")
    assert status_word(page) == "running"
    page.evaluate("fake.push('stale', false); fake.push('status', 'done')")
    assert status_word(page) == "done" and root.get_attribute("data-stale") == "false"


def test_a_finished_run_fills_the_progress_bar(page):
    mount(page)
    page.evaluate("fake.push('progress', {iteration: 107, max_iterations: 600, loss: 0.5}); fake.push('status', 'running')")
    bar = page.locator("progress.ut-progress")
    assert page.evaluate("document.querySelector('progress.ut-progress').position") == pytest.approx(107 / 600, abs=1e-3)
    page.evaluate("fake.push('progress', {iteration: 107, max_iterations: 600, loss: 0.5, done: true}); fake.push('status', 'done')")
    assert page.evaluate("document.querySelector('progress.ut-progress').position") == 1
    assert "107 / 600" in page.locator(".ut-status").inner_text()
    assert bar.is_visible()


def test_an_error_stays_until_dismissed(page):
    mount(page)
    page.evaluate("fake.push('error', 'color=: column Meta holds dicts'); fake.push('status', 'error')")
    alert = page.locator('[role="alert"]')
    assert alert.is_visible()
    page.click('[data-tool="force-point"]')
    drag(page, [(100, 100)])  # an edit: the error stays until fixed or dismissed
    next_paint(page)
    assert alert.is_visible() and alert.inner_text() == "color=: column Meta holds dicts"
    page.click('[data-action="dismiss-error"]')
    assert alert.is_hidden()
    assert {"type": "dismiss-error"} in page.evaluate("fake.sent")
    page.evaluate("fake.push('status', 'idle')")  # no kernel reply yet: it stays dismissed
    assert alert.is_hidden()
    page.evaluate("fake.push('error', 'a new error')")
    assert alert.is_visible() and alert.inner_text() == "a new error"


def test_run_without_a_kernel_says_so(page):
    # A restored widget: the saved state holds the layout, and no kernel is behind it.
    page.evaluate("""() => unitopia.mount(Object.assign(unitopia.defaultState(), {
        units: unitopia.f32([[0, 0, 40, 40]]), colors: unitopia.u8([[200, 30, 30, 255]]),
        frame: unitopia.f32([[200, 200, 0, 1]]), frame_count: 12, status: 'done'}))""")
    page.wait_for_selector(ROOT)
    wait_red_at(page, 200, 200)
    notice = page.locator('[data-role="notice"]')
    page.click('[data-action="run"]')
    assert notice.is_hidden()
    notice.wait_for(state="visible", timeout=4000)
    assert "Waiting for the kernel" in notice.inner_text()   # busy, or not started
    assert page.locator(".ut-status-word").text_content() == "waiting for the kernel"
    assert page.evaluate("fake.sent") == [{"type": "run"}]
    # With a kernel that answers, no notice.
    page.evaluate("fake.playPython()")
    page.click('[data-action="run"]')
    assert notice.is_hidden()
    page.wait_for_function("fake.get('status') === 'running'")
    page.wait_for_timeout(2500)
    assert notice.is_hidden()


def test_run_says_so_at_once_when_the_message_cannot_be_sent(page):
    mount(page)
    page.evaluate("() => { fake.send = () => { throw new Error('no comm'); }; }")
    page.click('[data-action="run"]')
    assert page.locator('[data-role="notice"]').is_visible()
    assert "No kernel is connected" in page.locator('[data-role="notice"]').inner_text()


def test_a_closed_comm_shows_no_kernel_and_stop_does_not_throw(page):
    # A kernel restart mid-run: the model's comm closes, sending throws "Cannot send".
    page.evaluate("() => unitopia.mount(Object.assign(unitopia.defaultState(), {status: 'running'}))")
    page.wait_for_selector(ROOT)
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.evaluate("() => { fake.send = () => { throw new Error('Cannot send'); }; fake.emit('comm_live_update'); }")
    assert page.locator(ROOT).get_attribute("data-kernel") == "gone"
    assert page.locator(".ut-status-word").text_content() == "no kernel"
    assert "No kernel is connected" in page.locator('[data-role="notice"]').inner_text()
    page.locator('[data-action="stop"]').click(force=True)
    page.locator('[data-action="export-svg"]').click()
    page.wait_for_timeout(100)
    assert errors == []
    # the comm's own close event says the same without a probe
    page.evaluate("() => unitopia.mount(Object.assign(unitopia.defaultState(), {status: 'running'}))")
    page.evaluate("() => fake.emit('comm:close')")
    assert page.locator(ROOT).get_attribute("data-kernel") == "gone"
