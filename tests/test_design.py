"""Tests for the design model (scene, chart): orientation, margins, layers and blocks, JSON."""
import json
import math

import numpy as np
import pandas as pd
import pytest
from scipy.spatial import cKDTree

import unitopia_widget as uw
from unitopia_widget.design.files import load_design
from unitopia_widget.design.scene import VERSION, block_order

ELLIPSE = uw.Container.ellipse(400, 250, 220, 200)


pytestmark = pytest.mark.usefixtures("one_thread")


def ones(n, **cols):
    return pd.DataFrame({"v": np.ones(n), **cols})


def angle_errors(table, target) -> np.ndarray:
    """Degrees between each mark's up axis (sin a, -cos a) and its ``target (N, 2)`` direction."""
    a = np.radians(table["angle"].to_numpy())
    up = np.stack([np.sin(a), -np.cos(a)], axis=1)
    target = target / np.linalg.norm(target, axis=1, keepdims=True)
    return np.degrees(np.arccos(np.clip((up * target).sum(1), -1, 1)))


# --- orientation ---------------------------------------------------------------------

@pytest.mark.parametrize("degrees", [30, -45.5, 180])
def test_fixed_orientation_sets_every_angle(degrees):
    table = uw.Chart(ones(12), mark="triangle", size="v", orientation=degrees,
                     boundary="open", fill=0.3, iterations=20).layout()
    np.testing.assert_allclose(table["angle"], degrees, atol=1e-4)


def test_no_orientation_keeps_marks_upright():
    table = uw.Chart(ones(12), mark="triangle", size="v", iterations=20).layout()
    assert (table["angle"] == 0).all()


def test_rotate_lets_the_optimiser_turn_marks():
    table = uw.Chart(ones(30), mark="triangle", size="v", rotate=True, container=ELLIPSE,
                     iterations=80).layout()
    assert (table["angle"].abs() > 1e-3).mean() > 0.5


@pytest.mark.parametrize("mark, boundary", [("triangle", "closed"), ("drop", "open")])
def test_to_center_points_each_up_axis_at_the_centroid(mark, boundary):
    kw = dict(boundary="open", fill=0.4) if boundary == "open" else {}
    chart = uw.Chart(ones(40), mark=mark, size="v", orientation="to_center", container=ELLIPSE,
                     iterations=200, **kw)
    table = chart.layout()
    cx, cy = ELLIPSE.centroid(chart.canvas)
    to_centre = np.stack([cx - table["x"], cy - table["y"]], axis=1)
    far = np.linalg.norm(to_centre, axis=1) > 0.5 * table["height"].mean()   # direction defined
    err = angle_errors(table[far], to_centre[far])
    print(f"to_center ({mark}, {boundary}, {far.sum()} marks): median {np.median(err):.2f} deg, "
          f"90th percentile {np.percentile(err, 90):.2f} deg, max {err.max():.2f} deg")
    assert np.median(err) < 5 and np.percentile(err, 90) < 10


def test_orientation_errors():
    with pytest.raises(ValueError, match=r"orientation must be one of None, 'to_center', "
                                         r"'along_emitter', 'random', \('random', lo, hi\) in "
                                         r"degrees, or a number of degrees; got 'center'"):
        uw.Chart(ones(3), orientation="center")
    with pytest.raises(ValueError, match=r"orientation must be finite"):
        uw.Chart(ones(3), orientation=math.inf)
    with pytest.raises(ValueError, match=r"orientation=\('random', lo, hi\) needs lo < hi <= "
                                         r"lo \+ 360 degrees; got \('random', 30, -30\)"):
        uw.Chart(ones(3), orientation=("random", 30, -30))
    with pytest.raises(ValueError, match=r"lo \+ 360 degrees; got \('random', -200, 200\)"):
        uw.Chart(ones(3), orientation=("random", -200, 200))
    with pytest.raises(TypeError, match=r"orientation's lowest angle must be a number, got 'a'"):
        uw.Chart(ones(3), orientation=("random", "a", 30))


def resultant(degrees) -> float:
    """Mean resultant length of angles in degrees: 1 when all point one way, ~0 when spread."""
    a = np.radians(np.asarray(degrees, float))
    return float(np.hypot(np.cos(a).mean(), np.sin(a).mean()))


@pytest.fixture(scope="module")
def scattered_petals():
    """Petals turned at random, in a blob, held (rotate=False) and refined (rotate=True)."""
    kw = dict(mark="drop", size="v", orientation="random", container=ELLIPSE, iterations=60)
    return [uw.Chart(ones(120), rotate=turn, **kw).layout() for turn in (False, True)]


def test_random_orientation_turns_each_mark_its_own_way(scattered_petals):
    held, refined = scattered_petals
    print(f"mean resultant length: held {resultant(held['angle']):.3f}, "
          f"refined {resultant(refined['angle']):.3f}")
    assert resultant(held["angle"]) <= 0.25 and resultant(refined["angle"]) <= 0.25
    assert held["angle"].nunique() == len(held)
    again = uw.Chart(ones(120), mark="drop", size="v", orientation="random", container=ELLIPSE,
                     iterations=60).layout()
    np.testing.assert_allclose(again["angle"], held["angle"])       # drawn from the seed


def test_random_orientation_within_a_range_and_kept_in_the_design():
    chart = uw.Chart(ones(40), mark="drop", size="v", orientation=("random", -30, 30),
                     boundary="open", fill=0.3, iterations=20)
    angle = chart.layout()["angle"]
    assert angle.between(-30, 30).all() and angle.max() - angle.min() > 40
    saved = json.loads(json.dumps(chart.design()))
    assert saved["layers"][0]["orientation"] == ["random", -30.0, 30.0]
    assert uw.Chart.from_design(ones(40), saved).layers[0].orientation == ("random", -30.0, 30.0)
    scope = {"df": ones(40)}
    exec(chart.to_code(), scope)
    assert scope["chart"].layers[0].orientation == ("random", -30.0, 30.0)


# --- margins ------------------------------------------------------------------------------

@pytest.mark.parametrize("margin", [0.1, 0.25])
def test_margin_opens_the_gaps_between_equal_circles(margin):
    # a pile pressed together by a point force: neighbours touch at their margins
    chart = uw.Chart(ones(40), mark="circle", size="v", margin=margin, container=ELLIPSE,
                     boundary="open", fill=0.3, forces=[uw.PointForce(400, 440)], iterations=200)
    table = chart.layout()
    xy = table[["x", "y"]].to_numpy()
    touching = table["width"].to_numpy()[0]                  # centre distance of touching circles
    # neighbours stand margin x their size apart: centres (1 + m) d apart
    nearest = cKDTree(xy).query(xy, k=2)[0][:, 1] / ((1 + margin) * touching)
    print(f"margin {margin}: nearest centre distance / ((1 + m) d): min {nearest.min():.4f}, "
          f"median {np.median(nearest):.4f}")
    assert nearest.min() > 0.97                # the gap is there (0.67 to 0.83 without margins)
    assert np.median(nearest) < 1.06           # and the pile is packed, so the test bites


def test_margin_column_gives_each_mark_its_own_gap():
    df = ones(40, m=np.r_[np.zeros(20), np.full(20, 0.3)])
    table = uw.Chart(df, mark="circle", size="v", margin="m", container=ELLIPSE, boundary="open",
                     fill=0.35, forces=[uw.PointForce(400, 440)], iterations=200).layout()
    xy, r = table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2
    m = df.loc[table["row"], "m"].to_numpy()
    ratio = np.array([np.hypot(*(xy[i] - xy[j])) / (r[i] * (1 + m[i]) + r[j] * (1 + m[j]))
                      for i, j in cKDTree(xy).query_pairs(4 * r.max())])
    print(f"margin column: worst centre distance / required {ratio.min():.4f}")
    assert ratio.min() > 0.97
    # the plain marks do come closer to each other than the padded ones
    plain = xy[m == 0]
    assert cKDTree(plain).query(plain, k=2)[0][:, 1].min() < 1.3 * 2 * r[0]


def test_margin_errors():
    with pytest.raises(ValueError, match=r"margin must be a column name or a fraction in \[0, 4\], got 5"):
        uw.Chart(ones(3), margin=5)
    with pytest.raises(ValueError, match=r"margin_of must be one of 'median', 'own'; got 'mean'"):
        uw.Chart(ones(3), margin=0.2, margin_of="mean")


def _gaps(table, margins):
    """``(pairs,)`` centre distance of near circle pairs over the one their ``margins`` need,
    and whether each pair is two large circles."""
    xy, r = table[["x", "y"]].to_numpy(), table["width"].to_numpy() / 2
    pairs = np.array(sorted(cKDTree(xy).query_pairs(4 * r.max())))
    i, j = pairs[:, 0], pairs[:, 1]
    need = r[i] * (1 + margins[i]) + r[j] * (1 + margins[j])
    big = r > 2 * r.min()
    return np.hypot(*(xy[i] - xy[j]).T) / need, big[i] & big[j]


@pytest.mark.parametrize("margin_of", ["median", "own"])
def test_marks_larger_than_the_median_keep_the_median_marks_gap(margin_of):
    """30 small circles and 8 of 16x their area (4x their width) pressed into a pile, margin
    0.5. By default a large circle keeps the gap a median (small) circle keeps, so two large
    ones stand 0.5 x a small width apart, not 0.5 x their own; "own" keeps version 3's moat."""
    df = ones(38, v=np.repeat([1.0, 16.0], [30, 8]))
    table = uw.Chart(df, mark="circle", size="v", margin=0.5, margin_of=margin_of, seed=2,
                     container=ELLIPSE, boundary="open", fill=0.3,
                     forces=[uw.PointForce(400, 440)], iterations=250).layout()
    big = table["width"].to_numpy() > 2 * table["width"].min()
    capped = np.where(big, 0.5 / 4, 0.5)                  # median width / own width = 1/4
    ratio, both = _gaps(table, capped)
    assert ratio.min() > 0.97                              # every gap the rule asks for is kept
    own, _ = _gaps(table, np.full(len(table), 0.5))
    close = own[both].min()   # two large circles: their distance over what their own gaps need
    print(f"margin_of={margin_of}: worst gap {ratio.min():.3f} of the capped rule's, large "
          f"pairs at {close:.3f} of their own moats")
    if margin_of == "median":
        assert close < 0.9                                 # they come closer than their own moats
    else:
        assert close > 0.95


def test_designs_before_version_4_keep_each_marks_own_margin():
    chart = uw.Chart(ones(3), margin=0.3)
    assert chart.layers[0].margin_of == "median"
    d = json.loads(json.dumps(chart.design()))
    assert d["version"] == VERSION and d["layers"][0]["margin_of"] == "median"
    d["layers"][0]["margin_of"] = "own"
    chart.apply_design(d)
    assert chart.layers[0].margin_of == "own"
    d["layers"][0].pop("margin_of")
    chart.apply_design(d)                                  # version 4 without the key: default
    assert chart.layers[0].margin_of == "median"
    chart.apply_design({**d, "version": 3})                # laid out on own sizes before version 4
    assert chart.layers[0].margin_of == "own" and chart.layers[0].encodings["margin"] == 0.3


# --- layers and blocks -----------------------------------------------------------------------

def sediment_chart(blocks=True):
    df = ones(60, g=["a"] * 30 + ["b"] * 30)
    chart = uw.Chart(df, by="g", mark="circle", size="v", container=uw.Container.ellipse(400, 250, 200, 200),
                     forces=[uw.DirectionalForce(90)], boundary="open", fill=0.4, iterations=300)
    if blocks:
        chart.layer("b").set(blocks=["a"])
    return chart


def test_a_blocking_layer_settles_on_top_of_the_one_it_blocks_on():
    chart = sediment_chart()
    table = chart.layout()
    mean_y = table.groupby("layer")["y"].mean()
    print(f"sedimentation: mean y of layer a {mean_y['a']:.1f}, layer b {mean_y['b']:.1f} "
          f"(container centre 250, radius 200)")
    assert mean_y["b"] < mean_y["a"] - 40               # b rests above a
    # and b does not sink into a: little overlap between the layers' discs
    a, b = table[table.layer == "a"], table[table.layer == "b"]
    d = cKDTree(a[["x", "y"]].to_numpy()).query(b[["x", "y"]].to_numpy())[0]
    assert d.min() > 0.9 * table["width"].iloc[0]


def test_layers_in_different_containers_ignore_each_other():
    # (layers sharing one container collide both ways: tests/test_groups.py)
    chart = sediment_chart(blocks=False)
    chart.layer("b").set(container=uw.Container.ellipse(401, 250, 200, 200))
    table = chart.layout()
    mean_y = table.groupby("layer")["y"].mean()
    assert abs(mean_y["a"] - mean_y["b"]) < 20          # both sink to the bottom, overlapping


def test_block_cycles_are_named():
    chart = uw.Chart(ones(6, g=list("aabbcc")), by="g")
    chart.layer("a").set(blocks=["c"])
    chart.layer("b").set(blocks=["a"])
    with pytest.raises(ValueError, match=r"block cycle: 'a' -> 'c' -> 'b' -> 'a'"):
        chart.layer("c").set(blocks=["b"])
    assert chart.layer("c").blocks == []                 # the refused change is not kept
    with pytest.raises(ValueError, match=r"block cycle: layer 'a' blocks on itself"):
        chart.layer("a").set(blocks=["a"])


def test_block_order_puts_blocking_layers_first():
    class L:
        def __init__(self, name, blocks):
            self.name, self.blocks = name, blocks
    assert block_order([L("x", ["z"]), L("y", []), L("z", ["y"])]) == [1, 2, 0]


def test_unknown_block_name_is_refused_with_a_suggestion():
    chart = uw.Chart(ones(4, g=["lily", "lily", "rose", "rose"]), by="g")
    with pytest.raises(ValueError, match=r"layer 'rose' blocks on 'lilly': no such layer \(did you "
                                         r"mean 'lily'\?\); the layers are 'lily', 'rose'"):
        chart.layer("rose").set(blocks=["lilly"])
    assert chart.layer("rose").blocks == []


def test_by_makes_one_layer_per_value_with_a_mark_dict():
    df = pd.DataFrame({"v": [1.0, 2, 3, 4, 5], "kind": ["rose", "tulip", "rose", "lily", "tulip"]})
    chart = uw.Chart(df, by="kind", size="v", mark={"rose": "heart", "tulip": "drop", "lily": "star"})
    assert [layer.name for layer in chart.layers] == ["lily", "rose", "tulip"]
    assert [layer.mark.to_json()["name"] for layer in chart.layers] == ["star", "heart", "drop"]
    assert chart.layer("rose").rows == {"column": "kind", "value": "rose"}
    table = uw.Chart(df, by="kind", size="v", mark={"rose": "heart", "tulip": "drop", "lily": "star"},
                     iterations=20).layout()
    assert dict(zip(table["row"], table["layer"])) == dict(df["kind"])
    with pytest.raises(ValueError, match=r"mark: no mark for category 'lily'"):
        uw.Chart(df, by="kind", mark={"rose": "heart", "tulip": "drop"})
    with pytest.raises(ValueError, match=r"needs shape=<column> \(each row draws the mark of its category\) or by=<column>"):
        uw.Chart(df, mark={"rose": "heart"})


def test_by_with_numbers_names_layers_by_value():
    df = pd.DataFrame({"v": [1.0, 2, 3], "year": [2025, 2024, 2025]})
    chart = uw.Chart(df, by="year")
    assert [layer.name for layer in chart.layers] == ["2024", "2025"]
    assert chart.layer("2025") is chart.layers[1] and chart.layer(0) is chart.layers[0]


def test_add_remove_and_move_layers():
    df = pd.DataFrame({"v": [1.0, 2, 3, 4], "type": ["rose", "lily", "rose", "lily"]},
                      index=[10, 20, 30, 40])
    chart = uw.Chart(df, size="v", iterations=20)
    roses = chart.add_layer("roses", data=df[df.type == "rose"], mark="heart", size="v",
                            blocks=["layer-1"], container=uw.Container.rect(0, 0, 400, 500),
                            iterations=20)
    assert roses.rows == {"index": [10, 30]} and chart.layers[-1] is roses
    table = chart.layout()
    assert table[table.layer == "roses"]["row"].tolist() == [10, 30]
    assert len(table) == 6
    with pytest.raises(ValueError, match=r"a layer named 'roses' exists already"):
        chart.add_layer("roses")
    with pytest.raises(ValueError, match=r"layer 'layer-1' is blocked on by \['roses'\]"):
        chart.remove_layer("layer-1")
    chart.move_layer("roses", 0)
    assert [layer.name for layer in chart.layers] == ["roses", "layer-1"]
    assert chart.layout()["layer"].tolist()[:2] == ["roses", "roses"]   # drawing order
    roses.set(blocks=[])
    chart.remove_layer("layer-1")
    assert [layer.name for layer in chart.layers] == ["roses"]
    with pytest.raises(ValueError, match=r"a chart keeps at least one layer"):
        chart.remove_layer("roses")
    with pytest.raises(KeyError, match=r"no layer 'rose' \(did you mean 'roses'\?\)"):
        chart.layer("rose")


def test_add_layer_with_rows_not_in_the_frame():
    chart = uw.Chart(ones(3))
    with pytest.raises(ValueError, match=r"1 of its rows are not in the DataFrame"):
        chart.add_layer("extra", data=pd.DataFrame({"v": [1.0]}, index=[99]))
    assert [layer.name for layer in chart.layers] == ["layer-1"]


def test_layer_set_unknown_field_suggests_the_closest():
    chart = uw.Chart(ones(3))
    with pytest.raises(TypeError, match=r"Layer.set: unknown field 'boundry' \(did you mean "
                                        r"'boundary'\?\)"):
        chart.layer("layer-1").set(boundry="open")
    with pytest.raises(TypeError, match=r"Chart\(\) got an unexpected keyword argument 'colour' "
                                        r"\(did you mean 'color'\?\)"):
        uw.Chart(ones(3), colour="red")


def test_layer_set_changes_the_layout():
    chart = uw.Chart(ones(20), size="v", boundary="open", fill=0.2, iterations=60)
    chart.layer("layer-1").set(container=uw.Container.rect(40, 60, 200, 300),
                               forces=[uw.PointForce(140, 210)])
    table = chart.layout()
    assert table["x"].between(40, 240).all() and table["y"].between(60, 360).all()


def test_layer_set_with_a_bad_column_is_refused_and_not_kept():
    chart = uw.Chart(ones(3), size="v")
    with pytest.raises(ValueError, match=r"size='w': no such column"):
        chart.layer("layer-1").set(size="w")
    assert chart.layer("layer-1").encodings["size"] == "v"


# --- design JSON ---------------------------------------------------------------------

@pytest.fixture
def rich_chart():
    df = pd.DataFrame({"d": [1.0, 2, 3, 4, 5, 6], "task": list("aabbcc"), "m": [0, .1, 0, .1, 0, .1]})
    chart = uw.Chart(df, by="task", mark={"a": "star", "b": "circle", "c": "heart"}, size="d",
                     color="task", margin="m", seed=7, canvas=(640, 400),
                     container=uw.Container.ellipse(320, 200, 200, 150).cut([[120, 200], [200, 210]], 8),
                     forces=[uw.PointForce(320, 330, strength=2.0), uw.DirectionalForce(90)],
                     iterations=20, background=np.zeros((8, 8, 3), np.uint8))
    chart.layer("b").set(blocks=["a"], emitter=uw.CurveEmitter(
        [[50, 50], [150, 20], [250, 80], [350, 50]], mode="band", direction=30), orientation=15)
    chart.layer("c").set(emitter=uw.GridEmitter(speed=0.5), boundary="open", fill=0.4,
                         orientation="to_center", rotate=True,
                         container=uw.Container.polygon([[0, 0], [300, 0], [0, 300]]))
    chart.add_layer("subset", data=df.iloc[[1, 3]], mark=uw.Mark.sketch([[[0, 0], [10, 10]]]),
                    color="#ff0000", order="d", width="d", iterations=20)
    return chart


def test_design_json_round_trip(rich_chart):
    design = rich_chart.design()
    assert design["schema"] == "unitopia-design" and design["version"] == VERSION
    text = json.dumps(design)
    other = uw.Chart(rich_chart.df)
    other.apply_design(json.loads(text))
    assert other.design() == design
    assert [layer.name for layer in other.layers] == ["a", "b", "c", "subset"]
    assert other.canvas == (640, 400) and other.seed == 7
    assert other.layer("b").emitter == rich_chart.layer("b").emitter
    assert other.layer("a").container == rich_chart.layer("a").container


def test_design_round_trip_gives_the_same_layout(rich_chart):
    other = uw.Chart(rich_chart.df)
    other.apply_design(json.loads(json.dumps(rich_chart.design())))
    pd.testing.assert_frame_equal(other.layout(), rich_chart.layout())


def test_save_json_and_load_design(rich_chart, tmp_path):
    path = tmp_path / "chart.json"
    rich_chart.save(path)
    d = load_design(path)
    assert d == json.loads(json.dumps(rich_chart.design()))
    other = uw.Chart(rich_chart.df)
    other.apply_design(d)
    assert other.design() == d


def test_corrupt_design_file(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{"schema": "unitopia-design", "version": 1, "layers": [')
    with pytest.raises(ValueError, match=r"design file '.*broken.json' is not valid JSON"):
        load_design(path)
    path.write_text('{"hello": 1}')
    with pytest.raises(ValueError, match=r"not a unitopia design: expected a JSON object with "
                                         r"\"schema\": \"unitopia-design\""):
        load_design(path)


def test_newer_design_version_is_refused(tmp_path, rich_chart):
    d = rich_chart.design()
    d["version"] = VERSION + 1
    path = tmp_path / "new.json"
    path.write_text(json.dumps(d))
    with pytest.raises(ValueError, match=rf"design: version {VERSION + 1} is newer than this "
                                         rf"unitopia-widget reads \(up to {VERSION}\); upgrade"):
        load_design(path)
    with pytest.raises(ValueError, match=r"is newer than this unitopia-widget reads"):
        uw.Chart(rich_chart.df).apply_design(d)


def test_a_bad_design_changes_nothing(rich_chart):
    before = rich_chart.design()
    bad = json.loads(json.dumps(before))
    bad["layers"][1]["blocks"] = ["nope"]
    with pytest.raises(ValueError, match=r"blocks on 'nope': no such layer"):
        rich_chart.apply_design(bad)
    bad = json.loads(json.dumps(before))
    bad["layers"][0]["encodings"]["size"] = "dd"
    with pytest.raises(ValueError, match=r"size='dd': no such column \(did you mean 'd'\?\)"):
        rich_chart.apply_design(bad)
    bad = json.loads(json.dumps(before))
    bad["layers"][2]["name"] = "a"
    with pytest.raises(ValueError, match=r"layer names must be unique"):
        rich_chart.apply_design(bad)
    assert rich_chart.design() == before


def test_layer_finds_a_by_layer_by_its_value_and_others_by_position():
    df = pd.DataFrame({"Year": [2025, 2026, 2025], "v": [1.0, 2.0, 3.0]})
    chart = uw.Chart(df, by="Year", size="v")
    assert chart.layer(2026).name == "2026"
    assert chart.layer(0).name == "2025"
    with pytest.raises(KeyError, match="no layer named 7 and no position 7"):
        chart.layer(7)


def test_load_takes_an_explicit_canvas(tmp_path):
    df = pd.DataFrame({"v": [1.0, 2.0, 3.0]})
    w = uw.UnitoPia(df, size="v", canvas=(640, 400))
    w.save(tmp_path / "d.json")
    again = uw.UnitoPia.load(tmp_path / "d.json", df, canvas=(640, 400))
    assert again.design["canvas"] == [640, 400]


def _spacing(chart) -> float:
    """Median nearest-centre distance over mark width."""
    p = chart.placements
    xy = p[["x", "y"]].to_numpy()
    dist, _ = cKDTree(xy).query(xy, k=2)
    return float(np.median(dist[:, 1]) / np.median(p["width"]))


def test_a_version_2_margin_keeps_its_spacing():
    """Version 2 padded each mark by margin x size (gap 2m); version 3's gap is m."""
    df = pd.DataFrame({"v": np.ones(30)})
    def spaced(design_version, margin):
        chart = uw.Chart(df, margin=margin, iterations=200, seed=1)
        d = chart.design()
        d["version"] = design_version
        chart.apply_design(d)
        chart.layout()
        return _spacing(chart)
    old = spaced(2, 0.4)                # as version 2 drew it: a gap of 0.8 x size
    assert abs(old / spaced(3, 0.8) - 1) < 0.03
    assert abs(old / spaced(3, 0.4) - 1) > 0.03   # read unconverted, it would draw closer


def test_a_version_2_margin_bound_to_a_column_is_named_in_a_warning():
    chart = uw.Chart(pd.DataFrame({"v": np.ones(3), "gap": [0.1, 0.2, 0.3]}), margin="gap",
                     iterations=20)
    d = chart.design()
    d["version"] = 2
    with pytest.warns(UserWarning, match=r"margin='gap'.*Double the column"):
        chart.apply_design(d)
    assert chart.design()["version"] == VERSION
