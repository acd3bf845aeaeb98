"""Moving the solver's small per-iteration values between host and device.

On a GPU, reading a value back waits for every queued kernel: done each
iteration, the host and the device take turns instead of working together.
``Readback`` copies the loss and the per-layer sums asynchronously and hands
the host the previous iteration's values (one iteration late, so the copy has
long arrived); ``upload`` sends the controlled scales without a stall. On the
CPU both are plain, immediate copies.
"""
from __future__ import annotations

import numpy as np
import torch


class Readback:
    """``push(tensor)`` queues a 1-D device tensor and returns the latest arrived values."""

    def __init__(self, device, lag: bool | None = None):
        self.device = torch.device(device)
        self.lag = self.device.type == "cuda" if lag is None else lag
        self.pending = None   # (host tensor, event or None) of the last push

    def push(self, tensor: torch.Tensor) -> np.ndarray:
        """The values of the previous push when lagging (of this one on the first), else these."""
        tensor = tensor.detach()
        if not self.lag:
            return tensor.cpu().numpy()
        cuda = self.device.type == "cuda"
        host = torch.empty(tensor.shape, dtype=tensor.dtype, pin_memory=cuda)
        host.copy_(tensor, non_blocking=cuda)
        event = None
        if cuda:
            event = torch.cuda.Event()
            event.record()
        previous, self.pending = self.pending, (host, event)
        arrived, done = previous or self.pending
        if done is not None:
            done.synchronize()
        return arrived.numpy()


def upload(array: np.ndarray, device) -> torch.Tensor:
    """``array`` as a float32 tensor on ``device``; from pinned memory, without a stall, on a GPU."""
    tensor = torch.from_numpy(np.ascontiguousarray(array, dtype=np.float32))
    device = torch.device(device)
    if device.type != "cuda":
        return tensor
    return tensor.pin_memory().to(device, non_blocking=True)
