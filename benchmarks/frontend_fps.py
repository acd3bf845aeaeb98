"""Front-end animation rate: marks painted per second while frames stream in.

Headless Chromium (Playwright) loads the fake-model test page, mounts the widget with
1,000 and 5,000 marks (star and circle SVG data URLs), pushes a new layout frame 30
times a second for about 5 seconds (as the kernel does during a run), and counts the
requestAnimationFrame draws that actually painted the marks. Prints a table; writes
nothing to disk.

    python benchmarks/frontend_fps.py [--seconds 5] [--sizes 1000 5000]

Needs the built bundle (npm --prefix js run build) and Chromium at /usr/bin/chromium.
"""

from __future__ import annotations

import argparse
import functools
import http.server
import os
import platform
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE_DIR = ROOT / "tests" / "browser" / "page"
STATIC_DIR = ROOT / "unitopia_widget" / "static"
CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]

# Runs in the page: mounts n marks, streams frames at `hz` for `seconds`, reports counts.
# Upright marks are the default (rotate=False); "rotating" turns every mark each frame.
STREAM_JS = """
async ([n, seconds, hz, rotating]) => {
  const s = unitopia.defaultState();
  s.marks = [
    {layer: 'layer-1', src: unitopia.svgMark('star', '#4e79a7'), aspect: 1},
    {layer: 'layer-1', src: unitopia.svgMark('circle', '#e15759'), aspect: 1},
  ];
  const side = Math.sqrt(800 * 500 * 0.55 / n);
  const units = [], base = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) {
    units.push([0, i % 2, side, side]);
    base.set([Math.random() * 800, Math.random() * 500, rotating ? Math.random() * 360 : 0], 3 * i);
  }
  const frameAt = (t) => {  // what Python sends: float32 (N, 4) bytes
    const f = new Float32Array(4 * n), scale = 0.6 + 0.4 * Math.min(1, t / 2);
    for (let i = 0; i < n; i++) {
      f[4 * i] = base[3 * i] + 20 * Math.sin(t + i);
      f[4 * i + 1] = base[3 * i + 1] + 20 * Math.cos(t + 0.5 * i);
      f[4 * i + 2] = rotating ? base[3 * i + 2] + 40 * t : 0;
      f[4 * i + 3] = scale;
    }
    return new DataView(f.buffer);
  };
  s.units = unitopia.f32(units);
  s.colors = unitopia.u8(units.map(() => [90, 90, 90, 255]));
  s.frame = frameAt(0);
  s.status = 'running';
  unitopia.mount(s);
  const stats = document.querySelector('[data-unitopia]').unitopiaStats;
  // Let the sprites decode before measuring.
  await new Promise((r) => setTimeout(r, 500));
  const p0 = stats.paints, ms0 = stats.paintMs;
  const t0 = performance.now();
  let pushed = 0;
  await new Promise((resolve) => {
    const timer = setInterval(() => {
      const t = (performance.now() - t0) / 1000;
      if (t >= seconds) { clearInterval(timer); resolve(); return; }
      fake.push('frame', frameAt(t));
      fake.push('frame_count', ++pushed);
    }, 1000 / hz);
  });
  const elapsed = (performance.now() - t0) / 1000;
  const paints = stats.paints - p0;
  unitopia.unmount();
  return {n, rotating, pushed, elapsed, paints, paintMs: (stats.paintMs - ms0) / Math.max(1, paints)};
}
"""


class _Handler(http.server.SimpleHTTPRequestHandler):
    def translate_path(self, path: str) -> str:
        clean = path.split("?", 1)[0]
        if clean.startswith("/static/"):
            return str(STATIC_DIR / clean[len("/static/"):])
        return super().translate_path(path)

    def log_message(self, *args) -> None:
        pass


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--hz", type=float, default=30.0)
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 5000])
    opts = parser.parse_args()
    if not (STATIC_DIR / "widget.js").exists():
        raise SystemExit("build the front end first: npm --prefix js ci && npm --prefix js run build")
    if not os.path.exists(CHROMIUM):
        raise SystemExit(f"needs Chromium at {CHROMIUM}")
    from playwright.sync_api import sync_playwright

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_Handler, directory=str(PAGE_DIR)))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}/index.html"
    rows = []
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            page = browser.new_page(viewport={"width": 1400, "height": 900})
            page.goto(url)
            page.wait_for_function("window.unitopiaReady === true")
            for n in opts.sizes:
                for rotating in (False, True):
                    rows.append(page.evaluate(STREAM_JS, [n, opts.seconds, opts.hz, rotating]))
            browser.close()
    finally:
        server.shutdown()
        server.server_close()

    print(f"front-end animation, headless Chromium, software rendering, {os.cpu_count()} cores, {platform.machine()}")
    print(f"{'marks':>6} {'marks are':>9} {'frames in':>10} {'in/s':>6} {'painted':>8} {'fps':>6} {'ms/paint':>9}")
    for r in rows:
        kind = "rotating" if r["rotating"] else "upright"
        print(f"{r['n']:>6} {kind:>9} {r['pushed']:>10} {r['pushed'] / r['elapsed']:>6.1f} {r['paints']:>8} "
              f"{r['paints'] / r['elapsed']:>6.1f} {r['paintMs']:>9.2f}")


if __name__ == "__main__":
    main()
