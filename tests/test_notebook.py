"""The widget in a real kernel: a notebook that keeps its chart through nbconvert, and a
kernel interrupt (the notebook's stop button) during ``run(wait=True)``.

Kernels import this checkout (PYTHONPATH), not an installed copy.
"""
from __future__ import annotations

import base64
import os
import re
import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient
from nbconvert import HTMLExporter
from test_svgcost import SCALED   # a filter the view-box cap lets through: resvg holds on

ROOT = Path(__file__).resolve().parents[1]
SETUP = ("import numpy as np, pandas as pd, torch, unitopia_widget as uw\n"
         "torch.set_num_threads(1)\n"
         "df = pd.DataFrame({'v': np.linspace(1, 4, 12), 'k': list('ab') * 6})\n")


@pytest.fixture
def kernel_env(tmp_path, monkeypatch):
    """This checkout on the kernel's path, and Jupyter's files in a temporary folder."""
    env = {"PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""),
           "JUPYTER_RUNTIME_DIR": str(tmp_path / "runtime"), "IPYTHONDIR": str(tmp_path / "ipython"),
           "OMP_WAIT_POLICY": "PASSIVE", "OMP_NUM_THREADS": "1"}
    for key, value in env.items():
        monkeypatch.setenv(key, value)
    return {**os.environ, **env}


def test_nbconvert_html_shows_the_laid_out_chart(tmp_path, kernel_env):
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_code_cell(SETUP + "w = uw.UnitoPia(df, size='v', color='k', "
                                  "iterations=30, title='Twelve rows')\nw"),
        nbformat.v4.new_code_cell("w.run(wait=True)\nw.status"),
    ])
    # what `jupyter nbconvert --to html --execute` does, in this process (the command's own
    # start took ~3 s): nbclient runs the cells in a new kernel, the HTML exporter renders
    NotebookClient(nb, timeout=300, resources={"metadata": {"path": str(tmp_path)}}).execute(env=kernel_env)
    html, _ = HTMLExporter().from_notebook_node(nb)
    assert "UnitoPia object at 0x" not in html
    # the layout, in the widget's own cell: nbconvert draws an SVG output as an <img>
    images = re.findall(r'<img [^>]*src="data:image/svg\+xml;base64,([^"]+)"', html)
    assert len(images) == 1
    svg = base64.b64decode(images[0]).decode()
    assert svg.startswith('<svg class="unitopia-static" ') and svg.count('class="unit"') == 12
    assert "Twelve rows" in svg and 'class="legend"' in svg


@pytest.fixture
def kernel(kernel_env):
    """A real IPython kernel on this checkout, ready: ``(manager, client)``."""
    from jupyter_client import KernelManager

    km = KernelManager(kernel_name="python3")
    km.start_kernel(env=kernel_env)
    kc = km.client()
    kc.start_channels()
    try:
        kc.wait_for_ready(timeout=120)
        yield km, kc
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)


def test_a_kernel_interrupt_during_run_wait_stops_the_run_cleanly(kernel):
    km, kc = kernel
    reply = kc.execute_interactive(SETUP + "import unitopia_widget\n"
                                   "assert unitopia_widget.__file__.startswith(%r)\n"
                                   "w = uw.UnitoPia(df, size='v', iterations=100000)\n" % str(ROOT),
                                   timeout=120)
    assert reply["content"]["status"] == "ok"
    msg_id = kc.execute("w.run(wait=True)", stop_on_error=False)   # keep later requests
    _wait_for_frames(kc, 2)
    reply = _interrupt(km, kc, msg_id)
    assert reply["content"]["status"] == "error"
    assert reply["content"]["ename"] == "KeyboardInterrupt"
    out = _value(kc, "(w.status, w._runner.running, len(w.placements), "
                     "w._chart.result.cancelled, w.progress['done'], "
                     "[t.name for t in __import__('threading').enumerate()])")
    status, running, placed, cancelled, done, threads = eval(out)
    assert (status, running, placed, cancelled, done) == ("stopped", False, 12, True, True)
    assert "unitopia-layout" not in threads
    assert _value(kc, "bool(np.allclose(np.frombuffer(w.frame, np.float32).reshape(-1, 4)[:, 0], "
                      "w.placements['x']))") == "True"       # the last frame is the layout


def test_a_kernel_interrupt_stops_a_hung_mark_render_within_a_second(kernel):
    # resvg holds the thread, so an interrupt never reached a mark's render: it runs in a
    # worker process, which the notebook's stop button ends
    km, kc = kernel
    reply = kc.execute_interactive(SETUP + "from unitopia_widget.io import svgsafe\n"
                                   "svgsafe.RENDER_SECONDS = 600\n", timeout=120)
    assert reply["content"]["status"] == "ok"
    msg_id = kc.execute(f"uw.Mark.from_spec({SCALED!r})", stop_on_error=False)
    time.sleep(4)                                  # well inside resvg by now
    sent = time.monotonic()
    reply = _interrupt(km, kc, msg_id)
    stopped = time.monotonic() - sent
    assert reply["content"]["status"] == "error"
    assert reply["content"]["ename"] == "KeyboardInterrupt"
    assert stopped < 1.0, stopped
    assert _value(kc, "bool(uw.Mark.from_spec('circle').silhouette(64).any())") == "True"


def _interrupt(km, kc, msg_id: str) -> dict:
    """Interrupt the kernel (the notebook's stop button); the reply to request ``msg_id``."""
    km.interrupt_kernel()
    reply = kc.get_shell_msg(timeout=120)
    while reply["parent_header"].get("msg_id") != msg_id:
        reply = kc.get_shell_msg(timeout=120)
    return reply


def _value(kc, expression: str) -> str:
    """The repr of ``expression`` evaluated in the kernel."""
    found = []

    def hook(msg):
        if msg["msg_type"] == "execute_result":
            found.append(msg["content"]["data"]["text/plain"])
    reply = kc.execute_interactive(expression, output_hook=hook, timeout=120)
    assert reply["content"]["status"] == "ok", reply["content"]
    return found[-1]


def _wait_for_frames(kc, count: int, timeout: float = 120.0) -> None:
    """Read iopub until the widget has sent ``count`` frames (its frame_count updates)."""
    import time
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        msg = kc.get_iopub_msg(timeout=timeout)
        if msg["msg_type"] == "comm_msg":
            state = msg["content"]["data"].get("state", {})
            if state.get("frame_count", 0) >= count:
                return
    raise AssertionError(f"no {count} frames within {timeout} s")
