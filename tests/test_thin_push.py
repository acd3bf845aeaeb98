"""Thin marks feel a directional force as round marks do: a pile that legalising shrinks
stays pressed onto each mark's own floor (``rules/legalize.press``), and a pile's marks end
where their ink meets, not where their boxes do (``rules/drop``)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from ink import ink_metrics
from unitopia_widget.design.forces import DirectionalForce, PointForce
from unitopia_widget.layout.rules import drop
from unitopia_widget.layout.rules.legalize import press
from unitopia_widget.layout.step.placement import Placement
from unitopia_widget.layout.step.raster import RasterGrid

pytestmark = pytest.mark.usefixtures("one_thread")

BAR = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 120 10">'
                  '<rect width="120" height="10" fill="#555"/></svg>')


def test_thin_bars_pushed_right_pile_in_the_right_of_the_pen():
    # 30 bars 12:1 at fill 0.6 do not pack at the asked scale: legalising shrinks them, and
    # each shrink about their own centres opened the gaps of the pile (mean x 0.53 of the pen)
    c = uw.Chart(pd.DataFrame({"v": np.random.default_rng(1).uniform(1, 3, 30)}), mark=BAR,
                 size="v", orientation=0.0, container=uw.Container.rect(20, 20, 260, 160),
                 boundary="open", canvas=(300, 200), fill=0.6,
                 forces=[uw.DirectionalForce(0)], seed=0)
    table = c.layout()
    assert c.result.phases.get("polish.legalize", 0) > 1      # the case: the scale gave way
    assert (table["x"].mean() - 20) / 260 > 0.6               # within the right 40%


ARROW = uw.Mark.svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 96 8">'
                    '<rect x="0" y="3" width="82" height="2" fill="#333"/>'
                    '<polygon points="80,0 96,4 80,8" fill="#c33"/></svg>')


def arrows() -> uw.Chart:
    """60 arrows 12:1 whose heads stand taller than their shafts, pushed right at fill 0.5."""
    return uw.Chart(pd.DataFrame({"v": np.random.default_rng(1).uniform(1, 3, 60)}), mark=ARROW,
                    size="v", orientation=0.0, container=uw.Container.rect(20, 20, 360, 240),
                    boundary="open", fill=0.5, forces=[uw.DirectionalForce(0)], canvas=(400, 280),
                    seed=1)


def test_arrows_pushed_right_fall_until_their_ink_meets(monkeypatch):
    # the pile rested with the heads of staggered rows stopped on each other's boxes, a mean
    # x of 0.58 of the pen; dropped by their ink they pile in its right part (0.69); and an
    # arrow whose head then rests on another's steps aside, past it, and falls on (0.72)
    c = arrows()
    table = c.layout()
    assert c.result.phases.get("finish.drop") == 1
    pull = (table["x"].mean() - 20) / 360
    assert pull > 0.62
    assert ink_metrics(c.to_svg(legend=False), c.canvas)["overlap"] < 0.005
    monkeypatch.setattr(drop, "step_aside", lambda *args: None)
    straight = arrows()
    assert pull > (straight.layout()["x"].mean() - 20) / 360 + 0.015


def test_a_shrinking_pile_settles_onto_each_marks_own_floor():
    # a step: the floor is at y 100 left of x 50 and at y 50 right of it; boxes 16 px wide
    step = uw.Container.polygon([(0, 0), (100, 0), (100, 50), (50, 50), (50, 100), (0, 100)])
    p = SimpleNamespace(regions=(step, step), layer=np.array([0, 0, 0, 1]),
                        grid=RasterGrid((100, 100), 1.0, pad=2), terms=SimpleNamespace(rests=None),
                        half_w=np.full(4, 8.0), half_h=np.full(4, 8.0), margin=np.zeros(4))
    center = np.array([[25.0, 60.0], [25.0, 20.0], [75.0, 30.0], [25.0, 50.0]])
    place = Placement(center, np.zeros(4), np.ones(4, bool), np.zeros(4, bool), "cpu")
    optimizer = torch.optim.Adam([place.t])
    piles = [(torch.tensor([0, 1, 2]), [DirectionalForce(90)]),
             (torch.tensor([3]), [PointForce(75, 0)])]         # a point holds no floor: stays
    press(p, place, optimizer, piles, np.ones(4))
    moved = place.t.detach().numpy()
    # each box down to half a px above its own floor: the low one (0), the high step's (2),
    # and the box of the mark that stays, below mark 1 (not the container's floor)
    assert moved[:, 1] == pytest.approx([91.5, 34.0, 41.5, 50.0])
    assert moved[:, 0] == pytest.approx(center[:, 0])


def test_a_stratum_stays_out_of_the_shadow_of_the_one_it_rests_on():
    # layer 1 rests on layer 0 (rests[1, 0]): its mark stops above the top of layer 0's box
    # where that box stood, short of the floor the lower mark drops to
    box = uw.Container.rect(0, 0, 100, 100)
    p = SimpleNamespace(regions=(box, box), layer=np.array([0, 1]),
                        grid=RasterGrid((100, 100), 1.0, pad=2),
                        terms=SimpleNamespace(rests=torch.tensor([[0.0, 0.0], [1.0, 0.0]])),
                        half_w=np.full(2, 8.0), half_h=np.full(2, 8.0), margin=np.zeros(2))
    center = np.array([[25.0, 45.0], [20.0, 10.0]])
    place = Placement(center, np.zeros(2), np.ones(2, bool), np.zeros(2, bool), "cpu")
    optimizer = torch.optim.Adam([place.t])
    down = [DirectionalForce(90)]
    press(p, place, optimizer, [(torch.tensor([0]), down), (torch.tensor([1]), down)], np.ones(2))
    assert place.t.detach().numpy()[:, 1] == pytest.approx([91.5, 29.0])
