"""Marks of every kind the repository supports, made in code or read from its data folders.

Each maker takes a ``numpy.random.Generator`` and a folder for files it writes, and returns
``(label, mark or list of marks, thin)``; ``thin`` is True for marks 10:1 or thinner, which
the generator may give ``height=`` or an orientation.
"""
from __future__ import annotations

import math
import os

import numpy as np
from PIL import Image, ImageDraw

import unitopia_widget as uw
from designs import flake   # benchmarks/designs.py: the line-drawn snowflake

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STYLED = [os.path.join(ROOT, "benchmarks", "data", n + ".svg")
          for n in ("flower", "raindrop", "bag")]
STYLED += [os.path.join(ROOT, "notebooks", "data", n + ".svg")
           for n in ("daisy", "leaf", "tulip", "cornflower", "bubble", "pin")]
SHAPES = ["circle", "star", "square", "triangle", "heart", "drop", "hexagon", "diamond", "cross"]
ARROW = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 120 10"><defs><style>'
         '.shaft { fill: #4e79a7; } .tip { fill: #e15759; }</style></defs>'
         '<rect class="shaft" x="0" y="3" width="104" height="4"/>'
         '<path class="tip" d="M104 0 L120 5 L104 10 Z"/></svg>')


def shape(rng, folder):
    """A built-in shape, or two or three of them as a mark group."""
    names = list(rng.choice(SHAPES, size=int(rng.choice([1, 1, 2, 3])), replace=False))
    return "shape:" + "+".join(names), names if len(names) > 1 else names[0], False


def styled_icon(rng, folder):
    """An SVG icon whose colours come from a ``<style>`` block (or attributes and groups)."""
    path = STYLED[int(rng.integers(len(STYLED)))]
    return "icon:" + os.path.basename(path)[:-4], uw.Mark.svg(path), False


def png(rng, folder):
    """A PNG as saved by different editors: RGBA with alpha, grey with alpha (LA), a
    palette with a transparent index, RGB on a white background, or RGBA fully opaque."""
    mode = ["RGBA", "LA", "P", "RGB", "RGBA-opaque"][int(rng.integers(5))]
    side = int(rng.integers(48, 97))
    clear = mode in ("RGBA", "LA", "P")
    img = Image.new("RGBA", (side, side), (255, 255, 255, 0 if clear else 255))
    draw = ImageDraw.Draw(img)
    colour = tuple(int(c) for c in rng.integers(20, 200, 3)) + (255,)
    k = int(rng.integers(3, 7))
    pts = [(side / 2 + side * (0.46 if i % 2 == 0 else 0.22) * math.cos(math.pi * i / k),
            side / 2 + side * (0.46 if i % 2 == 0 else 0.22) * math.sin(math.pi * i / k))
           for i in range(2 * k)]
    draw.polygon(pts, fill=colour)
    draw.ellipse([side * 0.38, side * 0.38, side * 0.62, side * 0.62], fill=(255, 255, 255, 255))
    if mode == "LA":
        img = img.convert("LA")
    elif mode == "P":
        img = img.quantize(colors=8)
        img.info["transparency"] = img.getpixel((0, 0))   # the corner's palette index is clear
    elif mode == "RGB":
        img = img.convert("RGB")
    path = os.path.join(folder, f"mark-{mode}-{side}-{k}.png")
    img.save(path, **({"transparency": img.info["transparency"]} if mode == "P" else {}))
    return "png:" + mode, uw.Mark.image(path), False


def sun(rng) -> uw.Mark:
    """An outlined sun with 6 to 10 rays, sketched."""
    t = np.linspace(0, 2 * math.pi, 40)
    rays = [np.array([[50 + 24 * math.cos(a), 50 + 24 * math.sin(a)],
                      [50 + 40 * math.cos(a), 50 + 40 * math.sin(a)]])
            for a in np.linspace(0, 2 * math.pi, int(rng.integers(6, 11)), endpoint=False)]
    return uw.Mark.sketch([np.c_[50 + 20 * np.cos(t), 50 + 20 * np.sin(t)]] + rays, width=4)


def sketch(rng, folder):
    """A line-drawn sketch: an outlined sun with rays, a zigzag or a spiral."""
    kind = ["sun", "zigzag", "spiral"][int(rng.integers(3))]
    if kind == "sun":
        return "sketch:sun", sun(rng), False
    if kind == "zigzag":
        pts = np.c_[np.linspace(0, 60, 7), np.tile([0, 30], 4)[:7]]
        return "sketch:zigzag", uw.Mark.sketch([pts], width=5), False
    t = np.linspace(0, 5 * math.pi, 80)
    return "sketch:spiral", uw.Mark.sketch([np.c_[t * np.cos(t), t * np.sin(t)]], width=3), False


def hollow(rng, folder):
    """A ring: sketched, an outlined SVG circle, or the styled test icon with ``fill: none``."""
    kind = ["ring", "outline", "styled"][int(rng.integers(3))]
    if kind == "ring":
        t = np.linspace(0, 2 * math.pi, 41)
        return "hollow:ring", uw.Mark.sketch([np.c_[50 + 40 * np.cos(t), 50 + 40 * np.sin(t)]],
                                             width=7), False
    if kind == "outline":
        return "hollow:outline", uw.Mark.svg(
            '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><circle cx="50" '
            'cy="50" r="44" fill="none" stroke="#4e79a7" stroke-width="6"/></svg>'), False
    return "hollow:styled", uw.Mark.svg(os.path.join(ROOT, "tests", "data", "marks",
                                                     "class_styled.svg")), False


def spiky(rng, folder):
    """Thin-armed marks: the styled snowflake icon, or one to three drawn snowflakes."""
    if rng.random() < 0.4:
        return "spiky:snowflake", uw.Mark.svg(os.path.join(ROOT, "benchmarks", "data",
                                                           "snowflake.svg")), False
    k = int(rng.integers(1, 4))
    colours = ["#4e79a7", "#76b7b2", "#59a14f"]
    marks = [flake(int(rng.integers(5, 13)), float(rng.uniform(0.35, 0.75)),
                   float(rng.uniform(4, 8)), colours[i]) for i in range(k)]
    return f"spiky:flakes{k}", marks if k > 1 else marks[0], False


def thin(rng, folder):
    """Marks 10:1 or thinner: an arrow 12:1 (styled), a strand of hair 12:1 (styled), a bar 10:1."""
    kind = ["arrow", "strand", "bar"][int(rng.integers(3))]
    if kind == "arrow":
        return "thin:arrow", uw.Mark.svg(ARROW), True
    if kind == "strand":
        return "thin:strand", uw.Mark.svg(os.path.join(ROOT, "benchmarks", "data",
                                                       "strand.svg")), True
    return "thin:bar", uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 10">'
                                   '<rect width="100" height="10" fill="#f28e2b"/></svg>'), True


KINDS = {"shape": shape, "icon": styled_icon, "png": png, "sketch": sketch, "hollow": hollow,
         "spiky": spiky, "thin": thin}
