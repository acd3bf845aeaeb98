"""One design of the corpus laid out and measured: ``run(spec, folder, seed)`` returns a
flat record (the design's tags, the ink measures, the order measures, seconds, the solver's
iterations and the budget its layers allow, warnings)."""
from __future__ import annotations

import time
import traceback
import warnings

from . import generate, measure, order

DEFAULT_OPEN_FILL = 0.5   # the engine's fill of an open container that none of its layers sets


def asked_fills(layers, containers) -> dict:
    """Open layer name -> the fill its container is asked to reach (the first layer in it
    that sets one, else the default)."""
    first = {}
    for layer in layers:
        if layer.boundary == "open" and layer.fill is not None:
            first.setdefault(id(containers[layer.name]), layer.fill)
    return {layer.name: first.get(id(containers[layer.name]), DEFAULT_OPEN_FILL)
            for layer in layers if layer.boundary == "open"}


def run(spec: generate.Spec, folder: str, seed: int = 0, png: str | None = None) -> dict:
    """Build, lay out, export and measure one design; ``png``: also save the chart there.
    A design that fails records the error instead of measures."""
    record = {"id": spec.id, "seed": seed}
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            built = generate.build(spec, folder, seed)
            chart = built.chart
            t0 = time.perf_counter()
            chart.layout()
            record["seconds"] = time.perf_counter() - t0
        # a layout that spends its whole budget did not end by its own criteria (the settle
        # never came to rest): the legalising rounds after it get what is left
        record["iterations"] = int(chart.result.iterations)
        record["budget"] = max(layer.iterations for layer in chart.layers)
        record["tags"] = dict(built.tags)
        record["warnings"] = [str(w.message)[:300] for w in caught
                              if not str(w.message).startswith("dropna=True")]
        layers = chart.layers
        closed = {layer.name for layer in layers if layer.boundary == "closed"}
        ink = measure.ink_measures(chart.to_svg(legend=False), chart.canvas, built.containers,
                                   closed, asked_fills(layers, built.containers))
        fill = min(ink["fill"], key=lambda rs: rs[0] / rs[1]) if ink["fill"] else (None, None)
        record.update(units=ink["units"], overlap=ink["overlap"], outside=ink["outside"],
                      empty=ink["empty"], fill=fill[0], fill_asked=fill[1], join=ink["join"],
                      strata=order.strata_in_order(chart.placements, layers),
                      rho=order.size_rho(chart.placements, layers, chart.canvas),
                      pull=order.pull(chart.placements, layers, chart.canvas))
        if png:
            chart.save(png, legend=False, outline=True)
    except Exception as exc:   # noqa: BLE001  (a design the engine refuses is a line of the board)
        record["error"] = f"{type(exc).__name__}: {exc}"[:300]
        record["traceback"] = traceback.format_exc()[-1500:]
    return record
