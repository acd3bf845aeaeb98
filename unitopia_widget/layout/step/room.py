"""Room left in closed containers: where a typical mark would still fit.

The fill controller grows the global scale while a container has room. Room
is measured as the layout checker measures emptiness: the share of the
container farther than a typical mark's radius from any mark.
"""
from __future__ import annotations

import numpy as np
from scipy import ndimage


def empty_share(cover: np.ndarray, inside: np.ndarray, reach: float) -> float:
    """Share of the container farther than ``reach`` from every mark.

    ``cover``: ``(H, W)`` raster coverage of all marks' footprints; ``inside``:
    ``(H, W)`` the container's coverage; ``reach``: raster px (a median mark
    radius less its margin band). Returns a share in [0, 1].
    """
    mask = inside >= 0.5
    total = int(mask.sum())
    if total == 0:
        return 0.0
    far = ndimage.distance_transform_edt(cover < 0.5) > max(reach, 1.0)
    return float((far & mask).sum()) / total
