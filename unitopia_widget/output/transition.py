"""The transition from one slide of a story to the next, unit by unit.

A unit of a slide is keyed by its row (the DataFrame index label) and its occurrence:
a row that two layers of a slide draw is two units, the first matched with the
first of the other slide, the second with the second. A unit's state in a slide
is ``(x, y, angle, w, h)``: centre (canvas px), angle (degrees clockwise), drawn
width and height (canvas px).

Over a transition's time ``t`` in [0, 1] each unit starts after a delay, its rank
from left to right times ``STAGGER``, and travels in a straight line with
smoothstep easing for the remaining ``1 - STAGGER``; size, angle (the short way)
and position interpolate together. A unit drawn with the same mark in both slides
is covered by its new look fading in over it (a recolour); a unit whose mark changes
cross-fades; a unit that leaves fades out in place, one that enters fades in.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

STAGGER = 0.3   # share of the transition over which the units' starts are spread
MAX_STEP = 0.04   # most a unit moves between consecutive frames, a share of the canvas's short side
EASE_SLOPE = 1.5   # the steepest slope of smoothstep


def unit_keys(rows) -> list[tuple]:
    """``(row, occurrence)`` per unit, in unit order."""
    seen: dict = {}
    keys = []
    for row in rows:
        n = seen.get(row, 0)
        seen[row] = n + 1
        keys.append((row, n))
    return keys


def slide_states(table) -> np.ndarray:
    """``(N, 5)`` x, y, angle, w, h per unit of a placements table."""
    return table[["x", "y", "angle", "width", "height"]].to_numpy(dtype=np.float64)


@dataclass
class Plan:
    """Who goes where in one transition. Per moving, leaving or entering unit
    (``M`` of them): ``a``/``b`` the unit's index in the first/second slide (-1: not
    there), ``delay`` its start in [0, STAGGER], ``fade`` True where its mark changes."""

    a: np.ndarray
    b: np.ndarray
    delay: np.ndarray
    fade: np.ndarray

    def to_json(self) -> dict:
        return {"a": self.a.tolist(), "b": self.b.tolist(),
                "delay": np.round(self.delay, 5).tolist(), "fade": self.fade.astype(int).tolist()}


def plan(keys_a, keys_b, states_a, states_b, shape_a, shape_b) -> Plan:
    """The plan from slide a to slide b: ``keys_*`` as ``unit_keys`` gives, ``states_*``
    ``(N, 5)``, ``shape_*`` a comparable id of each unit's mark (colour aside)."""
    where_b = {k: i for i, k in enumerate(keys_b)}
    a, b = [], []
    for i, k in enumerate(keys_a):
        a.append(i)
        b.append(where_b.pop(k, -1))
    for k, j in where_b.items():   # entering units, in the second slide's order
        a.append(-1)
        b.append(j)
    a, b = np.array(a, dtype=int), np.array(b, dtype=int)
    x = np.where(a >= 0, states_a[np.maximum(a, 0), 0], states_b[np.maximum(b, 0), 0])
    rank = np.empty(len(a))
    rank[np.argsort(x, kind="stable")] = np.arange(len(a))
    delay = STAGGER * rank / max(1, len(a) - 1)
    fade = np.array([i >= 0 and j >= 0 and shape_a[i] != shape_b[j] for i, j in zip(a, b)], bool)
    return Plan(a, b, delay, fade)


def progress(p: Plan, t: float) -> np.ndarray:
    """``(M,)`` each unit's eased progress in [0, 1] at transition time ``t``."""
    u = np.clip((t - p.delay) / (1 - STAGGER), 0.0, 1.0)
    return u * u * (3 - 2 * u)


def at(p: Plan, states_a: np.ndarray, states_b: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
    """The drawn units at time ``t``: ``(M, 6)`` states (x, y, angle, w, h, opacity) of the
    first slide's units and of the second's, in plan order (draw the first under the second)."""
    u = progress(p, t)[:, None]
    here_a, here_b = p.a >= 0, p.b >= 0
    sa = np.where(here_a[:, None], states_a[np.maximum(p.a, 0)], states_b[np.maximum(p.b, 0)])
    sb = np.where(here_b[:, None], states_b[np.maximum(p.b, 0)], sa)
    turn = (sb[:, 2] - sa[:, 2] + 180.0) % 360.0 - 180.0
    now = sa + (sb - sa) * u
    now[:, 2] = sa[:, 2] + turn * u[:, 0]
    u = u[:, 0]
    done = u >= 1.0
    alpha_a = np.where(p.fade | ~here_b, 1.0 - u, np.where(done, 0.0, 1.0))
    alpha_b = u
    alpha_a[~here_a], alpha_b[~here_b] = 0.0, 0.0
    return (np.concatenate([now, alpha_a[:, None]], axis=1),
            np.concatenate([now, alpha_b[:, None]], axis=1))


def frame_count(p: Plan, states_a, states_b, canvas, count: int) -> int:
    """At least ``count`` frames (ends included), and enough that no unit moves more
    than ``MAX_STEP`` of the canvas's short side between consecutive frames."""
    both = (p.a >= 0) & (p.b >= 0)
    dist = np.hypot(*(states_b[p.b[both], :2] - states_a[p.a[both], :2]).T)
    longest = float(dist.max()) if len(dist) else 0.0
    need = longest * EASE_SLOPE / ((1 - STAGGER) * MAX_STEP * min(canvas))
    return max(2, int(count), int(np.ceil(need)) + 1)
