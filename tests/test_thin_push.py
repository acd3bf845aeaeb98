"""Thin marks feel a directional force as round marks do: a pile that legalising shrinks
stays pressed to where the force holds it (``rules/legalize.press``)."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from unitopia_widget.design.forces import DirectionalForce, PointForce
from unitopia_widget.layout.rules.legalize import press
from unitopia_widget.layout.step.placement import Placement

pytestmark = pytest.mark.usefixtures("one_thread")

BAR = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 120 10">'
                  '<rect width="120" height="10" fill="#555"/></svg>')


def test_thin_bars_pushed_right_pile_in_the_right_of_the_pen():
    # 30 bars 12:1 at fill 0.6 do not pack at the asked scale: legalising shrinks them by
    # half, and each shrink opened the gaps of the pile (mean x 0.54 of the pen, now 0.70)
    c = uw.Chart(pd.DataFrame({"v": np.random.default_rng(1).uniform(1, 3, 30)}), mark=BAR,
                 size="v", orientation=0.0, container=uw.Container.rect(20, 20, 260, 160),
                 boundary="open", canvas=(300, 200), fill=0.6,
                 forces=[uw.DirectionalForce(0)], seed=0)
    table = c.layout()
    assert c.result.phases.get("polish.legalize", 0) > 1      # the case: the scale gave way
    assert (table["x"].mean() - 20) / 260 > 0.6               # within the right 40%


def test_a_shrinking_pile_is_pressed_along_its_pull_to_its_deepest_mark():
    center = np.array([[10.0, 0.0], [30.0, 5.0], [50.0, 0.0], [0.0, 0.0]])
    place = Placement(center, np.zeros(4), np.ones(4, bool),
                      np.zeros(4, bool), "cpu")
    optimizer = torch.optim.Adam([place.t])
    layers = [(torch.tensor([0, 1, 2]), [DirectionalForce(0)]),
              (torch.tensor([3]), [PointForce(0, 0)])]       # a point holds no floor: left
    press(place, optimizer, layers, np.full(4, 0.9))
    moved = place.t.detach().numpy()
    # 10% of each depth above the deepest centre (x 50), along the pull only
    assert moved[:, 0] == pytest.approx([14.0, 32.0, 50.0, 0.0])
    assert moved[:, 1] == pytest.approx(center[:, 1])
