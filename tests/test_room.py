"""Room made for added rows and closed over removed ones (``layout.prepare.room``), and the
discs relaxed after (``layout.prepare.relax``)."""
import math

import numpy as np
import pytest

import unitopia_widget as uw
from unitopia_widget.layout.prepare.lattice import container_region
from unitopia_widget.layout.prepare.relax import Discs, relax, sample
from unitopia_widget.layout.prepare.room import radial_map, sites

SQUARE = container_region(uw.Container.rect(0, 0, 100, 100), (100, 100), 2.0)


def test_a_hole_opened_moves_marks_by_the_area_it_takes_and_not_beyond_its_reach():
    site, cell, q = np.array([50.0, 50.0]), math.pi * 4.0, 0.9   # a hole of radius 2
    reach = math.sqrt(4.0 / 0.1)                                  # ~6.3 px
    center = np.array([[53.0, 50.0], [50.0, 45.0], [50.0 + reach + 0.1, 50.0]])
    out = radial_map(center, site, cell, q)
    assert out[0] == pytest.approx([50.0 + math.sqrt(4.0 + 0.9 * 9.0), 50.0])
    assert out[1] == pytest.approx([50.0, 50.0 - math.sqrt(4.0 + 0.9 * 25.0)])
    assert out[2] == pytest.approx(center[2]), "beyond the reach nothing moves"


def test_a_hole_closed_pulls_marks_in_and_undoes_the_opened_one():
    site, cell, q = np.array([50.0, 50.0]), math.pi * 4.0, 0.9
    center = np.array([[53.0, 50.0], [47.0, 52.0]])
    opened = radial_map(center, site, cell, q)
    assert radial_map(opened, site, -cell / q, 1 / q) == pytest.approx(center)


def test_sites_keep_away_from_marks_the_edge_and_each_other():
    center = np.array([[25.0, 25.0], [75.0, 75.0], [0.0, 0.0]])
    taken = np.array([True, True, False])
    out = sites(SQUARE, center, np.full(3, 10.0), taken, np.array([20.0, 20.0]))
    assert np.hypot(*(out[0] - [25, 25])) > 30 and np.hypot(*(out[0] - [75, 75])) > 30
    assert np.hypot(*(out[0] - out[1])) > 20, "the second site is beyond the first one's reach"
    assert (SQUARE.depth_at(out) >= 20).all(), "as deep as their reach"


def test_bilinear_samples_and_their_gradient():
    field = np.array([[0.0, 2.0], [4.0, 6.0]])   # 2 x + 4 y at pixel centres, rho 1
    value, grad = sample(field, 1.0, np.array([[0.75, 1.0]]))
    assert value[0] == pytest.approx(0.25 * 2 + 0.5 * 4)
    assert grad[0] == pytest.approx([2.0, 4.0])


def test_the_energy_gradient_is_the_energys():
    rng = np.random.default_rng(0)
    center = rng.uniform(30, 70, (6, 2))
    radius = rng.uniform(5, 9, 6)
    free = np.array([0, 2, 3, 5])
    discs = Discs(radius, free, SQUARE)
    e, grad = discs.energy(center)
    assert e > 0
    for k, unit in enumerate(free):
        for a in range(2):
            step = center.copy()
            step[unit, a] += 1e-5
            assert (discs.energy(step)[0] - e) / 1e-5 == pytest.approx(grad[k, a], rel=1e-3, abs=1e-4)


def test_relaxed_discs_stop_overlapping_and_obstacles_stay():
    center = np.array([[50.0, 50.0], [55.0, 50.0], [96.0, 20.0]])   # the third pokes out
    radius = np.array([5.0, 5.0, 5.0])
    out = relax(center, radius, np.array([1, 2]), SQUARE, 100, 0.001)
    assert out[0] == pytest.approx(center[0]), "the obstacle stays"
    assert np.hypot(*(out[1] - out[0])) == pytest.approx(10.0, abs=0.05)
    assert out[2, 0] == pytest.approx(95.0, abs=0.3), "back inside its container"
