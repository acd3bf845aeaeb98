"""The finish's drop (``layout/rules/drop.py``) on footprints drawn by hand on a fine raster:
units fall along the pull, all at once, until their pixels meet another's or leave the
region, stepping over their own."""
from __future__ import annotations

import numpy as np
import torch

from unitopia_widget.layout.rules.drop import DropSettings, kinds_of, line, owner_test, reach, step_aside
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


def aside(fine: FineRaster, half_across: float):
    """``step_aside`` of unit 0, lifted, falling at most 100 px down, stopping 0 px short."""
    fine.lift(0)
    down = line(DOWN, 100)
    who = torch.full((fine.seen.shape[1],), -1, dtype=torch.int32)
    return step_aside(fine, 0, DOWN, down, kinds_of(down), half_across, 0, who, DropSettings())


def test_a_unit_resting_on_an_edge_steps_aside_and_falls_past_it():
    # a 10 px wide unit (columns 12 to 21) whose right 3 px rest on a post from the floor
    # (columns 19 to 22): 3 px to its left it clears the post and falls 30 px to the floor
    fine = raster(60, 40, [(20, 12, 10, 10), (30, 19, 30, 4)])
    assert aside(fine, 5.0) == (30, -3)
    # with the post under its middle no step of at most half its width clears it
    fine = raster(60, 40, [(20, 12, 10, 10), (30, 14, 30, 6)])
    assert aside(fine, 5.0) is None


def test_a_unit_does_not_step_aside_through_another():
    # the unit rests on a post; a wall stands beside it to the left, so the only way round
    # the post is through the wall: it stays
    fine = raster(60, 40, [(20, 12, 10, 10), (30, 19, 30, 4), (0, 8, 60, 4)])
    assert aside(fine, 5.0) is None


def test_a_shared_pixel_is_the_later_units_whatever_the_order_and_threads():
    # two units on the same 300 x 300 px: the later one (index 1) listed first, so that a
    # plain assignment (the last write wins) gives the pixels to unit 0 on one thread, and on
    # two to whichever thread writes last, as the machine's load decides (the layout of a
    # directional pile then changed with the load)
    fine = raster(300, 300, [(0, 0, 300, 300), (0, 0, 300, 300)])
    pix = torch.arange(300 * 300).repeat(2)
    which = torch.cat([torch.ones(300 * 300, dtype=torch.long), torch.zeros(300 * 300, dtype=torch.long)])
    rows, cols = torch.arange(300).repeat_interleave(300), torch.arange(300).repeat(300)
    before = torch.get_num_threads()
    try:
        for count in (1, 2):
            torch.set_num_threads(count)
            owned = owner_test(fine, which, pix)
            assert bool(owned(torch.ones_like(rows), rows, cols).all())
            assert not bool(owned(torch.zeros_like(rows), rows, cols).any())
    finally:
        torch.set_num_threads(before)
