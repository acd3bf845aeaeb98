"""The settling as a film: GIF and WebP (Pillow), MP4 and WebM (PyAV, extra ``[video]``).

Each distinct (layer, mark, colour) is rendered once from its vector art (resvg) at
the largest size it reaches, then every frame composites the sprites, resized and
rotated, over the page drawn without its units (background, outlines, legend,
title). A frame's unit transform is the SVG export's: the mark's box centred on
(x, y), rotated by the angle (degrees, clockwise on screen), scaled to its size.
The last frame is the final layout.
"""
from __future__ import annotations

import io
import os
import re
from numbers import Real

import numpy as np
from PIL import Image

from .composite import Compositor, clipped, distinct, sprites
from .export import png_array

FORMATS = (".gif", ".webp", ".mp4", ".webm")
VIDEO = {".mp4": ("libx264", {"preset": "veryfast", "crf": "20"}),
         ".webm": ("libvpx-vp9", {"deadline": "realtime", "cpu-used": "8", "crf": "30", "b": "0"})}
_UNIT = re.compile(r'<g class="unit"[^>]*><title>[^<]*</title><use href="#[^"]*"/></g>\n?')
_ROOT = re.compile(r'<svg([^>]*?) width="[^"]*" height="[^"]*" viewBox="[^"]*">')
_VIEW = re.compile(r'viewBox="([-\d.e]+) ([-\d.e]+) ([-\d.e]+) ([-\d.e]+)"')


def check_timing(fps, seconds) -> tuple[float, float]:
    """``fps`` in (0, 60], ``seconds`` in (0, 60]; None: 20 fps, 3 s."""
    fps = 20.0 if fps is None else fps
    seconds = 3.0 if seconds is None else seconds
    for name, v in (("fps", fps), ("seconds", seconds)):
        if not isinstance(v, Real) or isinstance(v, bool) or not 0 < v <= 60:
            raise ValueError(f"save: {name} must be a number in (0, 60], got {v!r:.40}")
    return float(fps), float(seconds)


def resample(frames: np.ndarray, count: int) -> np.ndarray:
    """``(count, N, 4)``: ``frames`` ``(F, N, 4)`` interpolated at ``count`` even times,
    the first and last kept exactly."""
    t = np.linspace(0.0, len(frames) - 1, max(2, count))
    lo = np.floor(t).astype(int)
    hi = np.minimum(lo + 1, len(frames) - 1)
    w = (t - lo)[:, None, None].astype(np.float32)
    return frames[lo] * (1 - w) + frames[hi] * w


def view_of(svg: str) -> tuple[float, float, float, float]:
    """The root viewBox of an exported SVG: x, y, width, height (canvas px)."""
    return tuple(float(v) for v in _VIEW.search(svg).groups())


def backdrop(svg: str, scale: float = 1.0, view=None) -> Image.Image:
    """The page of ``svg`` without its units, RGB over white, ``scale`` px per canvas px;
    ``view`` (x, y, w, h): the box drawn (default: the SVG's own viewBox)."""
    vx, vy, vw, vh = view_of(svg) if view is None else view
    page = _UNIT.sub("", svg)
    if view is not None:   # the same drawing, framed by another box
        page = _ROOT.sub(f'<svg\\1 width="{vw:.6g}" height="{vh:.6g}" viewBox="{vx:.6g} {vy:.6g} '
                         f'{vw:.6g} {vh:.6g}">', page, count=1)
    size = (max(1, int(round(vw * scale))), max(1, int(round(vh * scale))))
    art = Image.fromarray(png_array(page, (vw, vh), scale), "RGBA")
    back = Image.new("RGBA", size, "white")
    back.alpha_composite(art.resize(size) if art.size != size else art)
    return back.convert("RGB")


def render(chart, svg: str, fps=None, seconds=None, scale: float = 1.0) -> list[Image.Image]:
    """The settling's frames as RGB images over white, ``scale`` px per canvas px.
    ``svg``: the chart's export (its page without the units is the backdrop)."""
    fps, seconds = check_timing(fps, seconds)
    laid = chart.laid
    if laid is None or laid.frames is None:
        raise RuntimeError("no settling to animate: call run() (or run(wait=True)) first")
    units, table = laid.units, laid.placements
    frames = resample(laid.frames, int(round(fps * seconds)))
    vx, vy = view_of(svg)[:2]
    back = backdrop(svg, scale)
    pairs, kind = distinct(table, chart.layers, units.colors)
    # drawn size per frame and unit, canvas px
    drawn = 2 * np.stack([units.half_w, units.half_h], axis=1)[None] * frames[:, :, 3:4]
    big = np.zeros((len(pairs), 2))
    np.maximum.at(big, kind, drawn.max(axis=0) * scale)
    art = sprites(pairs, np.ceil(big))
    if "drawn" in table and (table["drawn"] < 1).any():   # partial marks, as in the PNG
        art, kind = clipped(art, kind, table["drawn"].to_numpy(dtype=float))
    paint = Compositor(art, (vx, vy), scale)
    opaque = np.ones((len(kind), 1), np.float32)
    return [paint.draw(back, kind, np.concatenate([f[:, :3], d, opaque], axis=1))
            for f, d in zip(frames, drawn)]


def write(path: str, images: list[Image.Image], fps: float, palette: Image.Image | None = None) -> bytes:
    """The encoded animation for ``path``'s extension (bytes; the caller writes them).
    ``palette``: the image whose colours a GIF keeps (default the last frame)."""
    ext = os.path.splitext(path)[1].lower()
    buf = io.BytesIO()
    ms = max(10, int(round(1000 / fps)))
    if ext == ".gif":   # one palette, the final layout's, for every frame: fast and steady
        palette = (images[-1] if palette is None else palette).quantize(
            255, method=Image.Quantize.FASTOCTREE)
        frames = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
        frames[0].save(buf, "GIF", save_all=True, append_images=frames[1:], duration=ms, loop=0)
    elif ext == ".webp":
        images[0].save(buf, "WEBP", save_all=True, append_images=images[1:], duration=ms, loop=0,
                       quality=85, method=0)
    elif ext in VIDEO:
        _video(buf, ext, images, fps)
    else:
        raise ValueError(f"save: an animation is {', '.join(FORMATS)}; got {ext!r}")
    return buf.getvalue()


def _video(buf, ext: str, images, fps: float) -> None:
    try:
        import av
    except ImportError:
        raise ImportError(f"save: writing {ext} needs PyAV; install the extra: "
                          f"pip install 'unitopia-widget[video]'") from None
    from fractions import Fraction

    codec, options = VIDEO[ext]
    w, h = images[0].size
    ew, eh = w + w % 2, h + h % 2   # yuv420p needs even sides
    with av.open(buf, "w", format="mp4" if ext == ".mp4" else "webm") as box:
        stream = box.add_stream(codec, rate=Fraction(fps).limit_denominator(1000), options=options)
        stream.width, stream.height, stream.pix_fmt = ew, eh, "yuv420p"
        for im in images:
            if (ew, eh) != (w, h):
                pad = Image.new("RGB", (ew, eh), "white")
                pad.paste(im)
                im = pad
            for packet in stream.encode(av.VideoFrame.from_image(im)):
                box.mux(packet)
        for packet in stream.encode():
            box.mux(packet)
