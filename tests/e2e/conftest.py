"""Fixtures for the real-JupyterLab end-to-end tests.

``lab_server`` (session scope) starts one ``jupyter lab`` headless on 127.0.0.1 with a
fixed free port (``port_retries=0``), a token, and temporary config, data, runtime and
IPython directories, so nothing of the user's own Jupyter setup leaks in. It stops only
the process it started. ``lab_page`` (session scope) is one browser page on that server
with one notebook and its kernel: loading JupyterLab, starting a kernel and importing
torch cost about 10 s a test on 2 cores. ``lab`` gives each test a :class:`Lab` helper
that fills that notebook with the test's cells (the old ones deleted, so their views are
gone), runs them in the shared kernel and reads their outputs back; page errors are
collected per test, and a notebook a test opens itself has its kernel shut down after it.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
STATIC_DIR = ROOT / "unitopia_widget" / "static"
from chromium import CHROMIUM, CHROMIUM_ARGS  # noqa: E402
SERVER_START_TIMEOUT = 60.0
KERNEL_TIMEOUT = 60_000  # ms: kernel start plus importing torch on a cold cache

if not os.path.exists(CHROMIUM):
    pytest.skip(f"JupyterLab tests need Chromium at {CHROMIUM} (apt-get install chromium)", allow_module_level=True)
pytest.importorskip("jupyterlab", reason="JupyterLab tests need jupyterlab (pip install jupyterlab)")
sync_api = pytest.importorskip("playwright.sync_api", reason="JupyterLab tests need the playwright Python package")
if not (STATIC_DIR / "widget.js").exists():
    pytest.skip("the front end is not built: run `npm --prefix js ci && npm --prefix js run build`", allow_module_level=True)


# --- the server ------------------------------------------------------------------------

def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _write_config(config_dir: Path, root_dir: Path, port: int, token: str) -> None:
    config = {
        "ServerApp": {
            "ip": "127.0.0.1",
            "port": port,
            "port_retries": 0,
            "open_browser": False,
            "allow_root": True,
            "root_dir": str(root_dir),
        },
        "IdentityProvider": {"token": token},
        "LabApp": {
            "expose_app_in_browser": True,  # window.jupyterapp
            "news_url": None,
            "check_for_updates_class": "jupyterlab.NeverCheckForUpdate",
        },
    }
    (config_dir / "jupyter_server_config.json").write_text(json.dumps(config, indent=1))
    labconfig = config_dir / "labconfig"
    labconfig.mkdir(exist_ok=True)
    # Without this a news toast ("Would you like to get notified...") covers the notebook.
    page_config = {"disabledExtensions": {"@jupyterlab/apputils-extension:announcements": True}}
    (labconfig / "page_config.json").write_text(json.dumps(page_config))


class LabServer:
    """One running ``jupyter lab``: its URL, token, notebook folder and REST helpers."""

    def __init__(self, proc: subprocess.Popen, url: str, token: str, root_dir: Path, log: Path):
        self.proc, self.url, self.token, self.root_dir, self.log = proc, url, token, root_dir, log

    def api(self, path: str, method: str = "GET"):
        req = urllib.request.Request(f"{self.url}{path}", method=method,
                                     headers={"Authorization": f"token {self.token}"})
        with urllib.request.urlopen(req, timeout=10) as resp:
            body = resp.read()
        return json.loads(body) if body else None

    def log_tail(self, n: int = 40) -> str:
        try:
            return "\n".join(self.log.read_text(errors="replace").splitlines()[-n:])
        except OSError:
            return ""

    def shutdown_sessions(self, path_prefix: str) -> None:
        """Shuts down the kernels of the notebooks whose path starts with ``path_prefix``."""
        for s in self.api("/api/sessions"):
            if s.get("path", "").startswith(path_prefix):
                try:
                    self.api(f"/api/sessions/{s['id']}", method="DELETE")
                except urllib.error.HTTPError:
                    pass


@pytest.fixture(scope="session")
def lab_server(tmp_path_factory):
    base = tmp_path_factory.mktemp("jupyterlab")
    dirs = {name: base / name for name in ("config", "data", "runtime", "ipython", "notebooks")}
    for d in dirs.values():
        d.mkdir()
    port, token = _free_port(), secrets.token_hex(16)
    _write_config(dirs["config"], dirs["notebooks"], port, token)
    env = dict(
        os.environ,
        JUPYTER_CONFIG_DIR=str(dirs["config"]),
        JUPYTER_DATA_DIR=str(dirs["data"]),
        JUPYTER_RUNTIME_DIR=str(dirs["runtime"]),
        IPYTHONDIR=str(dirs["ipython"]),
        PYTHONUNBUFFERED="1",
    )
    env.pop("ANYWIDGET_HMR", None)
    log = base / "jupyterlab.log"
    with open(log, "wb") as out:
        proc = subprocess.Popen([sys.executable, "-m", "jupyterlab", "--no-browser"], cwd=dirs["notebooks"],
                                env=env, stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    server = LabServer(proc, f"http://127.0.0.1:{port}", token, dirs["notebooks"], log)
    try:
        deadline = time.monotonic() + SERVER_START_TIMEOUT
        while True:
            if proc.poll() is not None:
                pytest.fail(f"jupyter lab exited with code {proc.returncode}:\n{server.log_tail()}")
            try:
                server.api("/api/status")
                break
            except (urllib.error.URLError, ConnectionError, OSError):
                if time.monotonic() > deadline:
                    pytest.fail(f"jupyter lab did not answer on port {port} within "
                                f"{SERVER_START_TIMEOUT:.0f} s:\n{server.log_tail()}")
                time.sleep(0.2)
        yield server
    finally:
        # Only the process started here: SIGTERM lets the server shut its own kernels down.
        if proc.poll() is None:
            proc.terminate()
            try:
                proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(timeout=10)
        shutil.rmtree(base, ignore_errors=True)


# --- the browser -----------------------------------------------------------------------

def notebook_json(cells: list[str]) -> dict:
    """The template notebook: code cells with no outputs and a python3 kernelspec."""
    return {
        "nbformat": 4,
        "nbformat_minor": 5,
        "metadata": {
            "kernelspec": {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"},
            "language_info": {"name": "python"},
        },
        "cells": [
            {"cell_type": "code", "id": f"cell-{i}", "metadata": {}, "execution_count": None,
             "outputs": [], "source": src}
            for i, src in enumerate(cells)
        ],
    }


# Appends a code cell (or reuses cell `index`), runs it and waits until the kernel
# answers; returns the cell's outputs as text plus any error. Tags the cell's node with
# data-e2e-cell so that Playwright locators can find what it displays.
RUN_CELL_JS = """
async ([code, index]) => {
  const nb = jupyterapp.shell.currentWidget.content;
  const shared = nb.model.sharedModel;
  let i = index;
  if (i === null) {
    i = shared.cells.length;
    shared.insertCell(i, {cell_type: 'code', source: code});
  }
  nb.deselectAll();
  nb.activeCellIndex = i;
  const ok = await jupyterapp.commands.execute('notebook:run-cell');
  const cell = nb.widgets[i];
  cell.node.dataset.e2eCell = String(i);
  const outputs = cell.model.outputs.toJSON();
  const error = outputs.filter(o => o.output_type === 'error')
                       .map(o => `${o.ename}: ${o.evalue}`).join('\\n');
  const stderr = outputs.filter(o => o.output_type === 'stream' && o.name === 'stderr')
                        .map(o => [].concat(o.text).join('')).join('');
  const text = Array.from(cell.node.querySelectorAll('.jp-OutputArea-output'))
                    .map(n => n.innerText).join('\\n');
  return {index: i, ok, error, stderr, text};
}
"""

SHARED_NOTEBOOK = "e2e-shared"

# The path of the document the page shows, or null (JupyterLab not loaded yet).
SHOWN_JS = """
() => { const w = window.jupyterapp && jupyterapp.shell.currentWidget;
        return (w && w.context && w.context.path) || null; }
"""

# Replaces every cell of the shown notebook by fresh code cells, in one change (a notebook
# is never left empty, which would make JupyterLab add a cell of its own).
REPLACE_CELLS_JS = """
(cells) => {
  const shared = jupyterapp.shell.currentWidget.content.model.sharedModel;
  shared.transact(() => {
    const old = shared.cells.length;
    shared.insertCells(old, cells.map(source => ({cell_type: 'code', source})));
    shared.deleteCellRange(0, old);
  });
}
"""


class Lab:
    """A notebook open in JupyterLab, driven through ``window.jupyterapp``."""

    def __init__(self, server: LabServer, page, name: str, notebook: str = SHARED_NOTEBOOK):
        """``name``: the test's own, for files it writes; ``notebook``: the shared notebook."""
        self.server, self.page, self.name, self.notebook = server, page, name, notebook
        self.other_pages: list = []

    def new_page(self):
        """A second page on the server for this test (closed after it), its errors watched:
        the shared page keeps its notebook and kernel."""
        page = watched_page(self.page.context, self.errors)
        self.other_pages.append(page)
        return page

    def open(self, cells: list[str]) -> None:
        """Puts ``cells`` in the shared notebook (opened from the template the first time, or
        when the page shows another), waits for an idle kernel, runs every cell."""
        path = self.server.root_dir / f"{self.notebook}.ipynb"
        if self.page.evaluate(SHOWN_JS) == path.name:
            self.page.evaluate(REPLACE_CELLS_JS, cells)
        else:
            path.write_text(json.dumps(notebook_json(cells), indent=1))
            self.page.goto(f"{self.server.url}/lab/tree/{path.name}?reset&token={self.server.token}")
        self.page.wait_for_function(
            """([name, n]) => {
                const w = window.jupyterapp && jupyterapp.shell.currentWidget;
                const k = w && w.sessionContext && w.sessionContext.session && w.sessionContext.session.kernel;
                return !!(w && w.context && w.context.path === name && w.context.isReady
                          && w.content.widgets.length === n
                          && k && k.status === 'idle' && k.connectionStatus === 'connected');
            }""",
            arg=[path.name, len(cells)], timeout=KERNEL_TIMEOUT, polling=100,
        )
        for i in range(len(cells)):
            self.run_cell(i)

    def run_cell(self, index: int | None = None, code: str = "") -> dict:
        out = self.page.evaluate(RUN_CELL_JS, [code, index])
        if out["error"] or not out["ok"]:
            raise AssertionError(f"cell {out['index']} failed: {out['error'] or out['text']}")
        return out

    def run(self, code: str) -> str:
        """Runs ``code`` in a new cell at the end; returns its printed output."""
        return self.run_cell(None, code)["text"].strip()

    def eval(self, expr: str):
        """The value of a Python expression in the kernel, through JSON."""
        text = self.run(f"import json as _json; print(_json.dumps({expr}))")
        return json.loads(text.splitlines()[-1])

    def wait_until(self, expr: str, timeout: float = 20.0, interval: float = 0.2):
        """Polls a Python expression until it is truthy; returns its last value."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.eval(expr)
            if value or time.monotonic() > deadline:
                return value
            time.sleep(interval)

    def cell(self, index: int):
        return self.page.locator(f'[data-e2e-cell="{index}"]')


def watched_page(context, errors: list[str]):
    """A new page of ``context`` whose uncaught errors are appended to ``errors``."""
    page = context.new_page()
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.on("console", lambda msg: msg.type == "error" and errors.append(f"console: {msg.text}"))
    return page


@pytest.fixture(scope="session")
def lab_page(lab_server, browser):
    """(page, errors): one page for every JupyterLab test, and the uncaught errors in it."""
    context = browser.new_context(viewport={"width": 1500, "height": 1100})
    context.set_default_timeout(15_000)
    errors: list[str] = []
    page = watched_page(context, errors)
    try:
        yield page, errors
    finally:
        context.close()
        lab_server.shutdown_sessions(SHARED_NOTEBOOK)


@pytest.fixture
def lab(lab_server, lab_page, request):
    page, errors = lab_page
    errors.clear()
    name = f"e2e-{request.node.name.replace('[', '-').replace(']', '')}-{secrets.token_hex(3)}"
    helper = Lab(lab_server, page, name)
    helper.errors = errors
    try:
        yield helper
    finally:
        for other in helper.other_pages:
            other.close()
        lab_server.shutdown_sessions(name)
    assert not errors, f"uncaught errors in the page: {errors}"
