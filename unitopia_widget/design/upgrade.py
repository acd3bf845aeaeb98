"""Older design dicts converted step by step to the current version, keeping their look.

``upgrade(d)`` returns a new dict of version :data:`scene.VERSION`; each step takes a
design of version ``v`` to ``v + 1`` and changes only what that version changed.
"""
from __future__ import annotations

import copy
import warnings
from numbers import Real


def _margin_v2_to_v3(d: dict) -> dict:
    """Version 3: a mark's footprint is its box x (1 + margin), so neighbours stand
    margin x size apart; before, each mark was padded by margin x size (gap 2 x margin).
    A numeric margin doubles. A margin bound to a column keeps its column, with a warning
    that its values now give the whole gap (double the column to keep the look): the
    design holds the column's name, not its values, and a bound margin is the column's
    value as it is (no scale of its own to double), so no change to the file alone keeps
    the look."""
    for layer in d.get("layers") or []:
        enc = layer.get("encodings") if isinstance(layer, dict) else None
        if not isinstance(enc, dict):
            continue
        margin = enc.get("margin")
        if isinstance(margin, Real) and not isinstance(margin, bool):
            enc["margin"] = 2 * margin
        elif isinstance(margin, str):
            warnings.warn(f"design layer {str(layer.get('name', '?'))[:60]!r}: margin={margin[:60]!r} "
                          f"was saved by design version 2, where a margin padded each mark (gap "
                          f"2 x margin); version 3 reads it as the whole gap, so the marks stand "
                          f"half as far apart. Double the column to keep the look", stacklevel=3)
    return d


def _footprint_v2_to_v3(d: dict) -> dict:
    """Version 3: a mark collides with its ink with enclosed holes filled (``footprint=
    "silhouette"``); before, with its ink alone. Older layers get ``footprint="ink"``."""
    d["layers"] = [{"footprint": "ink", **x} if isinstance(x, dict) else x
                   for x in d.get("layers") or []]
    return d


def _v2_to_v3(d: dict) -> dict:
    """Version 3 changed what ``margin`` means and the default footprint."""
    return _footprint_v2_to_v3(_margin_v2_to_v3(d))


def _v3_to_v4(d: dict) -> dict:
    """Version 4: a margin is a fraction of a mark's size up to its layer's median mark's
    (``margin_of="median"``); before, of each mark's own size however large. Older layers
    get ``margin_of="own"``, which lays them out exactly as before."""
    d["layers"] = [{"margin_of": "own", **x} if isinstance(x, dict) else x
                   for x in d.get("layers") or []]
    return d


def _v4_to_v5(d: dict) -> dict:
    """Version 5: ``piles`` says how the layers lie as labelled piles; the layers of
    ``by=`` without a container of their own became piles, where before they shared the
    whole canvas. An older design keeps its containers and gets ``piles: null`` (no pile
    labels), so its layers lie where they lay."""
    d["piles"] = None
    return d


_STEPS = {2: _v2_to_v3, 3: _v3_to_v4, 4: _v4_to_v5}   # version v -> the step to v + 1 (version 1 reads as 2)


def upgrade(d: dict) -> dict:
    """A copy of design ``d`` (header already checked) converted to the current version."""
    from .scene import VERSION
    version = d["version"]
    if version == VERSION:
        return d
    d = copy.deepcopy(d)
    for v in range(version, VERSION):
        step = _STEPS.get(v)
        if step is not None:
            d = step(d)
    d["version"] = VERSION
    return d
