"""A design kept beside the notebook: ``design_path=``, ``save_design()`` and
``UnitoPia.load`` restore a sketch when the notebook is executed again."""
import copy
import json
import os

import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.jupyter import keep


@pytest.fixture
def df():
    return pd.DataFrame({"v": [1.0, 2.0, 3.0], "k": ["a", "b", "a"]})


def sketch(w):
    """What a front-end edit does: the design trait changes (a lasso container here)."""
    design = copy.deepcopy(w.design)
    design["layers"][0]["container"] = uw.Container.polygon(
        [[40, 40], [300, 60], [250, 300], [60, 260]]).to_json()
    w.design = design
    return design


def test_a_re_executed_cell_restores_the_sketch_from_its_design_path(df, tmp_path):
    path = tmp_path / "jar.unitopia.json"
    w = uw.UnitoPia(df, mark="star", size="v", design_path=path)    # first run: no file yet
    assert json.loads(path.read_text()) == w.design
    drawn = sketch(w)
    assert json.loads(path.read_text())["layers"][0]["container"] == drawn["layers"][0]["container"]
    again = uw.UnitoPia(df, mark="star", size="v", design_path=path)   # the cell, re-executed
    assert again.design == w.design and again.layer(0).container.kind == "polygon"


def test_load_restores_the_sketch_and_keeps_the_file_current(df, tmp_path):
    w = uw.UnitoPia(df, mark="star", color="k")
    path = w.save_design(tmp_path / "x.json")
    assert path == tmp_path / "x.json" == w.design_path
    w2 = uw.UnitoPia.load(path, df)               # w = UnitoPia.load("x.json", df)
    drawn = sketch(w2)
    w3 = uw.UnitoPia.load(path, df)               # re-executed after sketching
    assert w3.design == w2.design and w3.design["layers"][0]["container"] == \
        drawn["layers"][0]["container"]
    frozen = uw.UnitoPia.load(path, df, design_path=None)
    frozen.layer(0).set(margin=0.3)
    assert json.loads(path.read_text())["layers"][0]["encodings"]["margin"] == 0.0


def test_save_design_defaults_to_a_file_named_after_the_notebook(df, tmp_path, monkeypatch):
    monkeypatch.setenv("JPY_SESSION_NAME", str(tmp_path / "Sales 2025.ipynb"))
    assert keep.default_path() == tmp_path / "Sales 2025.unitopia.json"
    w = uw.UnitoPia(df)
    assert w.save_design() == tmp_path / "Sales 2025.unitopia.json"
    assert uw.UnitoPia.load(tmp_path / "Sales 2025.unitopia.json", df).design == w.design
    monkeypatch.setenv("JPY_SESSION_NAME", "analysis.ipynb")   # relative: the kernel's folder
    monkeypatch.chdir(tmp_path)
    assert keep.default_path() == tmp_path / "analysis.unitopia.json"
    monkeypatch.delenv("JPY_SESSION_NAME")
    assert keep.default_path() == tmp_path / "design.unitopia.json"


def test_a_design_path_in_a_missing_folder_is_refused_naming_that_path(df, tmp_path):
    path = tmp_path / "no such folder" / "x.unitopia.json"
    with pytest.raises(FileNotFoundError, match=f"cannot write {str(path)!r}") as caught:
        uw.UnitoPia(df, design_path=path)
    assert ".tmp" not in str(caught.value)


@pytest.mark.skipif(not os.path.exists("/proc/self/mem"), reason="needs Linux's /proc")
def test_an_unreadable_design_path_is_named_in_the_error(df, tmp_path):
    with pytest.raises(OSError, match="cannot read the design file '/proc/self/mem'"):
        uw.UnitoPia(df, design_path="/proc/self/mem")
    with pytest.raises(IsADirectoryError, match=f"cannot read the design file {str(tmp_path)!r}"):
        uw.UnitoPia.load(tmp_path, df)


def test_a_symlinked_design_file_keeps_its_link_and_its_target_gets_the_edits(df, tmp_path):
    target = tmp_path / "shared" / "jar.unitopia.json"
    target.parent.mkdir()
    uw.UnitoPia(df).save_design(target)
    link = tmp_path / "jar.unitopia.json"
    link.symlink_to(target)
    w = uw.UnitoPia(df, design_path=link)
    w.caption = "kept through the link"
    assert link.is_symlink() and link.resolve() == target
    assert json.loads(target.read_text())["caption"] == "kept through the link"
    assert not list(tmp_path.glob(".unitopia-*")) and not list(target.parent.glob(".unitopia-*"))


def test_two_widgets_on_one_design_path_do_not_overwrite_each_others_edits(df, tmp_path):
    path = tmp_path / "shared.unitopia.json"
    a = uw.UnitoPia(df, design_path=path)
    b = uw.UnitoPia(df, design_path=path)        # reads a's file, writes the same design
    a.layer(0).set(boundary="open", forces=[uw.PointForce(400, 450)])
    with pytest.warns(RuntimeWarning, match=f"design file {str(path)!r} changed since this "
                                            r"widget last read or wrote it.*"
                                            r"w.save_design\(force=True\).*UnitoPia.load"):
        b.caption = "x"
    kept = json.loads(path.read_text())
    assert kept["layers"][0]["forces"] == [{"kind": "point", "x": 400.0, "y": 450.0,
                                            "strength": 1.0}] and kept["caption"] is None
    with pytest.raises(RuntimeError, match="save_design\\(force=True\\)"):
        b.save_design()
    assert b.save_design(force=True) == path
    assert json.loads(path.read_text())["caption"] == "x"
    b.caption = "y"                               # b wrote last: its edits are written again
    assert json.loads(path.read_text())["caption"] == "y"
    reloaded = uw.UnitoPia.load(path, df)         # a takes the file's design instead
    reloaded.caption = "z"
    assert json.loads(path.read_text())["caption"] == "z"


def test_a_file_rewritten_with_the_same_bytes_is_no_conflict(df, tmp_path):
    path = tmp_path / "same.unitopia.json"
    w = uw.UnitoPia(df, design_path=path)
    data = path.read_bytes()
    path.unlink()
    path.write_bytes(data)                        # a new inode and time, the same design
    w.caption = "still mine"
    assert json.loads(path.read_text())["caption"] == "still mine"
