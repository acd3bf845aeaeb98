"""A story as a film: each slide held, the transitions between them (GIF, WebP, MP4, WebM).

Every distinct mark art of every slide is rendered once (``composite.sprites``) at the
largest size it is drawn at, and each frame is composited by ``composite.Compositor``
over the slides' pages without their units, cross-faded during a transition. All
slides are framed by one box, the union of their pages (canvas px).
"""
from __future__ import annotations

import numpy as np
from PIL import Image

from . import transition
from .animation import backdrop, view_of
from .composite import Compositor, distinct, sprites


def union_view(svgs) -> tuple[float, float, float, float]:
    """The box (x, y, w, h) holding every slide's page."""
    boxes = np.array([view_of(s) for s in svgs])
    x0, y0 = boxes[:, 0].min(), boxes[:, 1].min()
    x1, y1 = (boxes[:, 0] + boxes[:, 2]).max(), (boxes[:, 1] + boxes[:, 3]).max()
    return float(x0), float(y0), float(x1 - x0), float(y1 - y0)


def palette(frames: list[Image.Image], count: int = 12) -> Image.Image:
    """``count`` frames spread over the film, side by side: the colours a GIF keeps."""
    picked = [frames[i] for i in np.linspace(0, len(frames) - 1, min(count, len(frames))).astype(int)]
    w, h = picked[0].size
    sheet = Image.new("RGB", (w * len(picked), h))
    for i, im in enumerate(picked):
        sheet.paste(im, (i * w, 0))
    return sheet


def render(slides, plans, fps: float, hold: float, seconds: float,
           scale: float = 1.0) -> list[Image.Image]:
    """The story's frames, RGB. ``slides``: per slide ``(chart, svg, states)``, ``states``
    ``(N, 5)`` as ``transition.slide_states``; ``plans``: one ``transition.Plan`` per
    consecutive pair; each slide shows ``hold`` s, each transition ``seconds`` s or longer
    when a unit travels far (``transition.frame_count``)."""
    view = union_view([svg for _, svg, _ in slides])
    backs = [backdrop(svg, scale, view) for _, svg, _ in slides]
    ids: dict = {}
    kinds, art, big = [], [], []
    for chart, _, states in slides:   # one sprite per art over all slides, at its largest size
        found, kind = distinct(chart.laid.placements, chart.layers, chart.laid.units.colors)
        local = []
        for mark, color in found:
            key = (mark.svg_fragment("m", color), tuple(float(v) for v in mark.box_size))
            if key not in ids:
                ids[key] = len(art)
                art.append((mark, color))
                big.append(np.zeros(2))
            local.append(ids[key])
        glob = np.array(local, dtype=int)[kind]
        for k in np.unique(glob):
            big[k] = np.maximum(big[k], np.abs(states[glob == k, 3:5]).max(axis=0))
        kinds.append(glob)
    paint = Compositor(sprites(art, np.ceil(np.array(big).reshape(-1, 2) * scale)), view[:2], scale)
    held = max(1, int(round(fps * hold)))

    def still(k):
        states = slides[k][2]
        drawn = np.column_stack([states[:, :3], np.abs(states[:, 3:5]), np.ones(len(states))])
        return [paint.draw(backs[k], kinds[k], drawn)] * held

    out = still(0)
    for k, p in enumerate(plans):
        (_, _, sa), (_, _, sb) = slides[k], slides[k + 1]
        count = transition.frame_count(p, sa, sb, slides[k][0].canvas, round(fps * seconds))
        kind_a, kind_b = kinds[k][np.maximum(p.a, 0)], kinds[k + 1][np.maximum(p.b, 0)]
        kind = np.concatenate([kind_a, kind_b])
        alike = (p.a >= 0) & (p.b >= 0) & (kind_a == kind_b)   # the same sprite in both slides
        for t in np.linspace(0.0, 1.0, count)[1:-1]:
            now_a, now_b = transition.at(p, sa, sb, float(t))
            now_b[alike & (now_a[:, 5] == 1), 5] = 0.0   # drawn over itself: the one is enough
            states = np.concatenate([now_a, now_b])
            states[:, 3:5] = np.abs(states[:, 3:5])
            out.append(paint.draw(Image.blend(backs[k], backs[k + 1], float(t)), kind, states))
        out += still(k + 1)
    return out
