"""Browser tests of the built front end against a fake model (no Jupyter).

A thread serves ``tests/browser/page/`` (the fake-model page) and
``unitopia_widget/static/`` (the built bundle) on 127.0.0.1; Chromium runs
headless through Python Playwright.
"""

from __future__ import annotations

import functools
import http.server
import os
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGE_DIR = Path(__file__).resolve().parent / "page"
STATIC_DIR = ROOT / "unitopia_widget" / "static"
from chromium import CHROMIUM, CHROMIUM_ARGS  # noqa: E402

if not os.path.exists(CHROMIUM):
    pytest.skip(f"browser tests need Chromium at {CHROMIUM} (apt-get install chromium)", allow_module_level=True)
sync_api = pytest.importorskip("playwright.sync_api", reason="browser tests need the playwright Python package")
if not (STATIC_DIR / "widget.js").exists():
    pytest.skip("the front end is not built: run `npm --prefix js ci && npm --prefix js run build`", allow_module_level=True)


class _Handler(http.server.SimpleHTTPRequestHandler):
    """Serves /static/* from the package's static folder and everything else from page/."""

    def translate_path(self, path: str) -> str:
        clean = path.split("?", 1)[0].split("#", 1)[0]
        if clean.startswith("/static/"):
            return str(STATIC_DIR / clean[len("/static/"):].lstrip("/"))
        return super().translate_path(path)

    def end_headers(self) -> None:
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def log_message(self, format: str, *args) -> None:  # noqa: A002 - keep test output quiet
        pass


def serve_page() -> tuple[http.server.ThreadingHTTPServer, str]:
    """Starts the page server on a free port; returns (server, base URL)."""
    handler = functools.partial(_Handler, directory=str(PAGE_DIR))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}"


@pytest.fixture(scope="session")
def page_url():
    server, url = serve_page()
    yield f"{url}/index.html"
    server.shutdown()
    server.server_close()


VIEWPORT = {"width": 1400, "height": 1000}


@pytest.fixture(scope="session")
def shared_page(browser):
    """(page, errors): one page for the fake-model tests, and the errors raised in it. A new
    page per test cost about 0.5 s of the ~1 s a test takes; each test still loads a fresh
    document."""
    context = browser.new_context(viewport=VIEWPORT, accept_downloads=True)
    context.set_default_timeout(5000)
    pg = context.new_page()
    errors: list[str] = []
    pg.on("pageerror", lambda exc: errors.append(str(exc)))
    pg.on("dialog", lambda d: (errors.append(f"dialog: {d.message}"), d.dismiss()))
    yield pg, errors
    context.close()


@pytest.fixture
def page(shared_page, page_url):
    """The fake-model page, freshly loaded, at the default viewport, with no permissions."""
    pg, errors = shared_page
    errors.clear()
    pg.context.clear_permissions()
    pg.set_viewport_size(VIEWPORT)
    pg.goto(page_url)
    pg.wait_for_function("window.unitopiaReady === true")
    pg.js_errors = errors
    yield pg
    assert not errors, f"errors in the page: {errors}"
