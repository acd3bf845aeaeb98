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


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items):
    """Groups for pytest-xdist's ``--dist loadgroup`` (scripts/test.sh): a test file runs on one
    worker, so its module fixtures (shared layouts) are built once, and every JupyterLab test
    runs on the one worker that starts the server they share."""
    for item in items:
        group = "jupyterlab" if item.get_closest_marker("jupyterlab") else item.nodeid.split("::")[0]
        item.add_marker(pytest.mark.xdist_group(group))
