"""``fill-scale``: the controller that grows a closed container's scale into its room."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .state import Rule


@dataclass(frozen=True)
class FillScaleSettings:
    grow_overlap: float = 0.01     # the scale grows below half this overlap
    scale_step: float = 0.003      # log-scale step per iteration
    # room grows a scale while its footprints poke out by less than a share of grow_overlap:
    # outside_bare for bare marks, all of it with margins of 0.1 and more (a mark pressed
    # against the edge pokes its margin band out long before its ink)
    outside_bare: float = 0.4
    outside_per_margin: float = 6.0


def grow_outside(median: np.ndarray, c: FillScaleSettings = FillScaleSettings()) -> np.ndarray:
    """``(G,)`` the outside share below which room still grows each group's scale, from the
    median margin ``median (G,)`` of its units (``Scales.margin``)."""
    return c.grow_overlap * np.minimum(c.outside_bare + c.outside_per_margin * median, 1.0)


class FillScale(Rule):
    """Every settle iteration, controlled scales (closed layers filling their containers):
    grow while the measured overlap stays below ``grow_overlap / 2``, or while the container
    has room (even as jammed marks keep some overlap, and while footprints poke out a
    little); give way above it once marks rest, or as they leave the container. Poking out is
    worse than touching: room never grows a scale past a mark outside. Needed by closed
    boundaries (the scale is controlled, not learned: a gradient balance between fill and
    overlap settles at a few percent of overlap with spiky marks). No scale grows past its
    group's cap (``prepare.fit``), the largest at which each of its marks still fits somewhere
    in its container: a mark of an outlying size would otherwise outgrow every place, and a
    scale at its cap has no room left to grow into (the settle goes on only as long as a
    scale grows). Acts when a scale moved."""

    name = "fill-scale"
    reads = ("overlap_g", "outside_g", "room", "grow_outside", "travelling", "ctl")
    writes = ("ctl", "since_best", "grow_outside")
    Settings = FillScaleSettings

    def applies(self, s):
        return bool(s.ctl.free.any())

    def start(self, s):
        s.grow_outside = grow_outside(s.ctl.margin, self.settings)

    def __call__(self, s):
        c, ctl = self.settings, s.ctl
        crowd = np.maximum(s.overlap_g, s.outside_g)
        grow = ctl.free & ((crowd < 0.5 * c.grow_overlap) | (
            s.room & (s.overlap_g < 1.5 * c.grow_overlap) & (s.outside_g < s.grow_outside)))
        shrink = ctl.free & ((crowd > 1.5 * c.grow_overlap) | (s.outside_g > c.grow_overlap)) \
            & (not s.travelling)
        before = ctl.log.copy()
        ctl.log += c.scale_step * (grow.astype(float) - shrink.astype(float))
        if s.p.group_cap is not None:   # no scale grows past where its largest mark fits
            ctl.log = np.minimum(ctl.log, np.log(s.p.group_cap))
        if (ctl.log > before).any():
            s.since_best = 0
        return bool((ctl.log != before).any())
