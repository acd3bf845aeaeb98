"""Silhouette renders kept on disk across processes (``io.rendercache``): a kept render is
the one resvg returns, byte for byte; nothing is kept where the folder is switched off or
cannot be written."""
import numpy as np
import pytest

from unitopia_widget.io import rendercache, svgsafe

SVG = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><circle cx="5" cy="5" r="4"/></svg>'


def root():
    return svgsafe.parse_svg(SVG)


def test_a_kept_render_is_read_back_without_resvg_and_equals_its_render(tmp_path, monkeypatch):
    monkeypatch.setenv("UNITOPIA_CACHE_DIR", str(tmp_path))
    drawn = svgsafe.render_svg(root(), 40, 30, opaque=True, keep=True)
    assert len(list(tmp_path.glob("*.png"))) == 1 and not list(tmp_path.glob("*.part"))

    def refused(*args):
        raise AssertionError("resvg ran for a kept render")
    monkeypatch.setattr(svgsafe, "_render", refused)
    kept = svgsafe.render_svg(root(), 40, 30, opaque=True, keep=True)
    assert kept.dtype == np.uint8 and np.array_equal(kept, drawn)
    with pytest.raises(AssertionError, match="resvg ran"):   # another size, or not kept: rendered
        svgsafe.render_svg(root(), 41, 30, opaque=True, keep=True)
    with pytest.raises(AssertionError, match="resvg ran"):
        svgsafe.render_svg(root(), 40, 30, opaque=True)


def test_another_style_sheet_or_resvg_version_is_another_render(monkeypatch):
    plain = rendercache.name(SVG, None)
    assert plain == rendercache.name(SVG, None) and plain != rendercache.name(SVG, svgsafe.OPAQUE_CSS)
    monkeypatch.setattr(rendercache, "_resvg", lambda: "0.0.1")
    assert rendercache.name(SVG, None) != plain


def test_nothing_is_kept_when_switched_off_or_the_folder_cannot_be_written(tmp_path, monkeypatch):
    monkeypatch.setenv("UNITOPIA_CACHE_DIR", "")
    assert rendercache.directory() is None
    svgsafe.render_svg(root(), 20, 20, keep=True)
    blocked = tmp_path / "a-file"
    blocked.write_text("not a folder")
    monkeypatch.setenv("UNITOPIA_CACHE_DIR", str(blocked / "renders"))
    drawn = svgsafe.render_svg(root(), 20, 20, keep=True)
    assert drawn.shape == (20, 20, 4) and blocked.read_text() == "not a folder"
