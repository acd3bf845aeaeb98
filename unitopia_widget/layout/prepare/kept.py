"""What a layout makes once and a next layout of the same container reads again (regions,
containment fields), kept by key among the last few asked for."""
from __future__ import annotations


def kept(store: dict, key, make, keep: int):
    """``store[key]``, made by ``make()`` where missing; ``store`` keeps the ``keep`` last
    asked for (a value asked for again moves to the end). Values are only read."""
    value = store.pop(key, None)
    if value is None:
        value = make()
    store[key] = value
    while len(store) > keep:
        del store[next(iter(store))]
    return value
