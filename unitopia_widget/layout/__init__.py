"""The layout engine, in stages (docs/engine-map.md): ``prepare/`` makes the solver's
``Problem`` once, ``step/`` renders, scores and steps the marks every iteration,
``rules/`` is the schedule run after each step; ``solver`` runs the loop and ``engine``
ties a design and a DataFrame to a ``Layout``. Imports run step <- prepare <- rules <-
solver <- engine."""
