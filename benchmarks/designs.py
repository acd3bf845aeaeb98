"""Real designs through the public API, measured from the SVG export.

Hand-drawn-looking containers (narrow parts, holes, two piles), icons styled
by ``<style>`` classes with strokes and groups (``benchmarks/data``),
heavy-tailed data (lognormal, 100x-700x spreads; a Pareto column, 760,000x),
margins (a page of drops turned to its centre; tied sizes at 0.2 and 0.4), seven kinds of snowflakes around
lettering, tall thin marks (data-true and on a ``height_range``), blocked layers and emitters (a stack whose layers
shrink 4x; nine layers three to a bowl; snowflakes stacked in a vase), turning rectangles, line-drawn
sketches, hollow rings and a container PNG with faint alpha pixels (assets
made in code). Each
design is laid out by ``uw.UnitoPia``, exported to SVG, and measured by an independent checker
(``measure_svg.py``, kept outside the repository; its path is an argument):
overlap, outside, emptiness (closed containers: the share farther than one
median mark radius from any ink), area-to-value CV; blocked layers report
their mean heights (bottom layer first), or under one point force their mean
distance from it (innermost layer first).

    python benchmarks/designs.py --tool /work/shared/tools/measure_svg.py [NAME ...]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import pandas as pd
from PIL import Image

import unitopia_widget as uw

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
W, H = 800, 600


def icon(name: str) -> uw.Mark:
    return uw.Mark.svg(os.path.join(DATA, name + ".svg"))


def lognormal(n: int, spread: float, seed: int) -> np.ndarray:
    """n lognormal values rescaled so that max / min is exactly ``spread``."""
    v = np.random.default_rng(seed).lognormal(0.0, 1.0, n)
    logs = (np.log(v) - np.log(v).min()) / np.ptp(np.log(v)) * math.log(spread)
    return np.exp(logs)


def blob(cx, cy, rx, ry, wobble, seed, n=48):
    """A hand-drawn-looking closed curve (polygon points)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    k = 1 + wobble * np.convolve(np.tile(rng.normal(0, 1, n), 3), np.ones(5) / 5, "same")[n:2 * n]
    return np.stack([cx + rx * k * np.cos(t), cy + ry * k * np.sin(t)], 1)


def ring_path(points) -> str:
    return "M " + " L ".join(f"{x:.1f} {y:.1f}" for x, y in points) + " Z"


def neck_container() -> uw.Container:
    """Two wobbly lobes joined by a narrow neck (about 50 px wide), a hole in the left one."""
    pts = []
    for cx, rx, ry, a0, a1, joint in ((230, 180, 200, 0.13, 2 * math.pi - 0.13, (431, 324)),
                                      (610, 160, 180, math.pi + 0.14, 3 * math.pi - 0.14, (431, 276))):
        for a in np.linspace(a0, a1, 40):
            k = 1 + 0.05 * math.sin(3 * a + cx) + 0.03 * math.sin(7 * a)
            pts.append((cx + rx * k * math.cos(a), 300 - ry * k * math.sin(a)))
        pts.append(joint)
    hole = [(200 + 40 * math.cos(a), 290 + 36 * math.sin(a))
            for a in np.linspace(0, 2 * math.pi, 24, endpoint=False)]
    return uw.Container.path(ring_path(pts) + " " + ring_path(hole))


def two_piles() -> uw.Container:
    """A W-shaped vessel: two cups side by side sharing a wall that stops half way up."""
    pts = [(60, 80), (90, 560), (370, 560), (390, 330), (410, 330), (430, 560), (710, 560), (740, 80)]
    return uw.Container.polygon(pts)


def seesaw() -> uw.Container:
    """The space above a tilted plank on a pivot."""
    return uw.Container.polygon([(40, 40), (760, 40), (760, 380), (40, 500)])


def design_bubbles():
    df = pd.DataFrame({"favourites": lognormal(118, 720, 0)})
    c = neck_container()
    return dict(df=df, mark="circle", size="favourites", container=c, boundary="closed"), [c]


def design_snowflakes():
    df = pd.DataFrame({"size": lognormal(69, 220, 1)})
    outer = blob(400, 300, 360, 260, 0.04, 5)
    word = [(230, 240), (570, 240), (570, 360), (230, 360)]   # the word SNOW: a hole
    c = uw.Container.path(ring_path(outer) + " " + ring_path(word))
    return dict(df=df, mark=icon("snowflake"), size="size", margin=0.1, container=c,
                boundary="closed"), [c]


def design_bags(scales="shared"):
    df = pd.DataFrame({"bag": ["a"] * 60 + ["b"] * 15, "price": lognormal(75, 100, 2)})
    a = uw.Container.polygon(blob(220, 330, 170, 220, 0.04, 7))
    b = uw.Container.polygon(blob(590, 330, 170, 220, 0.04, 8))
    kw = {} if scales == "shared" else {"scales": scales}   # the default, spelled out or not
    w = uw.UnitoPia(df, mark=icon("bag"), size="price", canvas=(W, H), seed=0, by="bag", piles=None,
                    boundary="closed", **kw)
    w.layer("a").set(container=a)
    w.layer("b").set(container=b)
    return w, [a, b]


def design_hair():
    rng = np.random.default_rng(3)
    df = pd.DataFrame({"length": rng.lognormal(0, 0.5, 90)})
    c = uw.Container.polygon(blob(400, 300, 300, 170, 0.05, 9))
    return dict(df=df, mark=icon("strand"), height="length", rotate=True, container=c,
                boundary="closed"), [c]


def design_strands(span=None):
    """Tall strands whose heights spread 94x: data-true, most of the container stays empty;
    ``span`` (``height_range=``) maps the heights linearly onto that range of px instead."""
    df = pd.DataFrame({"length": lognormal(90, 94, 5)})
    c = uw.Container.polygon(blob(400, 300, 300, 220, 0.05, 12))
    return dict(df=df, mark=icon("strand"), height="length", height_range=span, container=c,
                boundary="closed"), [c]


def design_raindrops():
    df = pd.DataFrame({"mm": lognormal(80, 30, 4)})
    c = uw.Container.polygon(blob(400, 300, 280, 250, 0.05, 11))
    return dict(df=df, mark=icon("raindrop"), size="mm", margin=0.4, orientation="to_center",
                container=c, boundary="closed"), [c]


def design_flowers():
    df = pd.DataFrame({"year": np.repeat(np.arange(5), 24), "v": lognormal(120, 8, 5)})
    c = two_piles()
    w = uw.UnitoPia(df, mark=icon("flower"), size="v", by="year", container=c, canvas=(W, H),
                    forces=[uw.DirectionalForce(90)], boundary="open", seed=0)
    for k in range(1, 5):
        w.layer(str(k)).set(blocks=[str(k - 1)])
    return w, [c]


def design_strata():
    """Five layers blocked in turn in two piles, largest marks first, each layer's
    linear size 4^(1/4)x below the last (4x from first to last)."""
    k = np.repeat(np.arange(5), 24)
    df = pd.DataFrame({"year": k, "v": lognormal(120, 4, 14) * 16.0 ** (-k / 4)})
    c = two_piles()
    w = uw.UnitoPia(df, mark="circle", size="v", by="year", container=c, canvas=(W, H),
                    forces=[uw.DirectionalForce(90)], boundary="open", seed=0)
    for j in range(1, 5):
        w.layer(str(j)).set(blocks=[str(j - 1)])
    return w, [c]


def design_strata_alike():
    """Four layers blocked in turn in one wide trapezoid under a downward force, largest
    first, 20/40/60/80 marks, each layer 2x smaller (linear) than the one before but alike
    within itself (a 3x spread of areas, too little to be packed by size)."""
    k = np.repeat(np.arange(4), [20, 40, 60, 80])
    df = pd.DataFrame({"year": k, "v": lognormal(200, 3, 41) * 4.0 ** -k})
    c = uw.Container.polygon([(100, 40), (700, 40), (620, 570), (180, 570)])
    w = uw.UnitoPia(df, mark="circle", size="v", by="year", container=c, canvas=(W, H),
                    forces=[uw.DirectionalForce(90)], boundary="open", seed=0)
    for j in range(1, 4):
        w.layer(str(j)).set(blocks=[str(j - 1)])
    return w, [c]


def design_flake_stack():
    """Three layers of snowflakes stacked in a vase under a downward force, open, at the
    default fill, 20/40/80 marks, 4x smaller from first to last: six thin arms pack far
    less densely than their ink, so a fill of half the vase overflows it."""
    k = np.repeat(np.arange(3), [20, 40, 80])
    df = pd.DataFrame({"year": k, "v": lognormal(140, 2, 1) * 4.0 ** (-k / 2)})
    c = uw.Container.polygon([(300, 40), (500, 40), (460, 150), (650, 350), (560, 570),
                              (240, 570), (150, 350), (340, 150)])
    w = uw.UnitoPia(df, mark=icon("snowflake"), size="v", by="year", color="year", container=c,
                    canvas=(W, H), forces=[uw.DirectionalForce(90)], boundary="open", seed=0)
    for j in (1, 2):
        w.layer(str(j)).set(blocks=[str(j - 1)])
    return w, [c]


def design_rings_strata():
    """Three layers blocked in turn around a point force, largest marks first, each layer's
    linear size 2x below the last (4x from first to last), enough marks to ring the one
    before: rings around the point."""
    k = np.repeat(np.arange(3), [20, 60, 180])
    df = pd.DataFrame({"ring": k, "v": lognormal(len(k), 4, 24) * 16.0 ** (-k / 2)})
    c = uw.Container.ellipse(400, 300, 380, 280)
    w = uw.UnitoPia(df, mark="circle", size="v", by="ring", color="ring", container=c,
                    canvas=(W, H), forces=[uw.PointForce(400, 300)], boundary="open", seed=0)
    for j in (1, 2):
        w.layer(str(j)).set(blocks=[str(j - 1)])
    return w, [c]


def design_pareto():
    """300 Pareto(0.6) values (a spread of about 760,000x) in a closed ellipse."""
    df = pd.DataFrame({"followers": np.random.default_rng(0).pareto(0.6, 300) + 1})
    c = uw.Container.ellipse(400, 300, 360, 260)
    return dict(df=df, mark="circle", size="followers", container=c, boundary="closed"), [c]


def design_seesaw():
    df = pd.DataFrame({"kind": ["work"] * 40 + ["life"] * 40, "hours": lognormal(80, 10, 6)})
    c = seesaw()
    w = uw.UnitoPia(df, mark="star", size="hours", by="kind", container=c, canvas=(W, H),
                    forces=[uw.DirectionalForce(90)], boundary="open", seed=0)
    w.layer("work").set(emitter=uw.CurveEmitter([(80, 60), (200, 40), (300, 60), (380, 50)]))
    w.layer("life").set(emitter=uw.CurveEmitter([(420, 50), (520, 40), (620, 60), (740, 50)]),
                        blocks=["work"])
    return w, [c]


def design_grid():
    df = pd.DataFrame({"v": np.ones(150)})
    c = uw.Container.rect(150, 100, 500, 400)
    return dict(df=df, mark="circle", size="v", container=c, boundary="closed",
                emitter=uw.GridEmitter(direction=90)), [c]


def design_beeswarm():
    """500 marks, x= a skewed column on a log scale, sizes spread 10x, in a wobbly blob."""
    rng = np.random.default_rng(22)
    df = pd.DataFrame({"v": rng.lognormal(2.0, 0.8, 500), "s": lognormal(500, 10, 22)})
    c = uw.Container.polygon(blob(400, 300, 330, 230, 0.12, 22))
    return dict(df=df, mark="circle", size="s", x="v", x_scale="log", container=c), [c]


def design_waffle():
    """300 squares in rows and columns, grouped by kind, in a wobbly blob."""
    rng = np.random.default_rng(23)
    df = pd.DataFrame({"kind": rng.choice(list("abcd"), 300)})
    c = uw.Container.polygon(blob(400, 300, 320, 240, 0.12, 23))
    return dict(df=df, mark="square", color="kind", order="kind", arrange="grid", margin=0.15,
                container=c), [c]


def design_rects():
    rect = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 20">'
                       '<rect width="40" height="20" fill="#e15759"/></svg>')
    c = uw.Container.polygon(blob(400, 300, 300, 220, 0.05, 12))
    return dict(df=pd.DataFrame({"v": np.ones(150)}), mark=rect, size="v", rotate=True,
                container=c, boundary="closed"), [c]


def design_suns():
    t = np.linspace(0, 2 * math.pi, 40)
    rays = [np.array([[50 + 24 * math.cos(a), 50 + 24 * math.sin(a)],
                      [50 + 40 * math.cos(a), 50 + 40 * math.sin(a)]])
            for a in np.linspace(0, 2 * math.pi, 9)[:-1]]
    sun = uw.Mark.sketch([np.c_[50 + 20 * np.cos(t), 50 + 20 * np.sin(t)]] + rays, width=4)
    df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1, 5, 80)})
    c = uw.Container.polygon(blob(400, 300, 330, 240, 0.05, 13))
    return dict(df=df, mark=sun, size="v", container=c, boundary="closed"), [c]


def design_rings():
    """Hollow marks: sketched rings and outlined SVG circles; their middles stay free."""
    t = np.linspace(0, 2 * math.pi, 41)
    ring = uw.Mark.sketch([np.c_[50 + 40 * np.cos(t), 50 + 40 * np.sin(t)]], width=7)
    circle = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><circle '
                         'cx="50" cy="50" r="44" fill="none" stroke="#4e79a7" stroke-width="6"/></svg>')
    df = pd.DataFrame({"v": lognormal(90, 30, 14)})
    c = uw.Container.polygon(blob(400, 300, 330, 240, 0.05, 15))
    return dict(df=df, mark=[ring, circle], size="v", container=c, boundary="closed"), [c]


def faint_alpha_png(path) -> np.ndarray:
    """Two touching black rings on white, as a PNG whose alpha channel has 0.3% slightly
    transparent pixels (alpha 200..250), as real exported container PNGs do; returns the
    drawn rings, bool (H, W)."""
    y, x = np.mgrid[0:H, 0:W] + 0.5
    ink = np.zeros((H, W), bool)
    for cx in (245, 555):
        r = np.hypot(x - cx, y - 300)
        ink |= (r <= 155) & (r >= 60)
    rgba = np.full((H, W, 4), 255, np.uint8)
    rgba[ink, :3] = 0
    rng = np.random.default_rng(16)
    faint = rng.choice(W * H, int(0.003 * W * H), replace=False)
    rgba.reshape(-1, 4)[faint, 3] = rng.integers(200, 251, len(faint))
    Image.fromarray(rgba).save(path)
    return ink


def design_faint_png():
    """The container handed over as a PNG path with faint alpha pixels; measured against
    the rings as drawn, not as read."""
    path = os.path.join(tempfile.gettempdir(), "uw-faint-rings.png")
    drawn = uw.Container.image(faint_alpha_png(path))
    df = pd.DataFrame({"v": lognormal(100, 40, 17)})
    return dict(df=df, mark="circle", size="v", container=uw.Container.image(path),
                boundary="closed"), [drawn]


def bowl(cx: float, half: float = 115, rim: float = 150, floor: float = 560) -> uw.Container:
    """A bowl: the lower half of an ellipse of half width ``half``, open at its rim (px)."""
    t = np.linspace(0, math.pi, 33)
    return uw.Container.polygon(np.c_[cx + half * np.cos(t), rim + (floor - rim) * np.sin(t)])


def design_bowls():
    """Nine layers stacked three to a bowl in three bowls, each blocked on the one below it
    in its bowl, under a downward force; sizes spread 10x."""
    k = np.repeat(np.arange(9), 20)
    df = pd.DataFrame({"layer": k, "v": lognormal(180, 10, 18)})
    bowls = [bowl(cx) for cx in (140, 400, 660)]
    w = uw.UnitoPia(df, mark="circle", size="v", by="layer", canvas=(W, H), seed=0, piles=None,
                    forces=[uw.DirectionalForce(90)], boundary="open")
    for j in range(9):
        w.layer(str(j)).set(container=bowls[j // 3], blocks=[str(j - 1)] if j % 3 else [])
    return w, bowls


def design_page():
    """A closed page with a margin of 0.4 and drops turned to its centre."""
    df = pd.DataFrame({"mm": lognormal(80, 30, 19)})
    c = uw.Container.rect(60, 40, 680, 520)
    return dict(df=df, mark=icon("raindrop"), size="mm", margin=0.4, orientation="to_center",
                container=c, boundary="closed"), [c]


def flake(arms: int, branch: float, width: float, colour: str) -> uw.Mark:
    """A line-drawn snowflake: ``arms`` spokes, each with a pair of side branches at
    ``branch`` (share of the spoke), strokes ``width`` wide (viewBox units of 100)."""
    lines = []
    for a in np.linspace(0, 2 * math.pi, arms, endpoint=False) - math.pi / 2:
        u = np.array([math.cos(a), math.sin(a)])
        lines.append((50, 50, *(50 + 44 * u)))
        b = 50 + 44 * branch * u
        for turn in (0.6, -0.6):
            v = np.array([math.cos(a + turn), math.sin(a + turn)])
            lines.append((*b, *(b + 16 * v)))
    body = "".join(f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}"/>'
                   for x1, y1, x2, y2 in lines)
    return uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
                       f'<g stroke="{colour}" stroke-width="{width}" stroke-linecap="round">'
                       f'{body}</g></svg>')


def lettering() -> uw.Container:
    """A page around the block letters LIFE: each letter a hole made of rectangles that
    meet edge to edge (none overlap, so the holes stay holes)."""
    def box(x, y, w, h):
        return ring_path([(x, y), (x + w, y), (x + w, y + h), (x, y + h)])
    holes = [box(120, 200, 40, 200), box(160, 360, 80, 40),                        # L
             box(290, 200, 40, 200),                                               # I
             box(380, 200, 40, 200), box(420, 200, 90, 40), box(420, 280, 70, 40),  # F
             box(560, 200, 40, 200), box(600, 200, 90, 40), box(600, 280, 70, 40),
             box(600, 360, 90, 40)]                                                # E
    return uw.Container.path(box(40, 60, 720, 480) + " " + " ".join(holes))


def design_lettering():
    """Seven kinds of snowflakes in the region around lettering, closed, margin 0.1."""
    kinds = [flake(a, b, w, c) for a, b, w, c in (
        (6, 0.55, 6, "#4e79a7"), (6, 0.35, 8, "#76b7b2"), (8, 0.5, 5, "#59a14f"),
        (5, 0.6, 7, "#9c755f"), (6, 0.75, 5, "#af7aa1"), (12, 0.6, 4, "#4e79a7"),
        (7, 0.45, 6, "#76b7b2"))]
    df = pd.DataFrame({"v": lognormal(140, 20, 20)})
    c = lettering()
    return dict(df=df, mark=kinds, size="v", margin=0.1, container=c, boundary="closed"), [c]


def design_ties_margin():
    """400 upright raindrops of three tied sizes (1, 5 and 20; 205, 148 and 47 rows) with a
    margin of 0.2 in the necked container: the median mark is the smallest, so the margin
    bands of the largest (their own size's, before design version 4) border room a checker
    counts as empty."""
    df = pd.DataFrame({"v": np.repeat([1.0, 5.0, 20.0], [205, 148, 47])})
    c = neck_container()
    return dict(df=df, mark=icon("raindrop"), size="v", margin=0.2, container=c,
                boundary="closed"), [c]


def design_ties_wide():
    """The same tied drops (seeded counts) turned to the centre of a wobbly blob, margin 0.4:
    with each mark's own margin the large drops' moats read as 19-21% empty."""
    counts = np.random.default_rng(3).multinomial(400, [0.51, 0.37, 0.12])
    df = pd.DataFrame({"v": np.repeat([1.0, 5.0, 20.0], counts)})
    c = uw.Container.polygon(blob(400, 300, 340, 250, 0.06, 11))
    return dict(df=df, mark=icon("raindrop"), size="v", margin=0.4, orientation="to_center",
                container=c, boundary="closed"), [c]


DESIGNS = {"bubbles": design_bubbles, "snowflakes": design_snowflakes, "bags": design_bags,
           "bags-independent": lambda: design_bags("independent"), "hair": design_hair,
           "strands": design_strands, "strands-range": lambda: design_strands((20, 80)),
           "raindrops": design_raindrops, "flowers": design_flowers, "seesaw": design_seesaw,
           "grid90": design_grid, "rects": design_rects, "suns": design_suns,
           "rings": design_rings, "faint-png": design_faint_png,
           "strata": design_strata, "strata-alike": design_strata_alike, "rings-strata": design_rings_strata, "pareto": design_pareto, "beeswarm": design_beeswarm,
           "waffle": design_waffle, "bowls": design_bowls, "page": design_page,
           "lettering": design_lettering, "ties-margin": design_ties_margin,
           "ties-wide": design_ties_wide,
           "flake-stack": design_flake_stack}


def build(name):
    made, containers = DESIGNS[name]()
    if isinstance(made, dict):
        df = made.pop("df")
        made = uw.UnitoPia(df, canvas=(W, H), seed=0, **made)
    return made, containers


def mask_png(containers, path):
    cov = sum(np.asarray(c.coverage((W, H), 1.0)) for c in containers)
    Image.fromarray(np.where(cov >= 0.5, 0, 255).astype(np.uint8)).save(path)


def measure(name, tool, out):
    w, containers = build(name)
    t0 = time.perf_counter()
    w.run(wait=True)
    seconds = time.perf_counter() - t0
    svg, png, mask = (os.path.join(out, f"{name}.{e}") for e in ("svg", "png", "mask.png"))
    w.save(svg, legend=False)   # the bare chart: a legend widens the SVG past the mask
    w.save(png, legend=False)
    mask_png(containers, mask)
    size = w.layers[0].encodings["size"]
    args = [sys.executable, tool, svg, "--container", mask]
    if size is not None:
        values = os.path.join(out, f"{name}.values.json")
        with open(values, "w") as f:
            json.dump({str(k): float(v) for k, v in w.df[size].items()}, f)
        args += ["--values", values]
    m = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
    table = w.placements
    heights = [float(table[table.layer == layer.name]["y"].mean()) for layer in w.layers]
    points = [f for f in w.layers[0].forces if isinstance(f, uw.PointForce)]
    if len(points) == 1:   # rings: the mean distance from the point instead
        heights = [float(np.hypot(*(table[table.layer == layer.name][["x", "y"]]
                                    - [points[0].x, points[0].y]).to_numpy().T).mean())
                   for layer in w.layers]
    closed = all(layer.boundary == "closed" for layer in w.layers)
    return {"design": name, "seconds": seconds, "overlap": m.get("overlap"),
            "outside": m.get("outside"), "empty": m.get("empty") if closed else None,
            "cv": m.get("fidelity_cv"), "heights": heights if len(heights) > 1 else None}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("names", nargs="*", default=list(DESIGNS))
    ap.add_argument("--tool", default="/work/shared/tools/measure_svg.py")
    ap.add_argument("--out", default=os.path.join(tempfile.gettempdir(), "uw-designs"))
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    pct = lambda v: "" if v is None else f"{100 * v:.2f}"  # noqa: E731
    print("| design | s | overlap % | outside % | empty % | area CV | mean y per layer |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for name in a.names:
        try:
            r = measure(name, a.tool, a.out)
        except Exception as exc:   # noqa: BLE001  (a design the engine refuses: say so, go on)
            print(f"| {name} | failed: {type(exc).__name__}: {exc} |||||", flush=True)
            continue
        hs = "" if r["heights"] is None else " ".join(f"{h:.0f}" for h in r["heights"])
        cv = "" if r["cv"] is None else f"{r['cv']:.3f}"
        print(f"| {name} | {r['seconds']:.1f} | {pct(r['overlap'])} | {pct(r['outside'])} | "
              f"{pct(r['empty'])} | {cv} | {hs} |", flush=True)


if __name__ == "__main__":
    main()
