"""PyTorch's intra-op threads during a layout (``layout/step/threads.py``): passes over few
samples run on one thread (a second one, woken for each op, costs more than it saves), passes
over many on the caller's threads; the caller's count is given back after."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw
from unitopia_widget.layout import solver
from unitopia_widget.layout.step import threads


def threads_while_drawing(monkeypatch, few: int) -> list[int]:
    """Lay out 60 discs with two threads and ``threads.FEW`` = ``few``; the thread count at
    each pass's render."""
    seen, draw = [], solver.render_samples
    monkeypatch.setattr(threads, "FEW", few)
    monkeypatch.setattr(solver, "render_samples",
                        lambda *a: seen.append(torch.get_num_threads()) or draw(*a))
    before = torch.get_num_threads()
    torch.set_num_threads(2)
    try:
        uw.Chart(pd.DataFrame({"v": np.ones(60)}), mark="circle", size="v", iterations=40,
                 container=uw.Container.ellipse(200, 150, 120, 100)).layout()
        assert torch.get_num_threads() == 2   # given back
    finally:
        torch.set_num_threads(before)
    return seen


@pytest.mark.parametrize("few, expected", [(threads.FEW, 1), (1, 2)])
def test_a_layout_of_few_samples_draws_on_one_thread(monkeypatch, few, expected):
    seen = threads_while_drawing(monkeypatch, few)
    assert seen and set(seen) == {expected}
