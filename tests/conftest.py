"""Session-wide fixtures."""
from __future__ import annotations

import pytest

from chromium import launch


@pytest.fixture(scope="session")
def browser():
    """One headless Chromium for every browser and JupyterLab test of the session."""
    yield from launch()
