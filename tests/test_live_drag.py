"""Live drag (issue 49, item 2): "drag" messages from the Select tool pin the dragged marks
and reflow warm while the pointer moves, streaming frames; a newer message supersedes the
running reflow (the latest position wins, nothing queues); the drop ("pin") ends with the
usual final layout (``jupyter/drag.py``)."""
from __future__ import annotations

import os
import sys
import threading
import time

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.jupyter.drag import DRAG_STEPS
from unitopia_widget.jupyter.runner import BACKGROUND_NICE
from unitopia_widget.layout import engine

CENTRE = (200.0, 150.0)


@pytest.fixture(scope="module")
def laid():
    df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1.0, 10.0, 150)})
    w = uw.UnitoPia(df, size="v", container=uw.Container.ellipse(*CENTRE, 120, 120),
                    canvas=(400, 300), device="cpu")
    w.run(wait=True)
    return w


def widget(laid):
    """A widget laid out as ``laid`` (its chart's layout copied, not run again)."""
    w = uw.UnitoPia(laid.df, size="v", container=uw.Container.ellipse(*CENTRE, 120, 120),
                    canvas=(400, 300), device="cpu")
    chart = w._chart
    for name in ("laid", "_snapshot", "_origin", "_ran"):
        setattr(chart, name, getattr(laid._chart, name))
    w._laid_out, w.frame, w.status = laid._laid_out, laid.frame, "done"
    return w


def frame_of(w) -> np.ndarray:
    return np.frombuffer(w.frame, dtype=np.float32).reshape(-1, 4)


def wait_idle(w, timeout=60.0):
    end = time.monotonic() + timeout
    while w._drag_worker is not None or w._runner.running:
        assert time.monotonic() < end, "timed out"
        time.sleep(0.01)


def path(w, steps, step_px=4.0):
    """Unit 0's place and ``steps`` positions towards the container's centre."""
    x0, y0 = frame_of(w)[0, :2].astype(float)
    d = np.array(CENTRE) - (x0, y0)
    d = d / np.hypot(*d) * step_px
    return (x0, y0), [(x0 + d[0] * k, y0 + d[1] * k) for k in range(1, steps + 1)]


def drag(w, x, y, kind="drag"):
    w._on_message(w, {"type": kind, "units": [0], "x": [round(x, 2)], "y": [round(y, 2)]}, [])


def test_dragging_a_mark_reflows_its_neighbours_while_it_moves_and_the_drop_lays_out(laid, monkeypatch):
    w = widget(laid)
    static = []
    monkeypatch.setattr(w._static, "update", lambda: static.append(w.status))
    frames = []
    w.observe(lambda c: frames.append(frame_of(w).copy()), "frame")
    start, moves = path(w, 12)
    for x, y in moves:                 # a pointer move every 100 ms, the widget's throttle
        drag(w, x, y)
        time.sleep(0.1)
    during = list(frames)
    drag(w, *moves[-1], kind="pin")
    wait_idle(w)
    assert not w.error
    others = [k for k in range(1, len(during)) if len(during[k]) == len(during[k - 1])
              and np.abs(during[k][1:, :2] - during[k - 1][1:, :2]).max() > 0.01]
    assert len(others) >= 3, f"only {len(others)} streamed frames moved the other marks"
    assert w.status == "done" and not w.stale, "the drop ends with the final layout"
    assert not w._chart.result.cancelled, "the drop's run is not cut by a drag message"
    assert w.placements[["x", "y"]].iloc[0].tolist() == pytest.approx(moves[-1], abs=0.01)
    np.testing.assert_allclose(frame_of(w)[:, :2], w.placements[["x", "y"]], atol=1e-3)
    assert static == ["done"], "only the drop's run refreshes the notebook's static image"
    assert len(w.pinned) == 1


def test_a_newer_drag_supersedes_the_running_reflow_and_nothing_queues(laid, monkeypatch):
    w = widget(laid)
    chart, real = w._chart, w._chart.layout
    started, release, runs = threading.Event(), threading.Event(), []

    def layout(on_frame, **kwargs):    # the first run waits while nine more messages arrive
        runs.append(float(chart.pinned.x.iloc[0]))
        if len(runs) == 1:
            started.set()
            assert release.wait(30)
        frames = []                    # a run may end only once it offered DRAG_STEPS frames

        def offered(*frame):
            frames.append(1)
            on_frame(*frame)
        placements = real(on_frame=offered, **kwargs)
        # cut short, or over before it could be (a reflow offers a frame a step, and its last)
        runs[-1] = (runs[-1], chart.result.cancelled or len(frames) <= DRAG_STEPS + 1)
        return placements
    monkeypatch.setattr(chart, "layout", layout)
    _, moves = path(w, 10)
    drag(w, *moves[0])
    assert started.wait(30)
    for x, y in moves[1:]:
        drag(w, x, y)
    release.set()
    wait_idle(w)
    assert len(runs) == 2, f"the waiting messages were run one by one: {runs}"
    assert runs[0][0] == pytest.approx(moves[0][0], abs=0.01)
    assert runs[0][1], "the first reflow was cut short by the newer position after its first steps"
    assert runs[1] == (pytest.approx(moves[-1][0], abs=0.01), False), "the newest position won"
    assert w.placements.x.iloc[0] == pytest.approx(moves[-1][0], abs=0.01)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="per-thread nice is Linux's")
def test_the_runs_that_answer_a_drag_keep_the_kernels_priority_and_a_plain_run_yields(laid, monkeypatch):
    w = widget(laid)
    mine = os.getpriority(os.PRIO_PROCESS, threading.get_native_id())
    chart, real, seen = w._chart, w._chart.layout, []

    def layout(**kwargs):
        seen.append(os.getpriority(os.PRIO_PROCESS, threading.get_native_id()))
        return real(**kwargs)
    monkeypatch.setattr(chart, "layout", layout)
    _, moves = path(w, 2)
    drag(w, *moves[0])
    wait_idle(w)
    drag(w, *moves[1], kind="pin")
    wait_idle(w)
    w.run(wait=True)
    assert seen == [mine, mine, min(19, mine + BACKGROUND_NICE)]


def test_a_drag_outside_the_container_is_reported_and_the_drag_goes_on(laid):
    w = widget(laid)
    drag(w, 5.0, 5.0)
    wait_idle(w)
    assert "outside the container" in w.error
    _, moves = path(w, 2)
    drag(w, *moves[-1], kind="pin")
    wait_idle(w)
    assert w.status == "done" and not w.error


def pulling(df):
    """A widget of ``df`` in an open container, pulled by a point force left of its centre."""
    return uw.UnitoPia(df, size="v", container=uw.Container.ellipse(*CENTRE, 120, 120),
                       canvas=(400, 300), device="cpu", boundary="open", fill=0.15,
                       forces=[uw.PointForce(160.0, 150.0)])


@pytest.fixture(scope="module")
def pulled():
    w = pulling(pd.DataFrame({"v": np.random.default_rng(1).uniform(1.0, 10.0, 150)}))
    w.run(wait=True)
    return w


def near(table, at) -> float:
    """The marks' median distance to ``at``, px."""
    return float(np.median(np.hypot(table.x - at[0], table.y - at[1])))


def force(w, x, y, final=False):
    w._on_message(w, {"type": "force", "layer": 0, "index": 0, "x": round(x, 2), "y": round(y, 2),
                      "final": final}, [])


def test_dragging_a_point_force_reflows_every_mark_while_it_moves_and_the_drop_lays_out(pulled, monkeypatch):
    w = pulling(pulled.df)
    chart = w._chart
    for name in ("laid", "_snapshot", "_origin", "_ran"):
        setattr(chart, name, getattr(pulled._chart, name))
    w._laid_out, w.frame, w.status = pulled._laid_out, pulled.frame, "done"
    built = []
    real = engine.build_problem
    monkeypatch.setattr(engine, "build_problem", lambda *a, **k: built.append(1) or real(*a, **k))
    frames = []
    w.observe(lambda c: frames.append(frame_of(w).copy()), "frame")
    before = near(pulled.placements, (232.0, 150.0))
    moves = [(160.0 + 6 * k, 150.0) for k in range(1, 13)]
    for x, y in moves:                 # a pointer move every 100 ms, the widget's throttle
        force(w, x, y)
        time.sleep(0.1)
    during = list(frames)
    force(w, *moves[-1], final=True)
    wait_idle(w)
    assert not w.error
    moving = [k for k in range(1, len(during))
              if np.abs(during[k][:, :2] - during[k - 1][:, :2]).max() > 0.01]
    assert len(moving) >= 5, f"only {len(moving)} streamed frames moved the marks"
    assert w.status == "done" and not w.stale and not chart.result.cancelled, \
        "the drop ends with the final layout"
    assert w.layers[0].forces[0] == uw.PointForce(*moves[-1])
    assert w.design["layers"][0]["forces"][0]["x"] == pytest.approx(moves[-1][0])
    assert near(w.placements, moves[-1]) < before - 15, "the marks followed the force"
    assert built == [], "each run reused the last problem: no fields or sprites made again"


def test_a_force_message_for_no_point_force_is_reported(pulled):
    w = pulling(pulled.df)
    w._on_message(w, {"type": "force", "layer": 0, "index": 3, "x": 1.0, "y": 2.0}, [])
    wait_idle(w)
    assert "index must be the index of a point force of layer" in w.error
