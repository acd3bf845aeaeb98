"""The built front end, driven for real in headless Chromium against a fake model.

Mouse drags go through Playwright; the fake model records every save_changes()
and custom message, and lets a test push trait changes as Python would.
"""

from __future__ import annotations

import math

import pytest

pytestmark = pytest.mark.browser

STAGE = '[data-role="stage"]'
ROOT = "[data-unitopia]"
TOOLS = [
    "select", "container-freehand", "container-rect", "container-ellipse", "emitter-grid",
    "emitter-curve", "force-point", "force-direction", "erase",
]
ACTIONS = ["run", "stop", "undo", "redo", "export-svg", "export-png", "copy-code", "add-layer"]


# --- helpers -------------------------------------------------------------------------

def mount(page, views: int = 1, **state) -> int:
    """Mounts the widget on a fresh fake model; returns how many model listeners it added."""
    n = page.evaluate(
        "([s, v]) => unitopia.mount(Object.assign(unitopia.defaultState(), s), {views: v})", [state, views]
    )
    page.wait_for_selector(ROOT)
    next_paint(page)
    return n


def next_paint(page) -> None:
    page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")


def design(page) -> dict:
    return page.evaluate("fake.get('design')")


def layer(page, i: int = 0) -> dict:
    return design(page)["layers"][i]


def save_count(page) -> int:
    return page.evaluate("fake.saves.length")


def tool(page, name: str) -> None:
    page.click(f'[data-tool="{name}"]')


def to_page(page, x: float, y: float, view: int = 0) -> tuple[float, float]:
    box = page.locator(STAGE).nth(view).bounding_box()
    return box["x"] + x * box["width"] / 800, box["y"] + y * box["height"] / 500


def drag(page, points, view: int = 0) -> None:
    page.locator(STAGE).nth(view).hover()
    page.mouse.move(*to_page(page, *points[0], view))
    page.mouse.down()
    for p in points[1:]:
        page.mouse.move(*to_page(page, *p, view))
    page.mouse.up()


def click(page, x: float, y: float, view: int = 0) -> None:
    drag(page, [(x, y)], view)


def circle_points(cx, cy, r, n=40, turn=1.0):
    return [(cx + r * math.cos(2 * math.pi * turn * i / n), cy + r * math.sin(2 * math.pi * turn * i / n)) for i in range(n + 1)]


def push_layout(page, rows, units=None, titles=None, status="done", frame_count=1, offset=0):
    """Pushes units, colours, titles and one frame as Python would after a run."""
    units = units or [[0, 0, 40, 40] for _ in rows]
    page.evaluate(
        """([rows, units, titles, status, count, offset]) => {
            fake.push('units', unitopia.f32(units));
            fake.push('colors', unitopia.u8(units.map(() => [200, 30, 30, 255])));
            fake.push('titles', titles);
            fake.push('status', status);
            fake.push('frame', unitopia.f32(rows, offset));
            fake.push('frame_count', count);
        }""",
        [rows, units, titles or [f"row {i}" for i in range(len(rows))], status, frame_count, offset],
    )


def pixel(page, x: float, y: float) -> list[int]:
    """RGBA of the marks canvas at canvas point (x, y)."""
    return page.evaluate(
        """([x, y]) => {
            const c = document.querySelectorAll('[data-role="stage"] canvas')[1];
            const k = c.width / 800;
            return Array.from(c.getContext('2d').getImageData(Math.round(x * k), Math.round(y * k), 1, 1).data);
        }""",
        [x, y],
    )


def wait_red_at(page, x, y):
    page.wait_for_function(
        """([x, y]) => {
            const c = document.querySelectorAll('[data-role="stage"] canvas')[1];
            const k = c.width / 800;
            const d = c.getContext('2d').getImageData(Math.round(x * k), Math.round(y * k), 1, 1).data;
            return d[3] > 200 && d[0] > 180 && d[1] < 120;
        }""",
        arg=[x, y],
        timeout=5000,
    )


# --- the fixed test hooks ------------------------------------------------------------

def test_root_hooks_tools_and_actions(page):
    mount(page)
    root = page.locator(ROOT)
    assert root.get_attribute("data-status") == "idle"
    assert root.get_attribute("data-frames") == "0"
    assert page.locator(STAGE).count() == 1
    for name in TOOLS:
        assert page.locator(f'[data-tool="{name}"]').count() == 1, name
    for name in ACTIONS:
        assert page.locator(f'[data-action="{name}"]').count() == 1, name


# --- sketching -------------------------------------------------------------------------

def test_freehand_lasso_sets_a_polygon_once_per_stroke(page):
    mount(page)
    tool(page, "container-freehand")
    before = save_count(page)
    drag(page, circle_points(400, 250, 150))
    assert save_count(page) == before + 1, "one save per stroke, none per pointer move"
    c = layer(page)["container"]
    assert c["kind"] == "polygon" and c["cuts"] == []
    assert len(c["points"]) >= 8
    for x, y in c["points"]:
        assert math.hypot(x - 400, y - 250) == pytest.approx(150, abs=3)
    # An open stroke (three quarters of a circle) is closed on release anyway.
    drag(page, circle_points(400, 250, 100, turn=0.75))
    assert save_count(page) == before + 2
    assert layer(page)["container"]["kind"] == "polygon"


def test_rect_and_ellipse_containers(page):
    mount(page)
    tool(page, "container-rect")
    drag(page, [(100, 80), (200, 150), (300, 280)])
    c = layer(page)["container"]
    assert c["kind"] == "rect"
    assert [c["x"], c["y"], c["w"], c["h"]] == pytest.approx([100, 80, 200, 200], abs=1)
    tool(page, "container-ellipse")
    drag(page, [(500, 100), (700, 300)])
    c = layer(page)["container"]
    assert c["kind"] == "ellipse"
    assert [c["cx"], c["cy"], c["rx"], c["ry"]] == pytest.approx([600, 200, 100, 100], abs=1)
    assert save_count(page) == 2


def test_point_forces_and_direction_force(page):
    mount(page)
    tool(page, "force-point")
    click(page, 100, 100)
    click(page, 300, 400)
    forces = layer(page)["forces"]
    assert [(f["kind"], round(f["x"]), round(f["y"])) for f in forces] == [("point", 100, 100), ("point", 300, 400)]
    tool(page, "force-direction")
    drag(page, [(400, 100), (400, 150), (400, 200)])
    drag(page, [(400, 200), (450, 200), (500, 200)])
    forces = layer(page)["forces"]
    directions = [f for f in forces if f["kind"] == "direction"]
    assert len(directions) == 1, "one direction force per layer, a new one replaces it"
    assert directions[0]["angle"] == pytest.approx(0, abs=1)
    assert sum(f["kind"] == "point" for f in forces) == 2
    assert save_count(page) == 4


def test_curve_emitter_stroke_fits_beziers(page):
    mount(page)
    tool(page, "emitter-curve")
    stroke = [(100 + 12 * i, 250 + 80 * math.sin(i / 5)) for i in range(50)]
    drag(page, stroke)
    e = layer(page)["emitter"]
    assert e["kind"] == "curve" and e["mode"] == "free" and e["speed"] == 1.0
    pts = e["points"]
    assert len(pts) >= 4 and (len(pts) - 1) % 3 == 0
    assert pts[0] == pytest.approx(list(stroke[0]), abs=1.5)
    assert pts[-1] == pytest.approx(list(stroke[-1]), abs=1.5)
    assert save_count(page) == 1


def test_grid_emitter_click_inside_the_container(page):
    mount(page)
    tool(page, "container-rect")
    drag(page, [(100, 100), (300, 300)])
    tool(page, "emitter-grid")
    click(page, 600, 400)  # outside: ignored
    assert layer(page)["emitter"] is None
    click(page, 200, 200)
    assert layer(page)["emitter"] == {"kind": "grid", "speed": 1.0, "direction": None}


def test_eraser_adds_a_cut(page):
    mount(page)
    tool(page, "container-ellipse")
    drag(page, [(200, 100), (600, 400)])
    tool(page, "erase")
    drag(page, [(300, 250), (400, 250), (500, 260)])
    cuts = layer(page)["container"]["cuts"]
    assert len(cuts) == 1
    assert cuts[0]["width"] > 0 and len(cuts[0]["points"]) >= 2
    assert cuts[0]["points"][0] == pytest.approx([300, 250], abs=1)


def test_undo_redo_buttons_and_keys(page):
    mount(page)
    tool(page, "force-point")
    click(page, 100, 100)
    click(page, 200, 200)
    assert len(layer(page)["forces"]) == 2
    page.click('[data-action="undo"]')
    assert len(layer(page)["forces"]) == 1
    page.keyboard.press("Control+z")
    assert len(layer(page)["forces"]) == 0
    page.keyboard.press("Control+Shift+z")
    assert len(layer(page)["forces"]) == 1
    page.click('[data-action="redo"]')
    assert len(layer(page)["forces"]) == 2
    assert page.locator('[data-action="redo"]').get_attribute("aria-disabled") == "true"
    page.click('[data-action="redo"]', force=True)  # nothing left to redo: a no-op
    assert len(layer(page)["forces"]) == 2


def test_select_moves_a_container_and_deletes_a_force(page):
    mount(page)
    tool(page, "container-rect")
    drag(page, [(100, 100), (300, 300)])
    tool(page, "force-point")
    click(page, 500, 250)
    tool(page, "select")
    saves = save_count(page)
    drag(page, [(100, 200), (130, 210), (150, 220)])  # grab the left edge
    c = layer(page)["container"]
    assert [c["x"], c["y"]] == pytest.approx([150, 120], abs=1)
    assert save_count(page) == saves + 1, "a drag commits once, on release"
    click(page, 500, 250)  # pick the force
    page.keyboard.press("Delete")
    assert layer(page)["forces"] == []
    click(page, 150, 220)  # pick the container by its (moved) edge
    page.keyboard.press("Backspace")
    assert layer(page)["container"] is None


def test_select_drags_a_curve_emitter_handle(page):
    mount(page)
    tool(page, "emitter-curve")
    drag(page, [(100 + 10 * i, 300) for i in range(35)])
    first = layer(page)["emitter"]["points"][0]
    tool(page, "select")
    drag(page, [tuple(first), (first[0], first[1] - 40), (first[0], first[1] - 80)])
    moved = layer(page)["emitter"]["points"]
    assert moved[0] == pytest.approx([first[0], first[1] - 80], abs=1.5)
    assert (len(moved) - 1) % 3 == 0


# --- run, frames, status -------------------------------------------------------------

def test_run_and_stop_send_messages(page):
    mount(page)
    page.click('[data-action="run"]')
    page.evaluate("fake.push('status', 'running')")
    page.click('[data-action="stop"]')
    assert page.evaluate("fake.sent") == [{"type": "run"}, {"type": "stop"}]


def test_frames_update_data_frames_and_draw_marks(page):
    mount(page, marks=[])
    page.evaluate(
        "fake.push('marks', [{layer: 'layer-1', src: unitopia.svgMark('square', '#e01010'), aspect: 1}])"
    )
    # Unaligned byteOffset on purpose: anywidget hands out views into larger buffers.
    push_layout(page, [[200, 150, 0, 1.0], [600, 350, 45, 1.5]], status="running", frame_count=1, offset=3)
    root = page.locator(ROOT)
    assert root.get_attribute("data-status") == "running"
    assert root.get_attribute("data-frames") == "1"
    wait_red_at(page, 200, 150)
    wait_red_at(page, 600, 350)
    assert pixel(page, 400, 250)[3] == 0, "nothing drawn between the marks"
    # A second frame moves the first mark; the animation settles on the new position.
    page.evaluate("fake.push('frame', unitopia.f32([[300, 150, 0, 1], [600, 350, 45, 1.5]])); fake.push('frame_count', 2)")
    assert root.get_attribute("data-frames") == "2"
    wait_red_at(page, 300, 150)
    page.wait_for_function(
        """() => { const c = document.querySelectorAll('[data-role="stage"] canvas')[1];
                   return c.getContext('2d').getImageData(200, 150, 1, 1).data[3] === 0; }"""
    )
    page.evaluate("fake.push('status', 'done')")
    assert root.get_attribute("data-status") == "done"


def test_progress_status_and_error_banner(page):
    mount(page)
    banner = page.locator('[role="alert"]')
    assert banner.is_hidden()
    page.evaluate("fake.push('progress', {iteration: 12, max_iterations: 600, loss: 0.25}); fake.push('status', 'running')")
    assert "12 / 600" in page.locator(".ut-status").inner_text()
    page.evaluate("fake.push('error', 'container is empty <b>x</b>'); fake.push('status', 'error')")
    assert banner.is_visible()
    assert banner.inner_text() == "container is empty <b>x</b>"
    assert page.locator(ROOT).get_attribute("data-status") == "error"
    assert page.locator('[role="alert"] b').count() == 0


# --- after a run: hover, selection, export ------------------------------------------

def test_hover_shows_the_row_as_text(page):
    mount(page)
    evil = "<img src=x onerror=alert(1)>"
    push_layout(page, [[200, 200, 0, 1], [210, 200, 30, 1]], titles=["Task: A, Duration: 3", evil])
    tool(page, "select")
    page.locator(STAGE).hover()
    page.mouse.move(*to_page(page, 180, 200))
    tip = page.locator('[role="tooltip"]')
    tip.wait_for(state="visible")
    assert tip.inner_text() == "Task: A, Duration: 3"
    page.mouse.move(*to_page(page, 215, 200))  # topmost first: the later unit wins
    page.wait_for_function("document.querySelector('[role=tooltip]').textContent.startsWith('<img')")
    assert tip.inner_text() == evil
    assert page.locator(f"{ROOT} img[src='x']").count() == 0, "a title is text, never markup"
    page.mouse.move(*to_page(page, 700, 450))
    tip.wait_for(state="hidden")


def test_click_and_lasso_select_units(page):
    mount(page)
    rows = [[100 + 60 * i, 250, 0, 1] for i in range(8)]
    push_layout(page, rows)
    tool(page, "select")
    click(page, 160, 250)
    assert page.evaluate("fake.get('selected_units')") == [1]
    page.keyboard.down("Shift")
    click(page, 340, 250)
    page.keyboard.up("Shift")
    assert page.evaluate("fake.get('selected_units')") == [1, 4]
    drag(page, [(370, 200), (540, 200), (540, 300), (370, 300), (370, 205)])
    assert page.evaluate("fake.get('selected_units')") == [5, 6, 7]
    assert page.evaluate("fake.saves.at(-1).selected_units") == [5, 6, 7]
    click(page, 700, 450)  # a click on empty space clears
    assert page.evaluate("fake.get('selected_units')") == []


def test_export_reply_triggers_a_download(page):
    mount(page)
    page.click('[data-action="export-svg"]')
    page.click('[data-action="export-png"]')
    assert page.evaluate("fake.sent") == [{"type": "export", "format": "svg"}, {"type": "export", "format": "png"}]
    svg = '<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8"/>'
    with page.expect_download() as info:
        page.evaluate("s => fake.message({type: 'export', format: 'svg', data: s})", svg)
    dl = info.value
    assert dl.suggested_filename == "unitopia.svg"
    with open(dl.path(), encoding="utf-8") as fh:
        assert fh.read() == svg
    png = "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8DwHwAFBQIAX8jx0gAAAABJRU5ErkJggg=="
    with page.expect_download() as info:
        page.evaluate("s => fake.message({type: 'export', format: 'png', data: s})", png)
    assert info.value.suggested_filename == "unitopia.png"
    with open(info.value.path(), "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n"


def test_an_export_refused_mid_run_shows_a_notice_and_keeps_stop(page):
    mount(page)
    page.evaluate("fake.push('status', 'running')")
    page.click('[data-action="export-svg"]')
    page.evaluate("fake.message({type: 'notice', text: 'Export waits for the layout'})")
    notice = page.locator('[data-role="notice"]')
    assert notice.is_visible() and notice.inner_text() == "Export waits for the layout"
    assert page.locator(ROOT).get_attribute("data-status") == "running"
    assert page.locator('[data-action="stop"]').is_enabled()


# --- panels --------------------------------------------------------------------------

def test_field_dropped_on_size_sets_the_encoding(page):
    mount(page)
    page.locator('[data-field="Duration"]').drag_to(page.locator('[data-channel="size"]'))
    assert layer(page)["encodings"]["size"] == "Duration"
    # Click-to-pick fallback, then clear.
    page.click('[data-field="Task"]')
    page.click('[data-channel="color"]')
    assert layer(page)["encodings"]["color"] == "Task"
    page.click('[data-clear="size"]')
    assert layer(page)["encodings"]["size"] is None
    assert layer(page)["encodings"]["color"] == "Task"


def test_uploading_an_svg_or_png_adds_a_mark(page, tmp_path):
    mount(page)
    svg = tmp_path / "flower.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><circle cx="5" cy="5" r="4"/></svg>')
    page.set_input_files('[data-role="mark-upload"]', str(svg))
    page.wait_for_function("fake.get('design').layers[0].marks.at(-1).kind === 'svg'")
    assert layer(page)["marks"][0] == {"kind": "shape", "name": "circle"}, "an upload adds to the mark set"
    assert layer(page)["marks"][1]["svg"].startswith("<svg")
    png = tmp_path / "dot.png"
    png.write_bytes(bytes.fromhex(
        "89504e470d0a1a0a0000000d4948445200000001000000010806000000"
        "1f15c4890000000d49444154789c63f8cfc0f01f0005050200"
        "5fc8f1d20000000049454e44ae426082"
    ))
    page.set_input_files('[data-role="mark-upload"]', str(png))
    page.wait_for_function("fake.get('design').layers[0].marks.at(-1).kind === 'image'")
    assert layer(page)["marks"][2]["image"].startswith("data:image/png;base64,")


def test_sketched_mark(page):
    mount(page)
    page.click('[data-action="sketch-mark"]')
    pad = page.locator('[data-role="sketch-pad"]')
    pad.hover()
    box = pad.bounding_box()
    page.mouse.move(box["x"] + 20, box["y"] + 20)
    page.mouse.down()
    page.mouse.move(box["x"] + 80, box["y"] + 120, steps=5)
    page.mouse.up()
    page.click('[data-pad-action="use"]')
    mark = layer(page)["marks"][-1]
    assert len(layer(page)["marks"]) == 2
    assert mark["kind"] == "sketch" and len(mark["strokes"]) == 1 and mark["width"] > 0


def test_layers_panel_add_rename_block_settings(page):
    mount(page)
    page.click('[data-action="add-layer"]')
    d = design(page)
    assert [l["name"] for l in d["layers"]] == ["layer-1", "layer-2"]
    # The new layer is current: tools and settings act on it.
    tool(page, "force-point")
    click(page, 50, 60)
    assert design(page)["layers"][1]["forces"][0]["x"] == pytest.approx(50, abs=1)
    page.check('[data-block="layer-1"]')
    assert design(page)["layers"][1]["blocks"] == ["layer-1"]
    page.select_option('[data-setting="boundary"]', "open")
    page.check('[data-setting="rotate"]')
    page.fill('[data-setting="iterations"]', "250")
    page.press('[data-setting="iterations"]', "Enter")
    second = design(page)["layers"][1]
    assert (second["boundary"], second["rotate"], second["iterations"]) == ("open", True, 250)
    name = page.locator(".ut-layer-name").nth(0)
    name.fill("ground")
    name.press("Enter")
    assert design(page)["layers"][1]["blocks"] == ["ground"], "renames follow into blocks"
    page.locator('[data-layer="1"] [data-layer-action="delete"]').click()
    assert [l["name"] for l in design(page)["layers"]] == ["ground"]


def test_settings_turn_marks_at_random_angles_within_a_range(page):
    mount(page)
    page.select_option('[data-setting="orientation"]', "random")
    assert layer(page)["orientation"] == "random"
    page.fill('[data-setting="random_lo"]', "-30")
    page.press('[data-setting="random_lo"]', "Enter")
    page.fill('[data-setting="random_hi"]', "30")
    page.press('[data-setting="random_hi"]', "Enter")
    assert layer(page)["orientation"] == ["random", -30, 30]
    assert page.input_value('[data-setting="random_lo"]') == "-30"
    page.select_option('[data-setting="orientation"]', "none")
    assert layer(page)["orientation"] is None


def test_background_and_image_container_are_drawn(page):
    white = "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8DwHwAFBQIAX8jx0gAAAABJRU5ErkJggg=="
    mount(page)
    page.evaluate(
        """(img) => { const d = fake.get('design');
                   d.background = {image: img};
                   d.layers[0].container = {kind: 'image', image: img, threshold: 0.5, box: [100, 100, 200, 100], cuts: []};
                   fake.push('design', JSON.parse(JSON.stringify(d))); }""",
        white,
    )
    bg = page.locator(f"{STAGE} img")
    bg.wait_for(state="visible")
    assert bg.get_attribute("src") == white
    page.wait_for_function(
        """() => { const c = document.querySelectorAll('[data-role="stage"] canvas')[0], k = c.width / 800;
                   const alpha = (x, y) => c.getContext('2d').getImageData(x * k, y * k, 1, 1).data[3];
                   return alpha(200, 150) > 0 && alpha(400, 300) === 0; }"""
    )


def test_python_side_design_change_redraws_and_two_views_agree(page):
    n = mount(page, views=2)
    assert n > 0
    page.evaluate(
        """() => { const d = fake.get('design');
                   d.layers[0].container = {kind: 'rect', x: 10, y: 10, w: 100, h: 100, cuts: []};
                   fake.push('design', JSON.parse(JSON.stringify(d))); }"""
    )
    tool(page, "force-point")
    click(page, 400, 300, view=1)
    assert len(layer(page)["forces"]) == 1
    # Both views show the same state: the shared tool and undo history.
    assert page.locator('[data-tool="force-point"][aria-pressed="true"]').count() == 2
    page.locator('[data-action="undo"]').nth(0).click()
    assert layer(page)["forces"] == []
    # Aborting the views removes every listener they added.
    assert page.evaluate("unitopia.unmount(), fake.listenerCount()") == 0


def test_stage_scales_to_fit_a_narrow_cell_at_high_dpi(browser, page_url):
    context = browser.new_context(viewport={"width": 700, "height": 900}, device_scale_factor=2)
    context.set_default_timeout(5000)
    try:
        pg = context.new_page()
        pg.goto(page_url)
        pg.wait_for_function("window.unitopiaReady === true")
        mount(pg)
        box = pg.locator(STAGE).bounding_box()
        assert box["width"] < 700 and box["width"] / box["height"] == pytest.approx(800 / 500, rel=0.01)
        backing = pg.evaluate("document.querySelector('[data-role=stage] canvas').width")
        assert backing == round(box["width"] * 2), "drawn at devicePixelRatio"
        tool(pg, "container-rect")
        drag(pg, [(100, 100), (300, 300)])
        c = layer(pg)["container"]
        assert [c["x"], c["y"], c["w"], c["h"]] == pytest.approx([100, 100, 200, 200], abs=2), "pointer -> canvas px"
    finally:
        context.close()


def test_copy_as_python_puts_the_kernels_code_on_the_clipboard_or_in_a_selected_textarea(page):
    mount(page)
    page.context.grant_permissions(["clipboard-read", "clipboard-write"])
    page.click('[data-action="copy-code"]')
    assert page.evaluate("fake.sent") == [{"type": "code"}]
    code = "import unitopia_widget as uw\n\ndesign = {'layers': []}\nw = uw.UnitoPia.from_design(df, design)\n"
    page.evaluate("c => fake.message({type: 'code', code: c})", code)
    page.wait_for_function("() => document.querySelector('[data-role=notice]').innerText.includes('Copied')")
    assert page.evaluate("navigator.clipboard.readText()") == code
    # no clipboard API (an insecure page, an old front end): a selected textarea holds it
    page.evaluate("Object.defineProperty(navigator, 'clipboard', {value: undefined}); "
                  "document.execCommand = () => false")
    page.evaluate("c => fake.message({type: 'code', code: c})", code + "# again\n")
    area = page.locator("textarea.ut-code")
    area.wait_for()
    assert area.input_value() == code + "# again\n"
    assert page.evaluate("() => { const a = document.querySelector('textarea.ut-code'); "
                         "return [a.selectionStart, a.selectionEnd] }") == [0, len(code) + 8]


def test_position_slots_and_arrange_setting(page):
    mount(page)
    page.locator('[data-field="Duration"]').drag_to(page.locator('[data-channel="x"]'))
    page.click('[data-field="Task"]')
    page.click('[data-channel="y"]')
    assert (layer(page)["encodings"]["x"], layer(page)["encodings"]["y"]) == ("Duration", "Task")
    page.select_option('[data-setting="x_scale"]', "log")
    page.select_option('[data-setting="arrange"]', "grid")
    assert (layer(page)["x_scale"], layer(page)["arrange"]) == ("log", "grid")
    page.click('[data-clear="x"]')
    assert layer(page)["encodings"]["x"] is None
    assert page.locator('[data-setting="x_scale"]').count() == 0, "the scale shows once x is bound"
