"""What every iteration runs: the raster of the marks, the losses on it, the placement and
its optimiser, the controlled scales, the readback. Imports nothing else of ``layout/``."""
