"""The replay of the last run, in the built front end against a fake model: with the
kernel gone it plays from the first frame, the marks move, hover finds them where they
are shown, scrubbing to the end shows the final layout, nothing is sent, and a new run
clears the recording."""

from __future__ import annotations

import pytest

from test_frontend import ROOT, STAGE, mount, next_paint, to_page

pytestmark = pytest.mark.browser

REPLAY = '[data-role="replay"]'
FRAMES = 61   # x from 100 to 700 in steps of 10: two seconds of replay at 30 frames a second

# the x centre of the red 40 px square on the marks canvas's row y = 250, or null
MARK_X = """() => {
    const c = document.querySelectorAll('[data-role="stage"] canvas')[1];
    const k = c.width / 800;
    const row = c.getContext('2d').getImageData(0, Math.round(250 * k), c.width, 1).data;
    for (let i = 0; i < c.width; i++) if (row[4 * i + 3] > 200 && row[4 * i] > 180) return i / k + 20;
    return null;
}"""
MARKS_PNG = "() => document.querySelectorAll('[data-role=\"stage\"] canvas')[1].toDataURL()"


def mark_at(page, x: float) -> None:
    page.wait_for_function(f"(x) => {{ const m = ({MARK_X})(); return m !== null && Math.abs(m - x) < 2; }}", arg=x)


def test_replay_plays_and_scrubs_without_a_kernel(page):
    mount(page, marks=[])
    page.evaluate(
        """(n) => {
            fake.push('marks', [{layer: 'layer-1', mark: 0, src: unitopia.svgMark('square', '#e01010'), aspect: 1}]);
            fake.push('units', unitopia.f32([[0, 0, 40, 40]]));
            fake.push('colors', unitopia.u8([[224, 16, 16, 255]]));
            fake.push('titles', ['row 0']);
            fake.push('status', 'running');
            fake.push('frame_count', 0);
            for (let i = 0; i < n; i++) {
                fake.push('frame', unitopia.f32([[100 + 10 * i, 250, 0, 1]], i % 4));
                fake.push('frame_count', i + 1);
            }
            fake.push('status', 'done');
        }""",
        FRAMES,
    )
    mark_at(page, 700)
    next_paint(page)
    final = page.evaluate(MARKS_PNG)
    # the kernel goes: its comm closes, and any send would throw
    page.evaluate("() => { window.attempts = 0; fake.send = () => { window.attempts++; throw new Error('no comm'); }; fake.emit('comm:close'); }")
    assert page.locator(ROOT).get_attribute("data-kernel") == "gone"
    assert page.locator(REPLAY).is_visible()

    page.click(f'{REPLAY} [data-action="replay"]')
    xs = page.evaluate(
        f"""() => new Promise((done) => {{
            const xs = [], el = document.querySelector('{REPLAY}');
            const tick = () => {{
                xs.push(({MARK_X})());
                if (el.dataset.state === 'playing') requestAnimationFrame(tick);
                else requestAnimationFrame(() => done(xs.concat([({MARK_X})()])));
            }};
            requestAnimationFrame(tick);
        }})"""
    )
    assert xs[0] is not None and xs[0] < 160, f"the replay starts from the first frame, got x = {xs[:3]}"
    assert all(b >= a - 1 for a, b in zip(xs, xs[1:])), f"the mark moves one way: {xs}"
    assert len({round(x) for x in xs}) > 10, f"the mark moves through the run: {xs}"
    assert abs(xs[-1] - 700) < 2, f"the replay ends on the final layout, got {xs[-1]}"

    # keyboard scrubbing: Home is the first frame, arrows step frames, End the final layout
    scrub = page.locator(f"{REPLAY} input[type=range]")
    scrub.focus()
    page.keyboard.press("Home")
    mark_at(page, 100)
    page.keyboard.press("ArrowRight")
    page.keyboard.press("ArrowRight")
    mark_at(page, 120)
    assert page.locator(REPLAY).get_attribute("data-state") == "paused"
    # hover finds the mark where the replay shows it
    page.click('[data-tool="select"]')
    page.locator(STAGE).hover()
    page.mouse.move(*to_page(page, 120, 250))
    tip = page.locator('[role="tooltip"]')
    tip.wait_for(state="visible")
    assert tip.inner_text() == "row 0"
    page.mouse.move(*to_page(page, 700, 250))
    tip.wait_for(state="hidden")
    scrub.focus()
    page.keyboard.press("End")
    mark_at(page, 700)
    next_paint(page)
    assert scrub.input_value() == str(FRAMES - 1)
    assert page.evaluate(MARKS_PNG) == final, "the end of the replay is the final layout, pixel for pixel"
    assert page.evaluate("window.attempts") == 0, "the replay sends nothing to the kernel"

    # a new run clears the recording: the control hides and the live frames show
    page.evaluate("() => { fake.push('status', 'running'); fake.push('frame_count', 0); fake.push('error', ''); }")
    assert page.locator(REPLAY).is_hidden()
