"""Each distinct mark rendered once, then composited at every unit it draws.

A unit draws its layer's mark in its colour: the distinct (mark, colour) pairs are
rendered from their vector art by resvg, many in one atlas (one render, not one
per pair), each at the largest size a unit draws it. Every unit then pastes its
sprite resized and rotated, centred on its place (the SVG export's transform: the
mark's box centred on (x, y), rotated clockwise, scaled to its size).

``Compositor`` pastes the sprites for the PNG export, the settling's film and the
story's film alike. ``chart_png`` draws a laid-out chart so: the page under the
units (background, outlines), the units, then the overlay (legend, title,
caption). resvg builds one
node tree per ``<use>`` and refuses a document past its node limit, and its time
grows with the nodes: 20,000 units of a 51-element icon drawn as one SVG fail,
composited they take one small render.
"""
from __future__ import annotations

import io
from dataclasses import replace
from math import floor

import numpy as np
from PIL import Image

from ..io.svgsafe import SVG_NS
from .export import png_array, svg_size, to_svg

ATLAS_SIDE = 4096        # px: an atlas row's width (a wider sprite has a row of its own)
ATLAS_NODES = 200_000    # element tags in one atlas render, far inside resvg's limit
CACHE_PX = 1 << 25       # px of resized, rotated sprites kept for reuse (128 MB)


def distinct(table, layers, colors) -> tuple[list, np.ndarray]:
    """The units' distinct ``(mark, colour)`` pairs in first-seen order, and ``(N,)``
    int: the pair each unit draws. ``table``: the placements (``layer``, ``mark``)."""
    by_name = {layer.name: layer for layer in layers}
    ids: dict = {}
    pairs = []
    kind = np.empty(len(table), dtype=int)
    for n, key in enumerate(zip(table["layer"], table["mark"], colors)):
        k = ids.get(key)
        if k is None:
            k = ids[key] = len(pairs)
            pairs.append((by_name[key[0]].marks[key[1]], key[2]))
        kind[n] = k
    return pairs, kind


def sprites(pairs, sizes) -> list[Image.Image]:
    """RGBA sprites of ``pairs`` (``(mark, colour)``), the mark's box stretched to
    ``sizes`` (``(K, 2)`` px, rounded, at least 1: a unit drawn at its sprite's size is
    pasted unresampled). Packed in rows into atlases of at most
    ``ATLAS_SIDE`` px across and ``ATLAS_NODES`` tags, each atlas one resvg render."""
    sizes = np.maximum(1, np.rint(np.asarray(sizes, dtype=float)).astype(int)).reshape(-1, 2)
    fragments = [mark.svg_fragment(f"s{k}", color) for k, (mark, color) in enumerate(pairs)]
    out: list = [None] * len(pairs)
    batch, nodes = [], 0
    for k in sorted(range(len(pairs)), key=lambda k: -sizes[k, 1]):   # tall first: even rows
        tags = fragments[k].count("<")
        if batch and nodes + tags > ATLAS_NODES:
            _atlas(batch, fragments, pairs, sizes, out)
            batch, nodes = [], 0
        batch.append(k)
        nodes += tags
    if batch:
        _atlas(batch, fragments, pairs, sizes, out)
    return out


def _atlas(batch, fragments, pairs, sizes, out) -> None:
    """Render the sprites ``batch`` (indices) into atlases ``ATLAS_SIDE`` px across, one
    px apart, and cut them out into ``out``."""
    while batch:
        cells, x, y, row_h, width = [], 0, 0, 0, 0
        for i, k in enumerate(batch):
            w, h = sizes[k]
            if x and x + w > ATLAS_SIDE:   # next row
                x, y, row_h = 0, y + row_h + 1, 0
            if cells and y + h > ATLAS_SIDE:   # this atlas is full: the rest in the next
                break
            cells.append((k, x, y))
            x, row_h, width = x + w + 1, max(row_h, h), max(width, x + w)
        else:
            i = len(batch)
        batch = batch[i:]
        height = max(y + sizes[k, 1] for k, _, y in cells)
        body = []
        for k, cx, cy in cells:
            bw, bh = pairs[k][0].box_size
            body.append(f'<svg x="{cx}" y="{cy}" width="{sizes[k, 0]}" height="{sizes[k, 1]}" '
                        f'viewBox="0 0 {bw:.6g} {bh:.6g}" preserveAspectRatio="none">'
                        f'<use href="#s{k}"/></svg>')
        svg = (f'<svg xmlns="{SVG_NS}" xmlns:xlink="http://www.w3.org/1999/xlink" '
               f'width="{width}" height="{height}" viewBox="0 0 {width} {height}">'
               f'<defs>{"".join(fragments[k] for k, _, _ in cells)}</defs>{"".join(body)}</svg>')
        atlas = Image.fromarray(png_array(svg, (width, height)), "RGBA")
        for k, cx, cy in cells:
            out[k] = atlas.crop((cx, cy, cx + sizes[k, 0], cy + sizes[k, 1]))


def clipped(art: list, kind: np.ndarray, clips: np.ndarray) -> tuple[list, np.ndarray]:
    """``art`` with a sprite added for each distinct (sprite, clip below 1): the sprite with
    its columns past that share of its width cleared (a partial mark, ``to_svg``'s
    clipPath), and ``kind`` pointing the clipped units at theirs."""
    art, kind, made = list(art), kind.copy(), {}
    for n in np.nonzero(clips < 1)[0]:
        key = (int(kind[n]), float(clips[n]))
        if key not in made:
            cut = art[key[0]].copy()
            keep = int(round(cut.width * key[1]))
            cut.paste((0, 0, 0, 0), (keep, 0, cut.width, cut.height))
            made[key] = len(art)
            art.append(cut)
        kind[n] = made[key]
    return art, kind


def tile(sprite: Image.Image, w: int, h: int, angle: int) -> Image.Image:
    """``sprite`` at ``w`` x ``h`` px, rotated ``angle`` degrees clockwise (RGBA; the
    rotation grows it to hold the corners)."""
    im = sprite if sprite.size == (w, h) else sprite.resize((w, h), Image.BILINEAR)
    return im.rotate(-angle, Image.BICUBIC, expand=True) if angle else im


class Compositor:
    """Draws units as sprites over a backdrop: each sprite resized, rotated and faded
    once per (size, angle, opacity) it is drawn at, then pasted.

    ``sprites``: RGBA images, one per art; ``origin``: the canvas point at the top-left
    pixel; ``scale``: output px per canvas px. The backdrop is RGB (a film's frame) or
    RGBA whose colour is premultiplied by its alpha (Pillow's "RGBa" bytes labelled RGBA,
    a transparent page): there the paste of an opaque tile masked by its alpha is the
    premultiplied "over", ``out = src * a + dst * (1 - a)`` in every channel."""

    OPACITY_STEPS = 32   # opacities are drawn in 1/32 steps

    def __init__(self, sprites: list[Image.Image], origin=(0.0, 0.0), scale: float = 1.0):
        self.sprites, self.origin, self.scale = sprites, origin, scale
        self._cache: dict = {}
        self._cached = 0   # px held by the cache
        self._fade = [[round(v * q / self.OPACITY_STEPS) for v in range(256)]
                      for q in range(self.OPACITY_STEPS + 1)]

    def draw(self, back: Image.Image, kind: np.ndarray, states: np.ndarray) -> Image.Image:
        """``back`` (RGB, or premultiplied RGBA) with units drawn in order; ``kind`` ``(N,)``
        art index, ``states`` ``(N, 6)``: x, y (canvas px), angle (degrees clockwise), drawn
        w, h (canvas px), opacity in [0, 1]."""
        im = back.copy()
        core = im.im   # the pixel store: its paste skips Image.paste's per-call checks (x5 here)
        wh = np.rint(states[:, 3:5] * self.scale).astype(int)
        ang = np.rint(states[:, 2]).astype(int) % 360
        xy = (states[:, :2] - self.origin) * self.scale
        fade = np.rint(np.clip(states[:, 5], 0, 1) * self.OPACITY_STEPS).astype(int)
        cache = self._cache
        for k, w, h, a, q, x, y in zip(kind.tolist(), wh[:, 0].tolist(), wh[:, 1].tolist(),
                                       ang.tolist(), fade.tolist(), xy[:, 0].tolist(),
                                       xy[:, 1].tolist()):
            if w < 1 or h < 1 or q == 0:
                continue
            stores = cache.get((k, w, h, a, q, im.mode))
            if stores is None:
                if self._cached > CACHE_PX:
                    cache.clear()
                    self._cached = 0
                stores = cache[(k, w, h, a, q, im.mode)] = self._tile(k, w, h, a, q, im.mode)
                self._cached += stores[2] * stores[3]
            src, alpha, tw, th = stores
            x0, y0 = floor(x - tw / 2 + 0.5), floor(y - th / 2 + 0.5)
            core.paste(src, (x0, y0, x0 + tw, y0 + th), alpha)
        return im

    def _tile(self, k: int, w: int, h: int, angle: int, q: int, mode: str) -> tuple:
        """Sprite ``k`` at ``w`` x ``h`` px rotated ``angle`` degrees clockwise at opacity
        ``q`` steps: the pixel stores of its colour (``mode``, opaque) and alpha, and its
        width and height."""
        im = tile(self.sprites[k], w, h, angle)
        alpha = im.getchannel("A")
        if q < self.OPACITY_STEPS:
            alpha = alpha.point(self._fade[q])
        if mode == "RGB":
            src = im.convert("RGB")
        else:
            src = im.copy()
            src.putalpha(255)
        return src.im, alpha.im, im.width, im.height


def _page_png(svg: str, scale: float) -> Image.Image:
    return Image.fromarray(png_array(svg, svg_size(svg), scale), "RGBA")


def chart_png(canvas, table, layers, colors, background=None, page=None, under: str = "",
              scale: float = 1.0) -> bytes:
    """PNG bytes of the chart ``to_svg`` draws from the same arguments, at ``scale`` px
    per canvas px: its page drawn by resvg, its units composited from sprites."""
    w, h = canvas
    vx, vy, vw, vh = page.view if page is not None else (0, 0, w, h)
    none = table.iloc[:0]
    over = under_units = None
    if page is not None and page.overlay:
        over = _page_png(to_svg(canvas, none, layers, [], [], None, page, ""), scale)
    if background is not None or under:
        bare = replace(page, overlay="") if page is not None else None
        under_units = _page_png(to_svg(canvas, none, layers, [], [], background, bare, under), scale)
    drawn = under_units if under_units is not None else over   # resvg's size: every layer's
    size = drawn.size if drawn is not None else (max(1, int(round(vw * scale))),
                                                 max(1, int(round(vh * scale))))
    image = under_units if under_units is not None else Image.new("RGBA", size, (0, 0, 0, 0))
    pairs, kind = distinct(table, layers, colors)
    boxes = np.array([mark.box_size for mark, _ in pairs], dtype=float).reshape(-1, 2)
    cols = table[["x", "y", "angle", "sx", "sy"]].to_numpy(dtype=float)
    drawn = boxes[kind] * cols[:, 3:5]                                  # (N, 2) canvas px
    biggest = np.zeros((len(pairs), 2))
    np.maximum.at(biggest, kind, drawn * scale)
    art = sprites(pairs, biggest)
    if "drawn" in table and (table["drawn"] < 1).any():
        art, kind = clipped(art, kind, table["drawn"].to_numpy(dtype=float))
    # premultiplied colour, labelled RGBA for the compositor's "over"
    image = Image.frombytes("RGBA", size, image.convert("RGBa").tobytes())
    states = np.column_stack([cols[:, :3], drawn, np.ones(len(cols))])
    image = Compositor(art, (vx, vy), scale).draw(image, kind, states)
    image = Image.frombytes("RGBa", size, image.tobytes()).convert("RGBA")
    if over is not None:
        image.alpha_composite(over)
    buf = io.BytesIO()
    image.save(buf, "PNG")
    return buf.getvalue()
