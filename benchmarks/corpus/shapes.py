"""Containers drawn in code on a ``W`` x ``H`` canvas: blobs, bands, necks, holes, letters,
PNG masks (with and without alpha), slopes, two touching rings, and plain controls.

Each maker takes a ``numpy.random.Generator`` and a folder for files it writes, and
returns ``(label, container)``. ``band`` also takes the number of marks and the share of
the band they cover, so that it is 3 to 6 mark widths wide.
"""
from __future__ import annotations

import math
import os

import numpy as np
from PIL import Image, ImageDraw, ImageFont

import unitopia_widget as uw

W, H = 480, 360


def wobbly(cx, cy, rx, ry, wobble, rng, n=48) -> np.ndarray:
    """A hand-drawn-looking closed curve around (cx, cy): (n, 2) polygon points."""
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    k = 1 + wobble * np.convolve(np.tile(rng.normal(0, 1, n), 3), np.ones(5) / 5, "same")[n:2 * n]
    return np.stack([cx + rx * k * np.cos(t), cy + ry * k * np.sin(t)], 1)


def ring_path(points) -> str:
    return "M " + " L ".join(f"{x:.1f} {y:.1f}" for x, y in points) + " Z"


def blob(rng, folder):
    rx, ry = rng.uniform(150, 220), rng.uniform(110, 160)
    pts = wobbly(W / 2, H / 2, rx, ry, rng.uniform(0.03, 0.12), rng)
    return "blob", uw.Container.polygon(pts)


def thicken(line: np.ndarray, width: float) -> np.ndarray:
    """The outline of a polyline (k, 2) drawn ``width`` px wide (mitred joins)."""
    d = np.diff(line, axis=0)
    n = np.c_[-d[:, 1], d[:, 0]] / np.hypot(d[:, 0], d[:, 1])[:, None]
    normals = np.r_[n[:1], n[:-1] + n[1:], n[-1:]]
    normals /= np.einsum("ij,ij->i", normals, np.r_[n[:1], n])[:, None]   # mitre length
    return np.r_[line + normals * width / 2, (line - normals * width / 2)[::-1]]


def band(rng, folder, n: int, share: float):
    """A V-shaped or arched band whose width is 3 to 6 widths of the marks that cover
    ``share`` of it when there are ``n`` of them (clamped to 16..120 px)."""
    if rng.random() < 0.5:
        drop = rng.uniform(80, 200)
        line = np.array([[40, 60], [W / 2, 60 + drop], [W - 40, 60]], float)
        shape = "V"
    else:
        t = np.linspace(math.pi * 1.1, math.pi * 1.9, 24)
        line = np.c_[W / 2 + 190 * np.cos(t), 330 + 250 * np.sin(t)]
        shape = "arch"
    length = float(np.hypot(*np.diff(line, axis=0).T).sum())
    widths = rng.uniform(3, 6)
    width = float(np.clip(widths ** 2 * length * share / n, 16, 120))
    side = math.sqrt(length * width * share / n)
    return f"band:{shape}:{width / side:.1f}w", uw.Container.polygon(thicken(line, width))


def neck(rng, folder):
    """Two wobbly lobes joined by a neck 24 to 70 px wide."""
    half = rng.uniform(12, 35)
    pts = []
    for cx, a0, a1, joint in ((120, 0.0, 2 * math.pi, (240, H / 2 + half)),
                              (360, math.pi, 3 * math.pi, (240, H / 2 - half))):
        r = rng.uniform(85, 105)
        gap = math.asin(min(0.95, half / r))
        for a in np.linspace(a0 + gap, a1 - gap, 40):
            k = 1 + 0.05 * math.sin(3 * a + cx) + 0.03 * math.sin(7 * a)
            pts.append((cx + r * k * math.cos(a), H / 2 - r * k * math.sin(a)))
        pts.append(joint)
    return f"neck:{2 * half:.0f}px", uw.Container.polygon(pts)


def holes(rng, folder):
    """A blob with 2 to 4 round holes that do not touch each other or the edge."""
    outer = wobbly(W / 2, H / 2, 210, 155, 0.04, rng)
    k, rings, centres = int(rng.integers(2, 5)), [], []
    while len(rings) < k:
        c = np.array([rng.uniform(110, 370), rng.uniform(90, 270)])
        r = rng.uniform(18, 40)
        if all(np.hypot(*(c - o)) > r + q + 25 for o, q in centres):
            centres.append((c, r))
            t = np.linspace(0, 2 * math.pi, 24, endpoint=False)
            rings.append(np.c_[c[0] + r * np.cos(t), c[1] + r * np.sin(t)])
    d = " ".join(ring_path(p) for p in [outer] + rings)
    return f"holes:{k}", uw.Container.path(d)


def letters(rng, folder):
    """Letters from Pillow's built-in scalable font: the marks fill the letters ("in") or
    the page around them ("around", the letters are holes)."""
    word = ["UW", "ZOO", "MAP", "OK"][int(rng.integers(4))]
    font = ImageFont.load_default(size=int(rng.uniform(150, 190)) if len(word) < 3 else 140)
    img = Image.new("L", (W, H), 0)
    draw = ImageDraw.Draw(img)
    x0, y0, x1, y1 = draw.textbbox((0, 0), word, font=font, stroke_width=6)
    draw.text(((W - x1 - x0) / 2, (H - y1 - y0) / 2), word, font=font, fill=255, stroke_width=6,
              stroke_fill=255)
    ink = np.asarray(img) > 127
    if rng.random() < 0.35:
        return f"letters:in:{word}", uw.Container.image(ink)
    y, x = np.mgrid[0:H, 0:W]
    page = (x >= 20) & (x < W - 20) & (y >= 20) & (y < H - 20)
    return f"letters:around:{word}", uw.Container.image(page & ~ink)


def png_mask(rng, folder):
    """A blob saved as a PNG: an opaque figure on a transparent background (RGBA), black on
    white without alpha (RGB, or grey L), or black on white with faint alpha pixels."""
    mode = ["RGBA", "RGB", "L", "faint"][int(rng.integers(4))]
    pts = [tuple(p) for p in wobbly(W / 2, H / 2, rng.uniform(150, 210), rng.uniform(110, 150),
                                    0.08, rng)]
    img = Image.new("RGBA", (W, H), (0, 0, 0, 0) if mode == "RGBA" else (255, 255, 255, 255))
    ImageDraw.Draw(img).polygon(pts, fill=(200, 60, 40, 255) if mode == "RGBA" else (0, 0, 0, 255))
    if mode in ("RGB", "L"):
        img = img.convert(mode)
    elif mode == "faint":
        a = np.array(img)
        pick = rng.choice(W * H, int(0.003 * W * H), replace=False)
        a.reshape(-1, 4)[pick, 3] = rng.integers(200, 251, len(pick))
        img = Image.fromarray(a)
    path = os.path.join(folder, f"container-{mode}-{rng.integers(1 << 30)}.png")
    img.save(path)
    return f"png:{mode}", uw.Container.image(path)


def slope(rng, folder):
    """The space above a tilted plank: a floor falling 60 to 160 px across the canvas."""
    fall = rng.uniform(60, 160)
    low, high = (H - 20, H - 20 - fall) if rng.random() < 0.5 else (H - 20 - fall, H - 20)
    return f"slope:{fall:.0f}px", uw.Container.polygon([(20, 20), (W - 20, 20), (W - 20, high),
                                                        (20, low)])


def twin_rings(rng, folder):
    """Two heads that touch: two discs, or two rings (annuli), joined by a narrow overlap."""
    r = rng.uniform(95, 115)
    join = rng.uniform(6, 20)                        # how far the two discs overlap, px
    y, x = np.mgrid[0:H, 0:W] + 0.5
    a = np.hypot(x - (W / 2 - r + join / 2), y - H / 2)
    b = np.hypot(x - (W / 2 + r - join / 2), y - H / 2)
    if rng.random() < 0.5:
        return f"twins:discs:{join:.0f}", uw.Container.image((a <= r) | (b <= r))
    inner = r * rng.uniform(0.3, 0.45)
    return f"twins:rings:{join:.0f}", uw.Container.image(((a <= r) & (a >= inner)) |
                                                          ((b <= r) & (b >= inner)))


def plain(rng, folder):
    if rng.random() < 0.5:
        return "plain:rect", uw.Container.rect(60, 40, 360, 280)
    return "plain:ellipse", uw.Container.ellipse(W / 2, H / 2, 200, 150)


KINDS = {"blob": blob, "band": band, "neck": neck, "holes": holes, "letters": letters,
         "png": png_mask, "slope": slope, "twins": twin_rings, "plain": plain}
