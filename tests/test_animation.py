"""Tests for unitopia_widget.output.animation and layout.frames: the settling kept and
exported as GIF, WebP, MP4 and WebM whose last frame is the final layout."""
import sys

import numpy as np
import pandas as pd
import pytest
from PIL import Image, ImageSequence

import unitopia_widget as uw
from unitopia_widget.output.export import svg_size
from unitopia_widget.layout.frames import Frames
from unitopia_widget.output.export import png_array

pytestmark = pytest.mark.usefixtures("one_thread")


@pytest.fixture(scope="module")
def chart():
    rng = np.random.default_rng(3)
    df = pd.DataFrame({"v": rng.uniform(1, 4, 40), "g": rng.choice(["a", "b", "c"], 40)})
    c = uw.Chart(df, mark="star", size="v", color="g", rotate=True, iterations=40,
                 canvas=(320, 200), title="Stars settling")
    c.layout()
    return c


def _white(rgba: np.ndarray) -> np.ndarray:
    a = rgba[..., 3:4].astype(float) / 255
    return rgba[..., :3] * a + 255 * (1 - a)


def test_frames_bounded_even_and_end_on_final():
    kept = Frames(limit=10)
    for i in range(1000):
        kept.add(np.full((3, 4), i, np.float32))
    out = kept.finish(np.full((3, 4), -1, np.float32))
    assert len(out) <= 10 and out[-1, 0, 0] == -1
    steps = np.diff(out[:-1, 0, 0])
    assert steps.min() == steps.max() > 1   # evenly subsampled over the whole run


def test_chart_keeps_the_runs_frames(chart):
    assert chart.frames.ndim == 3 and chart.frames.shape[1:] == (40, 4) and len(chart.frames) > 5
    np.testing.assert_allclose(chart.frames[-1, :, :2], chart.placements[["x", "y"]], atol=1e-3)
    assert np.abs(chart.frames[0, :, :2] - chart.frames[-1, :, :2]).max() > 5   # it moved


@pytest.mark.parametrize("ext", [".gif", ".webp", ".mp4", ".webm"])
def test_last_frame_is_the_png_export(chart, tmp_path, ext):
    if ext in (".mp4", ".webm"):
        av = pytest.importorskip("av")
    path = tmp_path / f"settle{ext}"
    chart.save(path, fps=10, seconds=2.5)
    if ext in (".mp4", ".webm"):
        with av.open(str(path)) as box:
            images = [f.to_ndarray(format="rgb24") for f in box.decode(video=0)]
    else:
        images = [np.array(f.convert("RGB")) for f in ImageSequence.Iterator(Image.open(path))]
    assert len(images) >= 20
    svg = chart.to_svg()
    want = _white(png_array(svg, svg_size(svg)))
    h, w = want.shape[:2]
    first, last = (images[i][:h, :w].astype(float) for i in (0, -1))   # video pads to even sides
    assert np.abs(last - want).mean() / 255 <= 0.02
    assert np.abs(first - last).mean() / 255 > 0.005   # the settling moved


def test_bad_timing_and_missing_run_are_named(chart, tmp_path):
    with pytest.raises(ValueError, match="fps"):
        chart.save(tmp_path / "a.gif", fps=0)
    with pytest.raises(ValueError, match="fps and seconds"):
        chart.save(tmp_path / "a.png", fps=10)
    with pytest.raises(RuntimeError, match="run"):
        uw.Chart(pd.DataFrame({"v": [1.0]})).save(tmp_path / "a.gif")


def test_video_without_pyav_names_the_extra(chart, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "av", None)   # import av then raises ImportError
    with pytest.raises(ImportError, match=r"unitopia-widget\[video\]"):
        chart.save(tmp_path / "a.mp4", fps=10, seconds=2)
