"""An honest status: stopped vs done, a full bar when a run ends, stale layouts, errors that
stay until fixed or dismissed, conflicting channels, frames that cannot be sent, the legend
trait, the notebook's static image, and odd inputs that get clear errors."""
from __future__ import annotations

import base64
import copy
import re

import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.design.bezier import fit_bezier
from unitopia_widget.layout.prepare.problem import Cancelled
from unitopia_widget.jupyter import notebook
from test_runner import assert_frame_is_layout, poll

pytestmark = pytest.mark.usefixtures("one_thread")


@pytest.fixture
def df():
    return pd.DataFrame({"v": [1.0, 2.0, 3.0, 4.0, 1.5, 2.5, 3.5, 0.5],
                         "k": ["a", "b", "a", "b", "a", "b", "a", "b"]})


def test_a_converged_run_is_done_with_a_full_bar_and_a_stopped_one_says_stopped(df):
    w = uw.UnitoPia(df, size="v", iterations=40)
    w.run(wait=True)
    assert w.status == "done" and w.progress["done"] is True
    w.layer(0).set(iterations=5000)
    w.run()
    poll(lambda: w.frame_count >= 2)
    assert w.status == "running" and w.progress["done"] is False
    w.stop()
    assert w.status == "stopped" and w.progress["done"] is True
    assert_frame_is_layout(w)


def test_a_design_change_marks_the_layout_stale_until_the_next_run(df):
    w = uw.UnitoPia(df, size="v", color="k", iterations=30)
    w.layer(0).set(color=None)
    assert w.stale is False                      # no layout yet: nothing to invalidate
    w.run(wait=True)
    assert w.stale is False
    w.title = "A title"                          # title, caption, legend: the layout stands
    assert w.stale is False
    design = copy.deepcopy(w.design)
    design["layers"][0]["encodings"]["size"] = None
    w.design = design                            # a front-end edit that changes the layout
    assert w.stale is True
    design["layers"][0]["encodings"]["size"] = "v"
    w.design = design                            # undone: the shown layout is right again
    assert w.stale is False
    w.layer(0).set(margin=0.2)
    assert w.stale is True
    w.run(wait=True)
    assert w.stale is False


def test_binding_width_never_silently_unbinds_size(df):
    w = uw.UnitoPia(df, size="v", iterations=20)
    design = copy.deepcopy(w.design)
    design["layers"][0]["encodings"]["width"] = "v"
    w.design = design
    assert w.layer(0).encodings["size"] == "v" and w.layer(0).encodings["width"] is None
    assert "size='v' cannot be combined with width='v'" in w.error
    with pytest.raises(ValueError, match="size='v' cannot be combined with width='v'"):
        w.layer(0).set(width="v")
    assert w.layer(0).encodings["size"] == "v"


def test_errors_stay_until_fixed_or_dismissed(df):
    w = uw.UnitoPia(df, size="v", iterations=20)
    bad = copy.deepcopy(w.design)
    bad["layers"][0]["encodings"]["size"] = "nope"
    w.design = bad
    assert "size='nope'" in w.error
    w.title = "unrelated"                        # a Python-side change leaves it shown
    assert "size='nope'" in w.error
    good = copy.deepcopy(w.design)
    good["layers"][0]["encodings"]["margin"] = 0.1
    w.design = good                              # an accepted edit: the design is good again
    assert w.error == ""
    w.design = bad
    w._on_message(w, {"type": "dismiss-error"}, [])
    assert w.error == ""


def test_a_frame_that_cannot_be_sent_ends_the_run_as_an_error_keeping_its_layout(df, monkeypatch):
    import zmq
    w = uw.UnitoPia(df, size="v", iterations=5000)
    sent = []

    def send_state(key=None):
        if key == "frame" or (isinstance(key, (list, set, tuple)) and "frame" in key):
            sent.append(key)
            if len(sent) > 2:
                raise zmq.ZMQError(88, "Socket operation on non-socket")
    monkeypatch.setattr(w, "send_state", send_state)
    with pytest.warns(RuntimeWarning, match="a frame could not be sent"):
        w.run(wait=True)
    assert not w._runner.running
    assert w.status == "error" and "ZMQError" in w.error and "Socket operation" in w.error
    assert w.placements is not None and len(w.placements) == len(df)
    assert w._chart.result.cancelled                          # ended at once, not after 5000
    assert w.wait() is w.placements


def test_the_legend_trait_is_a_sanitised_image_updated_after_runs_and_edits(df):
    w = uw.UnitoPia(df, size="v", color="k", iterations=20)
    assert w.legend_image["src"].startswith("data:image/svg+xml;base64,")
    svg = base64.b64decode(w.legend_image["src"].split(",", 1)[1]).decode()
    assert 'data-channel="color"' in svg and "<script" not in svg
    assert w.legend_image["width"] > 0 and w.legend_image["height"] > 0
    w.run(wait=True)
    after_run = w.legend_image["src"]
    w.layer(0).set(color=None)
    assert 'data-channel="color"' not in base64.b64decode(w.legend_image["src"].split(",", 1)[1]).decode()
    assert w.legend_image["src"] != after_run
    w.legend = False
    assert w.legend_image == {}


def test_the_static_output_shows_the_chart_trusted_or_not(df, monkeypatch):
    w = uw.UnitoPia(df, size="v", iterations=20)
    data, _ = w._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in data
    view_text = "UnitoPia chart: 8 rows in 1 layer(s) (the live widget; its image follows)"
    assert data["text/plain"] == view_text              # no run state in it that would go stale
    before = w._static.bundle()
    assert "not laid out yet" in before["text/plain"] and "image/png" not in before
    assert before["image/svg+xml"].startswith('<svg class="unitopia-static" ')
    w.run(wait=True)
    assert w._repr_mimebundle_()[0]["text/plain"] == view_text
    data = w._static.bundle()
    # JupyterLab shows an untrusted output in its first safe type by rank, and sanitised
    # text/html is safe and ranks before image/png: the bundle holds none
    assert set(data) == {"text/plain", "image/svg+xml", "image/png"}
    assert data["text/plain"] == "UnitoPia chart: 8 rows in 1 layer(s), status done"
    svg = data["image/svg+xml"]
    assert svg.startswith('<svg class="unitopia-static" ')   # what the widget's CSS hides
    assert svg.count('class="unit"') == len(df)
    ids = re.findall(r'id="([^"]+)"', svg)
    refs = re.findall(r'href="#([^"]+)"', svg)
    assert ids and set(refs) <= set(ids) and all(i.startswith("c") for i in ids)
    assert base64.b64decode(data["image/png"])[:8] == b"\x89PNG\r\n\x1a\n"
    state = w.get_state()                        # what a saved notebook keeps of the widget
    assert len(state["frame"]) == 16 * len(df) and len(state["units"]) == 16 * len(df)
    assert state["marks"] and state["status"] == "done"

    monkeypatch.setattr(notebook, "SVG_BYTES", len(svg) - 1)   # a chart too large to draw as SVG
    big = w._static.bundle()
    assert big["image/svg+xml"].startswith('<svg class="unitopia-static" ')
    assert 'class="unit"' not in big["image/svg+xml"]
    assert f'href="data:image/png;base64,{big["image/png"]}"' in big["image/svg+xml"]
    monkeypatch.undo()

    def fails(scale):
        raise ValueError("SVG data parsing failed cause nodes limit reached")

    w._chart.to_png = fails   # a PNG that cannot be drawn: said, and no older image kept
    with pytest.warns(RuntimeWarning, match="its PNG could not be drawn: ValueError: SVG data"):
        data = w._static.bundle()
    assert set(data) == {"text/plain", "image/svg+xml"}
    assert data["text/plain"].endswith("its PNG could not be drawn: ValueError: SVG data parsing "
                                       "failed cause nodes limit reached")


def test_progress_starts_afresh_at_each_run(df):
    w = uw.UnitoPia(df, size="v", iterations=30)
    w.run(wait=True)
    assert w.progress["iteration"] > 0 and w.progress["done"]

    def stopped_before_its_first_step(**kwargs):
        raise Cancelled("stopped")

    w._chart.layout = stopped_before_its_first_step
    w.run(wait=True)
    assert w.status == "stopped"
    assert w.progress == {"iteration": 0, "max_iterations": 30, "loss": None, "done": True,
                          "stopped": True}


def test_a_sketch_too_large_to_draw_is_blamed_at_load_time():
    with pytest.raises(ValueError, match=r"sketch \(width 1e\+300, points spanning 10 x 10\): draws nothing"):
        uw.Mark.sketch([[[0, 0], [10, 5], [0, 10]]], width=1e300)
    with pytest.raises(ValueError, match=r"sketch .*: a mark 1e\+300 x 11 is more than 1e\+06 times wider"):
        uw.Mark.sketch([[[0, 0], [1e300, 5], [0, 10]]], width=1)


# --- odd inputs ------------------------------------------------------------------------

def test_long_layer_names_are_refused(df):
    with pytest.raises(ValueError, match="layer name is 10000 characters long.*at most 200"):
        uw.Chart(df).add_layer("x" * 10_000)
    c = uw.Chart(df)
    with pytest.raises(ValueError, match="layer name is 201 characters long"):
        c.layer(0).set(name="n" * 201)
    assert c.layer(0).name == "layer-1"


def test_colour_on_a_column_of_dicts_names_the_argument():
    df = pd.DataFrame({"v": [1.0, 2.0], "d": [{"a": 1}, {"b": 2}]})
    with pytest.raises(TypeError, match="color='d': the column's values must be categories.*dict"):
        uw.Chart(df, color="d")


def test_order_on_unorderable_objects_names_the_argument():
    df = pd.DataFrame({"v": [1.0, 2.0, 3.0], "o": [object(), object(), object()]})
    with pytest.raises(TypeError, match="order='o': the column's values cannot be put in order"):
        uw.Chart(df, order="o")


def test_a_stroke_with_a_nan_point_is_not_called_coincident():
    with pytest.raises(ValueError, match=r"stroke: point 1 is \[nan, 3.0\], not finite"):
        fit_bezier([[0, 0], [float("nan"), 3], [10, 10]])


def test_a_one_pixel_container_box_is_refused(df):
    mask = np.ones((4, 4), bool)
    with pytest.raises(ValueError, match="holds 1 px\\^2 for 8 marks, so each mark would be under 2 px"):
        uw.Chart(df, container=uw.Container.image(mask, box=(10, 10, 1, 1)))


def test_the_png_export_button_renders_the_whole_page_with_its_legend(df):
    from PIL import Image
    import io
    w = uw.UnitoPia(df, size="v", color="k", iterations=20, title="T")
    w.run(wait=True)
    sent = []
    w.send = lambda msg, buffers=None: sent.append(msg)
    w._on_message(w, {"type": "export", "format": "png"}, [])
    png = base64.b64decode(sent[0]["data"].split(",", 1)[1])
    width, height = Image.open(io.BytesIO(png)).size
    view = [float(v) for v in re.search(r'viewBox="([^"]+)"', w.to_svg()).group(1).split()]
    assert width == pytest.approx(2 * view[2], abs=3) and height == pytest.approx(2 * view[3], abs=3)
    assert width > 1600                                       # the canvas and its legend


def test_saving_a_stale_layout_warns_and_saving_during_a_run_names_wait(df, tmp_path):
    import warnings
    w = uw.UnitoPia(df, size="v", iterations=30)
    w.run(wait=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        w.save(tmp_path / "fresh.svg")               # a current layout: no warning
    w.layer(0).set(margin=0.2)
    with pytest.warns(UserWarning, match=r"stale layout.*w\.run\(wait=True\)"):
        w.save(tmp_path / "old.svg")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        w.save(tmp_path / "design.json")             # the design itself is never stale
    w.layer(0).set(iterations=5000)
    w.run()
    try:
        with pytest.raises(RuntimeError, match=r"while the layout is running: call w\.wait\(\)"):
            w.save(tmp_path / "running.png")
    finally:
        w.stop()


def test_the_progress_says_the_phase_and_the_run_time_not_only_the_loss(df):
    w = uw.UnitoPia(df, size="v", iterations=40)
    seen = []
    w.observe(lambda change: seen.append(dict(change["new"])), names="progress")
    w.run(wait=True)
    phases = {p.get("phase") for p in seen if not p["done"]} - {None}   # None: the start
    assert phases and phases <= {"settle", "polish"}
    final = w.progress
    assert final["done"] and not final["stopped"]
    assert final["seconds"] == pytest.approx(w._chart.result.seconds)   # the whole run
