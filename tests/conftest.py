"""Session-wide fixtures."""
from __future__ import annotations

import pytest
import torch

from chromium import launch


@pytest.fixture(scope="module")
def one_thread():
    """Layout tests run PyTorch on one thread: on two cores shared with other jobs,
    the second intra-op thread mostly waits."""
    before = torch.get_num_threads()
    torch.set_num_threads(1)
    yield
    torch.set_num_threads(before)


@pytest.fixture(scope="session")
def browser():
    """One headless Chromium for every browser and JupyterLab test of the session."""
    yield from launch()

