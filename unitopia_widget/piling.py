"""``Piling``: the chart's piles (``design/piles.py``), the part of ``Chart`` that lays its
layers out as labelled piles and keeps them so when layers come, go or block on others."""
from __future__ import annotations

import warnings

import numpy as np

from .design import piles as pile_mod
from .design.encodings import footprint
from .design.sharing import by_container


class Piling:
    """Mixed into ``Chart``: the ``piles`` setting and the containers it gives the layers."""

    _piles = None

    @property
    def piles(self):
        """How the layers lie as piles, each labelled with its layers' names (``design.piles``):
        ``"columns"``, ``"rows"``, ``"grid"``, or None (no piles). Setting an arrangement
        lays every layer out again as a pile, replacing its container (layers that block on
        one another share one); None puts every layer back on the whole canvas. A layer's
        forces are kept unless they are the pile's pull."""
        return self._piles

    @piles.setter
    def piles(self, value):
        arrange = pile_mod.check_piles(value)
        if arrange is None:
            for layer in self.layers:
                layer._apply({"container": None, "forces": self._own_forces(layer)})
            self._piles = None
            self.bind_check()
        else:
            self._lay_piles(arrange, keep_forces=False)   # all or nothing
        self._changed()

    def _own_forces(self, layer) -> list:
        """``layer``'s forces less the pull its pile gave it."""
        pulls = [] if self._piles is None else [pile_mod.pull(self._piles)]
        return [] if layer.forces == pulls else list(layer.forces)

    def _pile_regions(self, arrange: str, groups) -> list:
        """The container of each pile of ``groups`` (lists of layer indices): areas
        proportional to the footprint area of their marks at scale 1."""
        units = self._units
        foot = units.area * footprint(units.margin) ** 2
        mine = [np.isin(units.layer, g) for g in groups]
        totals = [float(foot[m].sum()) for m in mine]
        largest = [float(foot[m].max()) for m in mine]
        labels = [pile_mod.label_of([self.layers[i].name for i in g]) for g in groups]
        return pile_mod.regions(totals, largest, labels, self.canvas, arrange)

    def _lay_piles(self, arrange: str, keep_forces: bool) -> None:
        """Give every layer the container of its pile and, unless it has forces of its own
        (``keep_forces``: all it has are its own), the pile's pull; a refused layout (a pile
        too small for its marks, too many piles) changes nothing."""
        groups = pile_mod.groups(self.layers)
        rects = self._pile_regions(arrange, groups)
        before = [(layer, {"container": layer.container, "forces": layer.forces})
                  for layer in self.layers]
        for g, rect in zip(groups, rects):
            for i in g:
                layer = self.layers[i]
                own = list(layer.forces) if keep_forces else self._own_forces(layer)
                layer._apply({"container": rect, "forces": own or [pile_mod.pull(arrange)]})
        try:
            self.bind_check()
        except Exception:   # refused (a pile too small for its marks): nothing changes
            for layer, fields in before:
                layer._apply(fields)
            raise
        self._piles = arrange

    def _regroup(self, warn: bool = True) -> None:
        """After layers were added or their blocks changed: lay the piles out again when a
        layer has no container or blocks on a layer of another pile (or no longer on any
        of its own), so that layers that block on one another share a pile. Piles edited by
        hand are kept (``warn``: with a warning saying how to lay them out again)."""
        if self._piles is None or self._units is None:
            return
        shared = by_container(self.layers, pile_mod.has_container)
        placed = sum(len(g) for g in shared)
        wanted = pile_mod.groups(self.layers)
        if placed == len(self.layers) and sorted(wanted) == sorted(shared):
            return
        try:
            untouched = all(self.layers[g[0]].container == rect
                            for g, rect in zip(shared, self._pile_regions(self._piles, shared)))
        except ValueError:
            untouched = False
        if untouched:
            self._lay_piles(self._piles, keep_forces=False)
        elif warn:
            warnings.warn(f"the layers' piles were edited by hand, so they stay as they are "
                          f"although the layers' blocks (or a new layer) ask for other piles; "
                          f"set piles={self._piles!r} again to lay every layer out as a pile "
                          f"(layers that block on one another share one)", stacklevel=4)
