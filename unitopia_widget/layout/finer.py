"""Thin marks shrunk past the raster: a layout checked, and polished once more, on a raster
made for the scale it ended at.

The raster is made for the scale a layout starts at, its median thin mark
``prepare.assemble.THIN_ACROSS`` (1.5) raster px across. Long thin marks that jam at the
asked fill give up most of their size while legalising; drawn under ``THIN_ACROSS / FINER``
(1) raster px across, their crossings and side-by-side contacts read as no overlap. Such a
layout (``scales_past``) is drawn once on a raster made for its final scale; where that
raster sees more overlap and ink outside than the first one did, by more than a legal layout
keeps (``hidden``), the layout is polished once more from where it ended, on that raster
(``layout.engine``: the polish's legalising rounds, as the first solve's would have, had
they seen it). Round marks shrunk alike are still seen (equal discs are laid out at half the
aimed radius) and are not checked again. Units on curve tracks are checked too: the warm
start puts each at the arc length (and band offset) of where it ended.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..design.encodings import footprint
from .prepare.assemble import THIN_ACROSS, thin_across
from .prepare.problem import Problem
from .reflow import unit_scales
from .rules.legalize import LegalizeSettings
from .solver import Result
from .window import Window, final_stats

FINER = 1.5   # thin marks shrunk to THIN_ACROSS / FINER raster px across are checked on a finer raster


def scales_past(problem: Problem, units, result: Result) -> np.ndarray | None:
    """``(G,)`` the scale groups' scales in ``result`` where its median thin mark drawn at
    them is under ``THIN_ACROSS / FINER`` of ``problem``'s raster px across (the solve shrank
    the marks past what its raster resolves); None where the raster serves."""
    across = thin_across(units, result.unit_scale)
    if across is None or across * problem.grid.rho * FINER >= THIN_ACROSS:
        return None
    scales = problem.group_scales()
    scales[problem.layer_groups()[units.layer]] = result.unit_scale
    return scales


def hidden(p: Problem, seen: dict, legal: LegalizeSettings = LegalizeSettings()) -> bool:
    """Whether the units of ``p`` at its start, drawn on its raster, overlap and poke out by
    more than ``seen`` (the first raster's ``Result.stats`` of the same layout) says, by over
    what a legal layout keeps (``legal.final_overlap``: a share of the ink)."""
    n = len(p.layer)
    scale = unit_scales(p)
    band = footprint(p.margin)
    center = p.placement.transforms()[0].detach().cpu().numpy().astype(np.float64)
    drawn = Window(p, np.arange(n), center, np.zeros(n, bool), p.half_w * band * scale,
                   p.half_h * band * scale, 0.0)
    stats = final_stats(drawn, center, 0.0)
    more = stats["overlap"] + stats["outside"] - seen["overlap"] - seen["outside"]
    return more > legal.final_overlap


def counting_on(on_progress, first: Result):
    """``on_progress`` for the solve on the finer raster: its iterations counted on from
    ``first``'s, as ``joined`` counts them (a progress bar does not start again at 0)."""
    return lambda iteration, loss, stats: on_progress(first.iterations + iteration, loss, stats)


def joined(first: Result, second: Result) -> Result:
    """``second``, the solve on the finer raster, with ``first``'s iterations, seconds,
    phases and rules added (``phases["finer"]``: the second's iterations)."""
    phases = {k: first.phases.get(k, 0) + second.phases.get(k, 0)
              for k in {**first.phases, **second.phases}}
    return dataclasses.replace(
        second, iterations=first.iterations + second.iterations,
        seconds=first.seconds + second.seconds, phases={**phases, "finer": second.iterations},
        rules=tuple(dict.fromkeys(first.rules + second.rules)))
