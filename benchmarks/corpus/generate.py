"""The corpus: designs drawn from a seed through the public API (``uw.Chart``).

``corpus(seed, n)`` returns ``n`` ``Spec``s: the issue's kinds of failing design first
(``ISSUE_KINDS``), then mixed designs whose axes (container, mark, data, rows, force,
emitter, layers, boundary, margin, orientation) each run through all their values in a
shuffled cycle, so every value appears about equally often. ``build(spec, folder, seed)``
draws the details from ``(corpus seed, index)`` and returns a ``Built``: the chart (not yet
laid out), each layer's container, and the design's tags.
"""
from __future__ import annotations

import dataclasses
import os

import numpy as np
import pandas as pd

import unitopia_widget as uw

from . import marks, shapes, values
from .shapes import H, W

AXES = {
    "container": list(shapes.KINDS),
    "mark": list(marks.KINDS),
    "data": list(values.KINDS),
    "rows": ["shuffled", "shuffled", "ascending", "descending", "nan"],
    "force": ["none", "point", "directional", "directional", "two-points"],
    "emitter": ["none", "none", "grid", "curve"],
    "layers": [1, 1, 1, 2, 3, 4],
    "boundary": ["closed", "open"],
    "margin": [0.0, 0.0, 0.0, 0.1, 0.2, 0.4, 0.7, 1.0],
    "orientation": ["none", "none", "none", "to_center", "along_emitter", "degrees", "rotate"],
}


@dataclasses.dataclass(frozen=True)
class Spec:
    """One design of the corpus: its id, its index in the corpus, the corpus seed, and
    either an issue kind or the axis values it draws."""
    id: str
    index: int
    seed: int
    kind: str
    axes: tuple = ()


@dataclasses.dataclass
class Built:
    chart: uw.Chart
    containers: dict          # layer name -> uw.Container
    tags: dict                # axis -> value, as drawn (labels of container and mark)


def corpus(seed: int = 0, n: int = 120) -> list[Spec]:
    """``n`` specs (at least the issue kinds): ``k1``.. for the issue's kinds, ``m000``..
    for the mixed designs."""
    rng = np.random.default_rng(seed)
    out = [Spec(f"k{i + 1}-{name}", i, seed, name) for i, name in enumerate(ISSUE_KINDS)]
    mixed = max(0, n - len(out))
    cycles = {}
    for axis, options in AXES.items():
        reps = -(-mixed // len(options))
        cycles[axis] = [options[int(j)] for j in
                        np.concatenate([rng.permutation(len(options)) for _ in range(reps)])]
    for j in range(mixed):
        axes = tuple((axis, cycles[axis][j]) for axis in AXES)
        out.append(Spec(f"m{j:03d}", len(ISSUE_KINDS) + j, seed, "mixed", axes))
    return out[:max(n, len(ISSUE_KINDS))]


def build(spec: Spec, folder: str, layout_seed: int = 0) -> Built:
    """The chart of ``spec``; its PNG and mask assets are written into ``folder`` (made if
    missing)."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng([spec.seed, spec.index])
    if spec.kind != "mixed":
        return ISSUE_KINDS[spec.kind](rng, folder, layout_seed)
    return mixed(dict(spec.axes), rng, folder, layout_seed)


def inside_point(container: uw.Container, rng, low: bool = False) -> tuple[float, float]:
    """A random pixel centre inside ``container`` (``low``: among its lowest fifth)."""
    ys, xs = np.nonzero(np.asarray(container.coverage((W, H), 1.0)) >= 0.5)
    if low:
        keep = ys >= np.quantile(ys, 0.8)
        ys, xs = ys[keep], xs[keep]
    k = int(rng.integers(len(xs)))
    return float(xs[k]) + 0.5, float(ys[k]) + 0.5


def top_curve(container: uw.Container, rng) -> list:
    """A gently wavy curve across the middle of the container's upper part, 4 points."""
    x, y, w, h = container.bbox((W, H))
    xs = np.linspace(x + 0.3 * w, x + 0.7 * w, 4)
    return [(float(a), float(y + h * rng.uniform(0.15, 0.3))) for a in xs]


def forces_for(kind: str, container, rng) -> list:
    if kind == "point":
        return [uw.PointForce(*inside_point(container, rng, low=rng.random() < 0.5))]
    if kind == "two-points":
        return [uw.PointForce(*inside_point(container, rng)) for _ in range(2)]
    if kind == "directional":
        return [uw.DirectionalForce(float(rng.choice([90, 90, 90, 0, 180, 270, 45,
                                                      rng.uniform(0, 360)])))]
    return []


def emitter_for(kind: str, container, rng):
    if kind == "grid":
        return uw.GridEmitter(direction=None if rng.random() < 0.5 else 90.0)
    if kind == "curve":
        mode = str(rng.choice(["free", "line", "band"]))
        return uw.CurveEmitter(top_curve(container, rng), mode=mode)
    return None


def mixed(axes: dict, rng, folder: str, layout_seed: int) -> Built:
    """A design from one value per axis; the details (sizes, counts, places) from ``rng``.
    A design with strata (several layers) is open under a force, each layer's marks
    1.5 to 3 times smaller in area than the one below it."""
    layers = axes["layers"]
    boundary = "open" if layers > 1 else axes["boundary"]
    force = axes["force"] if layers == 1 or axes["force"] != "none" else "directional"
    fill = float(rng.uniform(0.2, 0.9)) if boundary == "open" else None
    n = int(rng.integers(30, 161)) if layers == 1 else int(rng.integers(25, 61)) * layers
    if axes["container"] == "band":
        label, container = shapes.band(rng, folder, n, fill or 0.6)
    else:
        label, container = shapes.KINDS[axes["container"]](rng, folder)
    mark_label, mark, thin = marks.KINDS[axes["mark"]](rng, folder)
    v = values.column(axes["data"], n, rng)
    layer = np.sort(rng.integers(0, layers, n))
    v = v * float(rng.uniform(1.5, 3.0)) ** -layer
    v = values.with_rows(v, axes["rows"], rng)
    df = pd.DataFrame({"v": v, "layer": layer})
    kw = dict(mark=mark, container=container, boundary=boundary, fill=fill, canvas=(W, H),
              seed=layout_seed, margin=axes["margin"], legend=False,
              forces=forces_for(force, container, rng),
              emitter=emitter_for(axes["emitter"], container, rng))
    kw["height" if thin and rng.random() < 0.4 else "size"] = "v"
    orientation = axes["orientation"]
    if orientation == "along_emitter" and not isinstance(kw["emitter"], uw.CurveEmitter):
        orientation = "to_center"
    if orientation == "rotate":
        kw["rotate"] = True
    elif orientation == "degrees":
        kw["orientation"] = float(rng.choice([0, 30, 45, 90]))
    elif orientation != "none":
        kw["orientation"] = orientation
    if axes["rows"] == "nan":
        kw["dropna"] = True
    if layers > 1:
        kw.update(by="layer", color="layer")
    chart = uw.Chart(df, **kw)
    for j in range(1, layers):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    tags = dict(axes, container=label, mark=mark_label, force=force, boundary=boundary,
                orientation=orientation, n=n, fill=fill)
    return Built(chart, {layer.name: container for layer in chart.layers}, tags)


def _stratified(df, layers, container, boundary, fill, forces, layout_seed) -> uw.Chart:
    """A chart of ``len(layers)`` layers (one mark each) chained by blocks, coloured by layer."""
    chart = uw.Chart(df, mark={i: m for i, m in enumerate(layers)}, shape="layer", by="layer",
                     color="layer", size="v", container=container, boundary=boundary, fill=fill,
                     forces=forces, canvas=(W, H), seed=layout_seed, legend=False)
    for j in range(1, len(layers)):
        chart.layer(str(j)).set(blocks=[str(j - 1)])
    return chart


def kind_band_strata(rng, folder, layout_seed) -> Built:
    """Issue kind 1: a V band about 4 mark widths wide, a point force above its bend, three
    layers chained by blocks (stars, then flowers on them, then suns), open at fill 0.7."""
    counts = [int(rng.integers(10, 16)), int(rng.integers(20, 31)), int(rng.integers(35, 51))]
    k = np.repeat(np.arange(3), counts)
    df = pd.DataFrame({"layer": k, "v": rng.lognormal(0, 0.4, len(k)) * 3.0 ** -k})
    label, container = shapes.band(rng, folder, len(k), 0.7)
    x, y, w, h = container.bbox((W, H))
    point = uw.PointForce(W / 2, y + h * 0.55)
    chart = _stratified(df, ["star", uw.Mark.svg(marks.STYLED[0]), marks.sun(rng)], container,
                        "open", 0.7, [point], layout_seed)
    return Built(chart, {layer.name: container for layer in chart.layers},
                 dict(container=label, mark="star/flower/sun", force="point", layers=3, n=len(k),
                      boundary="open", fill=0.7))


def kind_thin_directional(rng, folder, layout_seed) -> Built:
    """Issue kinds 2 and 3: arrows 12:1 turned to 0 degrees, pushed right into an open pen
    at fill 0.5."""
    n = int(rng.integers(50, 81))
    container = uw.Container.rect(40, 40, 400, 280)
    chart = uw.Chart(pd.DataFrame({"v": rng.uniform(1, 3, n)}), mark=uw.Mark.svg(marks.ARROW),
                     size="v", orientation=0.0, container=container, boundary="open", fill=0.5,
                     forces=[uw.DirectionalForce(0)], canvas=(W, H), seed=layout_seed, legend=False)
    return Built(chart, {"layer-1": container},
                 dict(container="pen", mark="thin:arrow", force="directional", n=n,
                      boundary="open", fill=0.5))


def kind_capped_scale(rng, folder, layout_seed) -> Built:
    """Issue kind 4: strands whose height column has one value 40 times the typical one,
    closed in a blob."""
    n = int(rng.integers(50, 81))
    v = rng.lognormal(0, 0.3, n)
    v[int(rng.integers(n))] = 40.0 * float(np.median(v))
    label, container = shapes.blob(rng, folder)
    strand = uw.Mark.svg(marks.ROOT + "/benchmarks/data/strand.svg")
    chart = uw.Chart(pd.DataFrame({"v": v}), mark=strand,
                     height="v", rotate=True, container=container, canvas=(W, H),
                     seed=layout_seed, legend=False)
    return Built(chart, {"layer-1": container}, dict(container=label, mark="thin:strand",
                                                     data="one 40x", n=n, boundary="closed"))


def kind_slope(rng, folder, layout_seed) -> Built:
    """Issue kind 5: two layers poured from curves onto a sloping plank under a downward
    force, the second blocked on the first."""
    label, container = shapes.slope(rng, folder)
    n = int(rng.integers(30, 46))
    df = pd.DataFrame({"layer": np.repeat([0, 1], n), "v": rng.lognormal(0, 0.5, 2 * n)})
    chart = uw.Chart(df, mark="star", size="v", by="layer", color="layer", container=container,
                     boundary="open", forces=[uw.DirectionalForce(90)], canvas=(W, H),
                     seed=layout_seed, legend=False)
    chart.layer("0").set(emitter=uw.CurveEmitter([(40, 40), (100, 30), (160, 30), (200, 40)]))
    chart.layer("1").set(emitter=uw.CurveEmitter([(280, 40), (320, 30), (380, 30), (440, 40)]),
                         blocks=["0"])
    return Built(chart, {"0": container, "1": container},
                 dict(container=label, mark="shape:star", force="directional", layers=2,
                      n=2 * n, boundary="open"))


def kind_twins(rng, folder, layout_seed) -> Built:
    """Issue kind 6: two touching discs filled closed, lognormal sizes."""
    while True:
        label, container = shapes.twin_rings(rng, folder)
        if label.startswith("twins:discs"):
            break
    n = int(rng.integers(60, 101))
    chart = uw.Chart(pd.DataFrame({"v": rng.lognormal(0, 0.9, n)}), mark="circle", size="v",
                     container=container, canvas=(W, H), seed=layout_seed, legend=False)
    return Built(chart, {"layer-1": container}, dict(container=label, mark="shape:circle",
                                                     data="lognormal", n=n, boundary="closed"))


def kind_lettering(rng, folder, layout_seed) -> Built:
    """The held-out snowflakes: seven kinds of drawn snowflakes around lettering, closed,
    margin 0.1."""
    while True:
        label, container = shapes.letters(rng, folder)
        if "around" in label:
            break
    kinds = [marks.flake(a, b, w, c) for a, b, w, c in (
        (6, 0.55, 6, "#4e79a7"), (6, 0.35, 8, "#76b7b2"), (8, 0.5, 5, "#59a14f"),
        (5, 0.6, 7, "#9c755f"), (6, 0.75, 5, "#af7aa1"), (12, 0.6, 4, "#4e79a7"),
        (7, 0.45, 6, "#76b7b2"))]
    v = rng.lognormal(0, 1, 110)
    chart = uw.Chart(pd.DataFrame({"v": v}), mark=kinds, size="v", margin=0.1, container=container,
                     canvas=(W, H), seed=layout_seed, legend=False)
    return Built(chart, {"layer-1": container}, dict(container=label, mark="spiky:flakes7",
                                                     data="lognormal", n=len(v), boundary="closed",
                                                     margin=0.1))


ISSUE_KINDS = {"band-strata": kind_band_strata, "thin-push": kind_thin_directional,
               "capped-scale": kind_capped_scale, "slope": kind_slope, "twins": kind_twins,
               "lettering": kind_lettering}
