"""Tests for uw.Story (story.py, output/transition.py, output/story_film.py,
output/story_page.py): units keep their row identity across slides, move continuously,
fade in and out, and the story saves as a film, one HTML page and its design JSON."""
import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from PIL import Image, ImageSequence

import unitopia_widget as uw
from unitopia_widget.design.scene import Mark
from unitopia_widget.output import transition
from unitopia_widget.output.export import png_array
from unitopia_widget.output.story_film import union_view

DATA = Path(__file__).parent / "data" / "marks"
PLAYER = Path(__file__).resolve().parents[1] / "js" / "src" / "story-player.js"
HOSTILE = '<img src=x onerror="alert(1)"></script><script>alert(2)</script>'
CANVAS = (200, 120)

pytestmark = pytest.mark.usefixtures("one_thread")


@pytest.fixture(scope="module")
def story():
    """Three small slides: all ten rows; rows 0-7 in two layers; rows 2-9 with another mark."""
    rng = np.random.default_rng(5)
    df = pd.DataFrame({"v": rng.uniform(1, 4, 10), "k": ["a", "b"] * 4 + [HOSTILE] * 2},
                      index=[f"r{i}" for i in range(10)])
    look = dict(size="v", iterations=20, canvas=CANVAS)
    slides = [uw.Chart(df, mark="circle", color="k", **look),
              uw.Chart(df.iloc[:8], mark="star", color="k", by="k", **look),
              uw.Chart(df.iloc[2:], mark=Mark.svg((DATA / "hostile.svg").read_text()), color="v",
                       rotate=True, **look)]
    return uw.Story(slides, titles=["All", "By kind", "Hostile <b>marks</b>"]).run()


def _rows(chart, index):
    return [chart.placements["row"].iloc[i] if i >= 0 else None for i in index]


def test_units_keep_their_row_across_slides(story):
    for k, p in enumerate(story.plans()):
        a, b = story.charts[k], story.charts[k + 1]
        ra, rb = _rows(a, p.a), _rows(b, p.b)
        both = [(x, y) for x, y in zip(ra, rb) if x is not None and y is not None]
        assert both and all(x == y for x, y in both)
        common = set(a.placements["row"]) & set(b.placements["row"])
        assert {x for x, _ in both} == common
        assert {x for x, y in zip(ra, rb) if y is None} == set(a.placements["row"]) - common
        assert {y for x, y in zip(ra, rb) if x is None} == set(b.placements["row"]) - common
    first, second = story.plans()
    assert {r for r, o in zip(_rows(story.charts[0], first.a), first.b) if o < 0} == {"r8", "r9"}
    assert {r for r, o in zip(_rows(story.charts[1], second.a), second.b) if o < 0} == {"r0", "r1"}


def test_a_row_drawn_twice_is_two_units_matched_in_order():
    assert transition.unit_keys(["x", "y", "x"]) == [("x", 0), ("y", 0), ("x", 1)]


def test_no_unit_jumps_more_than_five_percent_of_the_canvas(story):
    states = [transition.slide_states(c.placements) for c in story.charts]
    for k, p in enumerate(story.plans()):
        sa, sb = states[k], states[k + 1]
        count = transition.frame_count(p, sa, sb, CANVAS, 10)
        frames = [transition.at(p, sa, sb, t) for t in np.linspace(0, 1, count)]
        xy = np.stack([np.concatenate([fa[:, :2], fb[:, :2]]) for fa, fb in frames])
        jump = np.hypot(*np.diff(xy, axis=0).transpose(2, 0, 1)).max()
        assert jump <= 0.05 * min(CANVAS)
        assert np.hypot(*(xy[-1] - xy[0]).T).max() > 0.2 * min(CANVAS)   # the units did travel
        # the ends are the slides: each unit where its slide draws it, at full opacity
        start, end = frames[0][0], frames[-1][1]
        np.testing.assert_allclose(start[p.a >= 0, :5], sa[p.a[p.a >= 0]], atol=1e-9)
        np.testing.assert_allclose(end[p.b >= 0, :5], sb[p.b[p.b >= 0]], atol=1e-9)
        assert (start[p.a >= 0, 5] == 1).all() and (end[p.b >= 0, 5] == 1).all()


def test_leaving_units_fade_out_entering_fade_in_in_place_and_starts_are_staggered(story):
    sa, sb = (transition.slide_states(c.placements) for c in story.charts[:2])
    p = story.plans()[0]
    ts = np.linspace(0, 1, 11)
    frames = [transition.at(p, sa, sb, t) for t in ts]
    leaving = np.flatnonzero(p.b < 0)
    alpha = np.array([f[0][leaving, 5] for f in frames])
    assert (alpha[0] == 1).all() and (alpha[-1] == 0).all() and (np.diff(alpha, axis=0) <= 0).all()
    assert all(np.allclose(f[0][leaving, :5], sa[p.a[leaving]]) for f in frames)   # in place
    assert all((f[1][leaving, 5] == 0).all() for f in frames)
    sc = transition.slide_states(story.charts[2].placements)
    q = story.plans()[1]
    entering = np.flatnonzero(q.a < 0)
    alpha = np.array([transition.at(q, sb, sc, t)[1][entering, 5] for t in ts])
    assert (alpha[0] == 0).all() and (alpha[-1] == 1).all() and (np.diff(alpha, axis=0) >= 0).all()
    # staggered from left to right: early on, the leftmost unit has gone further than the rightmost
    u = transition.progress(p, 0.4)
    x = np.where(p.a >= 0, sa[np.maximum(p.a, 0), 0], sb[np.maximum(p.b, 0), 0])
    assert u[np.argmin(x)] > u[np.argmax(x)]


def test_a_changed_mark_cross_fades_and_a_recolour_is_covered():
    keys = [("r", 0)]
    sa = np.array([[10.0, 10, 350, 8, 8]])
    sb = np.array([[50.0, 10, 10, 16, 8]])
    same = transition.plan(keys, keys, sa, sb, ["star"], ["star"])
    other = transition.plan(keys, keys, sa, sb, ["star"], ["circle"])
    assert not same.fade[0] and other.fade[0]
    mid_same, mid_other = transition.at(same, sa, sb, 0.6), transition.at(other, sa, sb, 0.6)
    u = transition.progress(same, 0.6)[0]
    assert mid_same[0][0, 5] == 1 and mid_same[1][0, 5] == pytest.approx(u)   # new colour over the old
    assert mid_other[0][0, 5] == pytest.approx(1 - u) and mid_other[1][0, 5] == pytest.approx(u)
    assert 350 < mid_same[0][0, 2] or mid_same[0][0, 2] < 370   # the short way round, through 0
    assert mid_same[0][0, 3] == pytest.approx(8 + 8 * u)          # size interpolated


def test_the_browser_player_moves_units_as_the_film_does(story, tmp_path):
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node to run js/src/story-player.js")
    probe = tmp_path / "probe.mjs"
    probe.write_text(f"import {{ transitionAt }} from {json.dumps(PLAYER.as_uri())};\n"
                     "let text = ''; process.stdin.on('data', d => text += d);\n"
                     "process.stdin.on('end', () => { const {data, times} = JSON.parse(text);\n"
                     "  const out = data.transitions.map((_, k) => times.map(t => { const got = [];\n"
                     "    transitionAt(data, k, t, (side, i, s, a) => got.push([side, i, ...s, a]));\n"
                     "    return got; }));\n"
                     "  process.stdout.write(JSON.stringify(out)); });\n")
    times = [0.0, 0.3, 0.55, 0.8, 1.0]
    run = subprocess.run([node, str(probe)], input=json.dumps({"data": story.player(), "times": times}),
                         capture_output=True, text=True, timeout=60, check=True)
    got = json.loads(run.stdout)
    states = [transition.slide_states(c.placements) for c in story.charts]
    for k, p in enumerate(story.plans()):
        for t, drawn in zip(times, got[k]):
            now_a, now_b = transition.at(p, states[k], states[k + 1], t)
            want = [[0, int(p.a[m]), *now_a[m]] for m in range(len(p.a)) if p.a[m] >= 0]
            want += [[1, int(p.b[m]), *now_b[m]] for m in range(len(p.b)) if p.b[m] >= 0]
            key = lambda r: (r[0], r[1])   # noqa: E731
            np.testing.assert_allclose(sorted(drawn, key=key), sorted(want, key=key), atol=0.01)


@pytest.fixture(scope="module")
def film(story, tmp_path_factory):
    path = tmp_path_factory.mktemp("film") / "story.gif"
    story.save(path, fps=10, hold=0.5, seconds=1)
    return path


def test_the_gif_holds_each_slide_and_plays_the_transitions(story, film):
    states = [transition.slide_states(c.placements) for c in story.charts]
    moving = sum(transition.frame_count(p, states[k], states[k + 1], CANVAS, 10) - 2
                 for k, p in enumerate(story.plans()))
    with Image.open(film) as im:   # identical frames are merged: count the time instead
        frames = [(f.convert("RGB"), f.info["duration"]) for f in ImageSequence.Iterator(im)]
    assert sum(d for _, d in frames) == pytest.approx((3 * 5 + moving) * 100, abs=20)
    assert len(frames) >= 20
    svg = story.charts[2].to_svg(title=story.titles[2])
    x, y, w, h = union_view([c.to_svg(title=t) for c, t in zip(story.charts, story.titles)])
    framed = re.sub(r'width="[^"]*" height="[^"]*" viewBox="[^"]*"',
                    f'width="{w:g}" height="{h:g}" viewBox="{x:g} {y:g} {w:g} {h:g}"', svg, count=1)
    want = png_array(framed, (w, h))
    a = want[..., 3:4].astype(float) / 255
    want = want[..., :3] * a + 255 * (1 - a)
    last = np.asarray(frames[-1][0], dtype=float)[:want.shape[0], :want.shape[1]]
    assert np.abs(last - want).mean() / 255 <= 0.02


def test_the_mp4_has_every_frame(story, tmp_path):
    av = pytest.importorskip("av")
    two = uw.Story(story.charts[1:])
    sa, sb = (transition.slide_states(c.placements) for c in two.charts)
    moving = transition.frame_count(two.plans()[0], sa, sb, CANVAS, 10) - 2
    path = tmp_path / "story.mp4"
    two.save(path, fps=10, hold=0.2, seconds=1)
    with av.open(str(path)) as box:
        assert sum(1 for _ in box.decode(video=0)) == 2 * 2 + moving


def test_the_story_json_round_trips_and_a_loaded_story_asks_for_run(story, tmp_path):
    path = tmp_path / "story.json"
    story.save(path)
    df = story.charts[0].df
    loaded = uw.Story.load(path, df)
    assert loaded.to_json() == story.to_json()
    assert [c.design() for c in loaded.charts] == [c.design() for c in story.charts]
    assert [c.df.index.tolist() for c in loaded.charts] == [c.df.index.tolist() for c in story.charts]
    with pytest.raises(ValueError, match=r"df lacks 2 of the 10 rows of story slides\[0\]"):
        uw.Story.load(path, df.iloc[:8])
    with pytest.raises(ValueError, match=r"df is a list of 2 DataFrames for a story of 3 slides"):
        uw.Story.load(path, [df, df])
    with pytest.raises(RuntimeError, match=r"slides\[0\] has no layout yet: call story.run\(\)"):
        loaded.save(tmp_path / "story.html")
    path.write_text('{"schema": "unitopia-story", "version": 1, "slides": [{"rows": ["r0"], "design": {}}]}')
    with pytest.raises(ValueError, match=r"story slides\[0\]: not a unitopia design"):
        uw.Story.load(path, df)
    path.write_text("{")
    with pytest.raises(ValueError, match="story file .* is not valid JSON"):
        uw.Story.load(path, df)


def test_bad_input_is_named(story, tmp_path):
    c = story.charts[0]
    with pytest.raises(ValueError, match="slides is empty"):
        uw.Story([])
    with pytest.raises(TypeError, match=r"slides\[1\] is a str, not a chart"):
        uw.Story([c, "slide"])
    with pytest.raises(ValueError, match=r"titles has 1 entries for 2 slides"):
        uw.Story([c, c], titles=["one"])
    other = uw.Chart(c.df, canvas=(300, 120))
    with pytest.raises(ValueError, match=r"slides\[1\] has a 300 x 120 canvas and slides\[0\] a "
                                         r"200 x 120 one"):
        uw.Story([c, other])
    with pytest.raises(ValueError, match=r"seconds must be a number of seconds in \(0, 10\]"):
        uw.Story([c], seconds=0)
    with pytest.raises(ValueError, match=r"fps, hold and seconds are for a film"):
        story.save(tmp_path / "s.html", fps=10)
    with pytest.raises(ValueError, match=r"a story is saved as .html, .json"):
        story.save(tmp_path / "s.svg")


@pytest.mark.browser
def test_the_page_plays_offline_with_tooltips_and_the_next_button_moves_units(browser, story,
                                                                             tmp_path):
    path = tmp_path / "story.html"
    seconds, story.seconds = story.seconds, 2.0   # long enough to catch mid-way on a busy machine
    try:
        story.save(path)
    finally:
        story.seconds = seconds
    text = path.read_text()
    assert "onerror" not in text.split('id="story-data">')[0] and "<script>alert" not in text
    context = browser.new_context(offline=True)
    page = context.new_page()
    requests, dialogs, errors = [], [], []
    page.on("request", lambda r: requests.append(r.url))
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(path.as_uri())
    page.wait_for_selector("#story .story-next")
    shown = """() => [...document.querySelectorAll('#story .story-units')]
      .filter(h => h.style.display !== 'none')
      .map(h => [...h.shadowRoot.querySelectorAll('.story-root > g.unit')].map(g => [
        g.querySelector('title').textContent, g.getAttribute('transform'), g.getBoundingClientRect().width]))"""

    def state():   # the page's policy forbids eval, so poll from here
        return page.eval_on_selector("#story", "el => [el.dataset.slide, el.dataset.moving]")

    def settle(slide):
        for _ in range(300):
            if state() == [slide, "0"]:
                return
            page.wait_for_timeout(50)
        raise AssertionError(f"the story did not settle on slide {slide}: {state()}")

    first = page.evaluate(shown)
    assert len(first) == 1 and len(first[0]) == len(story.charts[0].placements)
    assert all(t.strip() and w > 0 for t, _, w in first[0])         # every unit drawn, with its tooltip
    assert any("onerror" in t for t, _, _ in first[0])              # hostile text shown as text
    page.click("#story .story-next")
    page.wait_for_timeout(150)
    assert state()[1] == "1"
    moving = page.evaluate(shown)
    assert len(moving) == 2                                           # both slides' units drawn
    settle("1")
    after = page.evaluate(shown)
    assert len(after) == 1 and len(after[0]) == len(story.charts[1].placements)
    assert [t for _, t, _ in moving[0]] != [t for _, t, _ in first[0]]   # units moved between
    page.keyboard.press("ArrowRight")
    settle("2")
    assert page.evaluate("document.scripts.length") == 2
    assert not dialogs and not errors and requests == [path.as_uri()]
    context.close()


def test_the_story_widget_carries_the_player_and_keeps_the_speed(story):
    from traitlets import TraitError

    w = story.widget()
    assert [len(s["units"]) for s in w.story["slides"]] == [len(c.placements) for c in story.charts]
    assert len(w.story["transitions"]) == 2 and w.seconds == story.seconds
    try:
        w.seconds = 2.5
        assert story.seconds == 2.5
    finally:
        w.seconds = 1.0
    with pytest.raises(TraitError, match=r"index must be a slide number in \[0, 3\), got 3"):
        w.index = 3
    data, _ = story._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in data
    assert data["text/plain"].startswith("<Story of 3 slides (10, 8, 8 rows): All / By kind")


def test_a_story_of_widgets_lays_them_out_and_reads_their_charts():
    df = pd.DataFrame({"v": np.linspace(1, 3, 6)})
    slides = [uw.UnitoPia(df, size="v", iterations=20, canvas=CANVAS),
              uw.UnitoPia(df.iloc[2:], size="v", mark="star", iterations=20, canvas=CANVAS)]
    story = uw.Story(slides).run()
    assert all(w.placements is not None and w.status == "done" for w in slides)
    assert story.charts == [w._chart for w in slides]
    p = story.plans()[0]
    assert (p.b < 0).sum() == 2 and (p.a < 0).sum() == 0
