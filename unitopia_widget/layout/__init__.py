"""The layout engine: raster, losses, solver, placement and the start."""
