"""The finish's drop (``layout/rules/drop.py``) on footprints drawn by hand on a fine raster:
units fall along the pull, all at once, until their pixels meet another's or leave the
region, stepping over their own."""
from __future__ import annotations

import numpy as np
import torch

from unitopia_widget.layout.rules.drop import reach
from unitopia_widget.layout.step.fine import FineRaster
from unitopia_widget.layout.step.raster import RasterGrid

DOWN = np.array([0.0, 1.0])     # a pull down the canvas (x, y)


def raster(rows: int, cols: int, boxes, inside=None) -> FineRaster:
    """Units drawn as boxes ``(row, column, height, width)`` on a ``rows`` x ``cols`` raster of
    one layer (each unit collides with every other); ``inside``: bool ``(rows, cols)``."""
    index = [torch.as_tensor((np.mgrid[r:r + h, c:c + w][0] * cols
                              + np.mgrid[r:r + h, c:c + w][1]).ravel()) for r, c, h, w in boxes]
    owner = torch.cat([torch.full((len(ix),), u) for u, ix in enumerate(index)])
    flat = torch.cat(index).long()
    seen = torch.zeros(rows * cols).index_add_(0, flat, torch.ones(len(flat)))[None]
    inside = torch.ones(1, rows * cols, dtype=torch.bool) if inside is None \
        else torch.as_tensor(inside.reshape(1, -1))
    bounds = np.concatenate([[0], np.cumsum([len(ix) for ix in index])])
    return FineRaster(RasterGrid((cols, rows), 1.0, pad=0), flat, owner, bounds,
                      torch.zeros(len(boxes), dtype=torch.long), torch.ones(1, 1), seen, inside)


def test_units_fall_together_until_their_pixels_meet_the_one_below_or_the_floor():
    # a 10 px square 5 px above the floor (row 60), and another 20 px above it
    fine = raster(60, 40, [(45, 10, 10, 10), (15, 12, 10, 10)])
    fell = reach(fine, np.array([0, 1]), DOWN, np.array([100, 100]))
    # all fall at once, each against where the others are: the upper one stops at the lower
    # one's place, the lower one at the floor
    assert fell.tolist() == [5, 20]
    assert reach(fine, np.array([1]), DOWN, np.array([7])).tolist() == [7]    # its limit


def test_a_unit_steps_over_its_own_pixels_as_it_falls():
    # an E on its back: two bars joined at one end, 6 px apart; falling, the upper bar's
    # lower edge comes onto the lower bar's place, which is its own, after 6 px
    e = [(10, 10, 4, 20), (14, 10, 6, 4), (20, 10, 4, 20)]
    fine = raster(60, 40, e)
    one = FineRaster(fine.grid, fine.index, torch.zeros_like(fine.owner), np.array([0, len(fine.index)]),
                     torch.zeros(1, dtype=torch.long), fine.collide, fine.seen, fine.inside)
    assert reach(one, np.array([0]), DOWN, np.array([100])).tolist() == [36]   # to the floor
