"""A generated design corpus and its measures (issue 45).

``generate.corpus(seed, n)`` draws designs (containers, marks, data, forces, emitters,
strata, margins, fills, orientations) through the public API; ``measure`` reads the
exported SVG, ``order`` the placements table; ``benchmarks/scoreboard.py`` runs them.
"""
