"""PyTorch's intra-op threads for a layout's passes: one where they are over few samples.

PyTorch splits an op over its threads past 32,768 elements. Under the passive wait policy
(``unitopia_widget/__init__.py``: idle threads sleep at once, for a notebook's browser) each
split wakes a sleeping thread, which costs more than the second thread saves on passes over
few samples. Table 1 (equal discs under a point force), solve seconds on a 2-core Xeon,
one / two threads: 1,000 discs (256,000 samples) 0.33 / 0.43; 2,000 (512,000) 0.75 / 0.82;
3,000 (768,000) 1.39 / 1.44; 5,000 (1.28 million) 2.35 / 2.03; 20,000 3.77 / 3.24.
"""
from __future__ import annotations

from contextlib import contextmanager

import torch

FEW = 1_000_000   # samples a pass: fewer run on one thread


@contextmanager
def fitted(samples: int, device: torch.device):
    """Within it, one intra-op thread where a pass draws under ``FEW`` ``samples`` on the
    CPU; the caller's thread count is given back after it, whatever happened."""
    given = torch.get_num_threads()
    if device.type == "cpu" and samples < FEW:
        torch.set_num_threads(1)
    try:
        yield
    finally:
        torch.set_num_threads(given)
