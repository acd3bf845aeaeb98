"""Debian's Chromium under Playwright, shared by the browser and JupyterLab tests.

One Playwright instance per test session: a second ``sync_playwright()`` in
the same session fails ("Sync API inside the asyncio loop").
"""
from __future__ import annotations

import pytest

CHROMIUM = "/usr/bin/chromium"
# the flags /work/shared/TESTING.md found to work on these machines
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def launch():
    """Yield a launched Chromium browser, then close it and stop Playwright."""
    from playwright import sync_api

    pw = sync_api.sync_playwright().start()
    try:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
    except Exception as exc:  # pragma: no cover - depends on the machine
        pw.stop()
        pytest.skip(f"Chromium did not start under Playwright: {exc}")
    yield b
    b.close()
    pw.stop()
