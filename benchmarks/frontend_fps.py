"""Frame rate in the cell: the widget in a real JupyterLab, its kernel running the layout.

Starts ``jupyter lab`` headless (temporary config, this checkout first on the kernel's
``PYTHONPATH``), opens a notebook in headless Chromium, shows a widget of N star marks in
three colours and runs ``w.run()`` in the kernel, which streams frames to the page. In the
page it measures:

- ``first frame``: from the run cell being sent to the first marks paint of a streamed frame;
- ``fps``: marks repaints (each one a ``requestAnimationFrame`` that changed the marks'
  pixels: the widget repaints only when the frame on screen moved) per second while running;
- ``frames/s``: frames received from the kernel per second while running;
- long tasks (``PerformanceObserver('longtask')``, over 50 ms) from the widget's display to
  a second after the run ends: how many, the longest, and when it started (s from the run
  cell, beside the run's end: negative is while the widget was shown).

Prints a table; ``--append`` adds it to benchmarks/RESULTS.md.

    python benchmarks/frontend_fps.py [--sizes 1000 20000] [--iterations 150 40] [--append]

Needs the built bundle, jupyterlab, playwright and Chromium at /usr/bin/chromium.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import secrets
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "e2e"))
from chromium import CHROMIUM, CHROMIUM_ARGS  # noqa: E402
from conftest import RUN_CELL_JS, _free_port, _write_config, notebook_json  # noqa: E402

SETUP = """\
import numpy as np, pandas as pd
import unitopia_widget as uw
rng = np.random.default_rng(0)
df = pd.DataFrame({{"v": rng.uniform(1, 10, {n}), "g": rng.choice(["a", "b", "c"], {n})}})
"""
WIDGET = 'w = uw.UnitoPia(df, mark="star", color="g", size={size}, iterations={iterations})\nw'

# Installed before the page loads: every long task of the page, with its start time.
OBSERVE_JS = """
window.fpsLongTasks = [];
new PerformanceObserver((list) => {
  for (const e of list.getEntries()) window.fpsLongTasks.push([e.startTime, e.duration]);
}).observe({type: 'longtask', buffered: true});
"""

# Samples the widget's paint counters every animation frame from just before Run.
WATCH_JS = """
(el) => {
  const st = el.unitopiaStats, w = window.fpsWatch = {
    t0: performance.now(), first: null, start: null, end: null, paints0: 0, frames0: 0,
    paints: 0, frames: 0};
  const tick = () => {
    const now = performance.now(), running = el.dataset.status === 'running';
    if (w.first === null && st.framesReceived > 0) w.pendingFirst = true;
    if (w.pendingFirst && w.first === null && st.paints > w.paintsAtFrame) w.first = now;
    if (w.first === null && !w.pendingFirst) w.paintsAtFrame = st.paints;
    if (running && w.start === null && w.first !== null) {
      w.start = now; w.paints0 = st.paints; w.frames0 = st.framesReceived;
    }
    if (w.start !== null && w.end === null && !running) {
      w.end = now; w.paints = st.paints - w.paints0; w.frames = st.framesReceived - w.frames0;
      return;
    }
    requestAnimationFrame(tick);
  };
  st.framesReceived = 0;
  w.paintsAtFrame = st.paints;
  requestAnimationFrame(tick);
}
"""


def start_lab(base: Path):
    dirs = {name: base / name for name in ("config", "data", "runtime", "ipython", "notebooks")}
    for d in dirs.values():
        d.mkdir()
    port, token = _free_port(), secrets.token_hex(16)
    _write_config(dirs["config"], dirs["notebooks"], port, token)
    env = dict(os.environ, JUPYTER_CONFIG_DIR=str(dirs["config"]), JUPYTER_DATA_DIR=str(dirs["data"]),
               JUPYTER_RUNTIME_DIR=str(dirs["runtime"]), IPYTHONDIR=str(dirs["ipython"]),
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep))
    log = open(base / "lab.log", "wb")
    proc = subprocess.Popen([sys.executable, "-m", "jupyterlab", "--no-browser"], cwd=dirs["notebooks"],
                            env=env, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 90
    while True:
        if proc.poll() is not None:
            raise SystemExit(f"jupyter lab exited with code {proc.returncode}; see {base / 'lab.log'}")
        try:
            req = urllib.request.Request(f"{url}/api/status", headers={"Authorization": f"token {token}"})
            urllib.request.urlopen(req, timeout=5).read()
            return proc, url, token, dirs["notebooks"]
        except (urllib.error.URLError, ConnectionError, OSError):
            if time.monotonic() > deadline:
                proc.terminate()
                raise SystemExit("jupyter lab did not answer within 90 s")
            time.sleep(0.3)


def run_cell(page, index=None, code=""):
    out = page.evaluate(RUN_CELL_JS, [code, index])
    if out["error"] or not out["ok"]:
        raise RuntimeError(f"cell {out['index']} failed: {out['error'] or out['text']}")
    return out


def measure(browser, url, token, folder: Path, n: int, sized: bool, iterations: int, timeout: float,
            profile: bool = False) -> dict:
    name = f"fps-{n}-{secrets.token_hex(3)}.ipynb"
    cells = [SETUP.format(n=n), WIDGET.format(size='"v"' if sized else "None", iterations=iterations)]
    (folder / name).write_text(json.dumps(notebook_json(cells)))
    context = browser.new_context(viewport={"width": 1400, "height": 1000})
    context.add_init_script(OBSERVE_JS)
    page = context.new_page()
    try:
        page.goto(f"{url}/lab/tree/{name}?reset&token={token}")
        page.wait_for_function(
            """(name) => { const w = window.jupyterapp && jupyterapp.shell.currentWidget;
                 const k = w && w.sessionContext && w.sessionContext.session && w.sessionContext.session.kernel;
                 return !!(w && w.context && w.context.path === name && w.content.widgets.length
                           && k && k.status === 'idle' && k.connectionStatus === 'connected'); }""",
            arg=name, timeout=120_000, polling=200)
        run_cell(page, 0)
        shown = page.evaluate("performance.now()")
        run_cell(page, 1)
        root = page.locator('[data-e2e-cell="1"] [data-unitopia]')
        root.wait_for(state="visible", timeout=60_000)
        root.scroll_into_view_if_needed()
        page.wait_for_timeout(1500)
        root.evaluate(WATCH_JS)
        cdp = context.new_cdp_session(page) if profile else None
        if cdp:
            cdp.send("Profiler.enable")
            cdp.send("Profiler.start")
        run_cell(page, None, "w.run()")
        page.wait_for_function("window.fpsWatch && window.fpsWatch.end !== null",
                               timeout=timeout * 1000, polling=250)
        page.wait_for_timeout(1000)
        if cdp:
            print_profile(cdp.send("Profiler.stop")["profile"])
        w = page.evaluate("window.fpsWatch")
        tasks = page.evaluate("window.fpsLongTasks")
        iterations_run = int(run_cell(page, None, "print(w._chart.result.iterations)")["text"].split()[-1])
    finally:
        context.close()
    mine = [d for s, d in tasks if s >= shown]
    worst = max(((d, s) for s, d in tasks if s >= shown), default=(0.0, w["t0"]))
    seconds = (w["end"] - w["start"]) / 1000
    return {"n": n, "sized": sized, "iterations": iterations_run,
            "first": (w["first"] - w["t0"]) / 1000, "run": seconds,
            "fps": w["paints"] / seconds, "in": w["frames"] / seconds,
            "long": len(mine), "longest": max(mine, default=0.0),
            "at": (worst[1] - w["t0"]) / 1000, "end": (w["end"] - w["t0"]) / 1000}


def print_profile(profile: dict, top: int = 25) -> None:
    """The page's functions by self time during the run (a CDP CPU profile)."""
    nodes = {node["id"]: node for node in profile["nodes"]}
    self_ms, gaps = {}, profile.get("timeDeltas", [])
    for sample, gap in zip(profile.get("samples", []), gaps[1:] + [0]):
        f = nodes[sample]["callFrame"]
        key = f"{f['functionName'] or '(anonymous)'} {f['url'].rsplit('/', 1)[-1]}:{f['lineNumber'] + 1}"
        self_ms[key] = self_ms.get(key, 0.0) + gap / 1000
    for key, ms in sorted(self_ms.items(), key=lambda kv: -kv[1])[:top]:
        print(f"{ms:9.0f} ms  {key}")


def table(rows) -> str:
    lines = [f"{'marks':>6} {'size=':>5} {'iters':>5} {'first frame s':>13} {'run s':>6} {'fps':>6} "
             f"{'frames/s':>8} {'long tasks':>10} {'longest ms':>10} {'at s':>6} {'run end s':>9}"]
    for r in rows:
        lines.append(f"{r['n']:>6} {'v' if r['sized'] else '-':>5} {r['iterations']:>5} {r['first']:>13.2f} "
                     f"{r['run']:>6.1f} {r['fps']:>6.1f} {r['in']:>8.1f} {r['long']:>10} {r['longest']:>10.0f} {r['at']:>6.1f} {r['end']:>9.1f}")
    return "\n".join(lines)


def machine() -> str:
    model = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo")
                  if line.startswith("model name")), platform.processor())
    load = os.getloadavg()[0]
    return (f"{os.cpu_count()} cores ({model}), {platform.machine()}, Linux {platform.release()}, "
            f"load average {load:.1f} at the start")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 20000])
    parser.add_argument("--iterations", type=int, nargs="+", default=[150, 40],
                        help="iterations cap of each size's run (the last one for the sizes after)")
    parser.add_argument("--timeout", type=float, default=300, help="seconds one run may take")
    parser.add_argument("--append", action="store_true", help="append the table to benchmarks/RESULTS.md")
    parser.add_argument("--profile", action="store_true", help="print the page's functions by self time")
    parser.add_argument("--note", default="", help="a line to write with --append")
    opts = parser.parse_args()
    if not os.path.exists(CHROMIUM):
        raise SystemExit(f"needs Chromium at {CHROMIUM}")
    from playwright.sync_api import sync_playwright

    where = machine()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        proc, url, token, folder = start_lab(Path(tmp))
        try:
            with sync_playwright() as pw:
                browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
                for k, n in enumerate(opts.sizes):
                    iterations = opts.iterations[min(k, len(opts.iterations) - 1)]
                    rows.append(measure(browser, url, token, folder, n, n <= 5000, iterations, opts.timeout,
                                        opts.profile))
                    print(table(rows[-1:]).splitlines()[-1], flush=True)
                browser.close()
        finally:
            proc.terminate()   # only the server started here; it shuts its kernels down
            proc.wait(timeout=30)
    text = table(rows)
    print(f"frame rate in the cell, JupyterLab + kernel + headless Chromium; {where}")
    print(text)
    if opts.append:
        with open(ROOT / "benchmarks" / "RESULTS.md", "a") as out:
            out.write(f"\n`python benchmarks/frontend_fps.py --sizes {' '.join(map(str, opts.sizes))} "
                      f"--iterations {' '.join(map(str, opts.iterations))}`; {where}. "
                      f"{opts.note}\n```\n{text}\n```\n")


if __name__ == "__main__":
    main()
