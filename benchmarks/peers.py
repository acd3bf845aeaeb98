"""pymunk, a physics engine, on the Table 1 set-up: the peer the engine is timed against.

Discs of the benchmark's radii (``discs.radii``: 60% of the container) start on
the engine's own start (``discs.lattice_start``: packed at the force point,
overlapping where sizes differ) or poured in (``discs.random_start``), inside a
static ring of segments, and fall towards the point force at the container's
bottom until they settle.

The pull is a constant acceleration ``GRAVITY`` towards the point (the engine's
point potential is the distance), applied every step to all bodies at once
through ``pymunk.batch`` (no Python per disc). Stopping: the discs' mean speed
below ``SETTLE_SPEED`` mean radii a second, checked every ``CHECK_EVERY`` steps
once a disc falling free would have moved one mean radius (the discs start at
rest), or ``MAX_STEPS``. Frictionless discs and walls (the engine's marks slide too),
one thread, pymunk's default bounding-box tree.

How it was tuned (1,000 discs, on the benchmark's 2-core CPU; the overlap is
the settled result's): for pymunk's lowest overlap at few steps.
- ``ITERATIONS`` 30 (as DESIGN.md's peer). 10x areas: 10 iterations 0.60%
  overlap (130 steps), 30 0.31% (80), 60 0.19% (70 steps, but 1.2 to 1.5x the
  time); heavy-tailed 1.07%, 0.59%, 0.32%; equal about 0.07% for all three.
- ``GRAVITY`` 100 px/s^2, ``DT`` 1/60 s: a settled pile keeps an overlap that
  grows with the pull (10x areas: 300 0.55%, 100 0.31%, 30 0.18% in 25% more steps).
- ``DAMPING`` 0.3 (velocity kept after one second): the overlap is the same for
  0.3, 0.8 and none (1.0), the steps fewest with 0.3 (equal: 90 against 130).
- ``SETTLE_SPEED`` 0.25 radii/s (0.004 radii a step); the solver's jitter floor
  is about 0.1 to 0.2. 0.1 takes 180 steps instead of 80 for 0.31% -> 0.19%
  overlap: later steps only shave the overlap slowly.
- The threaded solver (``Space(threaded=True)``, 2 threads) was 1.6x slower;
  the spatial hash no faster than the tree.
"""
from __future__ import annotations

import math
import time

import numpy as np
import pymunk
import pymunk.batch

from discs import CX, CY, FX, FY, R

DT = 1 / 60               # s a step
GRAVITY = 100.0           # px / s^2 towards the force point
ITERATIONS = 30           # solver iterations a step (pymunk's default is 10)
DAMPING = 0.3             # share of velocity kept after one second
SETTLE_SPEED = 0.25       # mean radii / s
CHECK_EVERY = 10          # steps
MAX_STEPS = 3000
RING_SEGMENTS, RING_THICKNESS = 256, 4.0   # the container: a polygon of capsules


def build(r: np.ndarray, start: np.ndarray) -> tuple[pymunk.Space, list[pymunk.Body]]:
    """A space with a static ring of radius ``R`` and one disc per radius ``r (n,)`` at
    ``start (n, 2)``; returns it and the discs' bodies, in the order of ``r``."""
    space = pymunk.Space()
    space.iterations = ITERATIONS
    space.damping = DAMPING
    rim = R + RING_THICKNESS   # capsule axes sit outside, so their inner surface is the circle
    angle = np.linspace(0, 2 * math.pi, RING_SEGMENTS + 1)
    ring = np.stack([CX + rim * np.cos(angle), CY + rim * np.sin(angle)], axis=1)
    for a, b in zip(ring[:-1], ring[1:]):
        wall = pymunk.Segment(space.static_body, tuple(a), tuple(b), RING_THICKNESS)
        wall.friction = 0.0
        space.add(wall)
    bodies = []
    for (x, y), ri in zip(start, r):
        mass = math.pi * ri * ri
        body = pymunk.Body(mass, pymunk.moment_for_circle(mass, 0, ri))
        body.position = float(x), float(y)
        disc = pymunk.Circle(body, float(ri))
        disc.friction = 0.0
        space.add(body, disc)
        bodies.append(body)
    return space, bodies


def settle(r: np.ndarray, start: np.ndarray) -> dict:
    """Run pymunk from ``start (n, 2)`` until the discs settle.

    Returns ``center (n, 2)`` in the order of ``r``, ``steps``, ``seconds``
    (building the space included).
    """
    t0 = time.perf_counter()
    space, bodies = build(r, start)
    fields = pymunk.batch.BodyFields.BODY_ID | pymunk.batch.BodyFields.POSITION
    state, force = pymunk.batch.Buffer(), pymunk.batch.Buffer()
    pymunk.batch.get_space_bodies(space, fields, state)   # the batch order includes static bodies
    where = {body_id: k for k, body_id in enumerate(memoryview(state.int_buf()).cast("P"))}
    rows = np.array([where[body.id] for body in bodies])
    mass = np.zeros((len(where), 1))
    mass[rows, 0] = math.pi * r * r   # static bodies get no pull
    fields = pymunk.batch.BodyFields.POSITION | pymunk.batch.BodyFields.VELOCITY
    limit = SETTLE_SPEED * float(r.mean())
    # at rest at first: no stop before a disc falling free would have moved one mean radius
    first = math.sqrt(2 * float(r.mean()) / GRAVITY) / DT
    steps = 0
    while True:
        state.clear()
        pymunk.batch.get_space_bodies(space, fields, state)
        pv = np.frombuffer(state.float_buf(), dtype=np.float64).reshape(-1, 4)   # x y vx vy
        if steps % CHECK_EVERY == 0 and steps >= first and (
                np.hypot(pv[rows, 2], pv[rows, 3]).mean() < limit or steps >= MAX_STEPS):
            break
        pull = np.stack([FX - pv[:, 0], FY - pv[:, 1]], axis=1)
        pull *= GRAVITY * mass / np.maximum(np.hypot(pull[:, 0], pull[:, 1]), 1e-6)[:, None]
        force.set_float_buf(pull.ravel())
        pymunk.batch.set_space_bodies(space, pymunk.batch.BodyFields.FORCE, force)
        space.step(DT)
        steps += 1
    return {"center": pv[rows, :2].copy(), "steps": steps, "seconds": time.perf_counter() - t0}
