"""Layers that lie in one container: a chart's layers grouped by the region they fill."""
from __future__ import annotations


def by_container(layers, keep=None) -> list[list[int]]:
    """``[[layer index, ...], ...]``: the layers (those ``keep(layer)`` takes, all without it)
    grouped by the container they lie in (``layer.region``, the canvas when none is set;
    containers compare by value), in the order of each group's first layer."""
    out: list[list[int]] = []
    for i, layer in enumerate(layers):
        if keep is not None and not keep(layer):
            continue
        group = next((g for g in out if layers[g[0]].region == layer.region), None)
        if group is None:
            out.append([i])
        else:
            group.append(i)
    return out
