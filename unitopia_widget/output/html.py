"""The chart as one self-contained HTML page: vector SVG, tooltips, legend, title, replay.

The page needs no kernel and no network. It carries the sanitised SVG export as a
JSON string parsed by the browser's XML parser (``DOMParser``, as when the SVG file
is opened itself), so the HTML parser never reads user content; a Content Security
Policy allows only the page's own script (by hash) and inline styles and data: images.
The replay is the last run's frames as JSON, per frame and unit ``[x, y, angle, sx,
sy]`` (canvas px, degrees, box scale), written into each unit's transform.
"""
from __future__ import annotations

import base64
import hashlib
import json
from xml.sax.saxutils import escape

import numpy as np

from .animation import resample

REPLAY_FRAMES = 60   # frames kept in the page: 1,000 units x 60 x 5 numbers is about 1.5 MB

SCRIPT = """
(function () {
  const data = JSON.parse(document.getElementById("chart-data").textContent);
  const doc = new DOMParser().parseFromString(data.svg, "image/svg+xml");
  const svg = document.importNode(doc.documentElement, true);
  document.getElementById("chart").appendChild(svg);
  const units = svg.querySelectorAll("g.unit");
  const frames = data.frames, box = data.box;
  const range = document.getElementById("scrub"), button = document.getElementById("play");
  range.max = String(Math.max(0, frames.length - 1));
  range.value = range.max;
  function show(f) {
    const fr = frames[f];
    for (let i = 0; i < units.length && 5 * i < fr.length; i++) {
      const o = 5 * i;
      units[i].setAttribute("transform", "translate(" + fr[o] + " " + fr[o + 1] + ") rotate(" +
        fr[o + 2] + ") scale(" + fr[o + 3] + " " + fr[o + 4] + ") translate(" +
        (-box[2 * i] / 2) + " " + (-box[2 * i + 1] / 2) + ")");
    }
    range.value = String(f);
  }
  let timer = null;
  function stop() { clearInterval(timer); timer = null; button.textContent = "Play"; }
  button.addEventListener("click", function () {
    if (timer) { stop(); return; }
    let f = Number(range.value) >= frames.length - 1 ? 0 : Number(range.value);
    button.textContent = "Pause";
    show(f);
    timer = setInterval(function () {
      f += 1;
      if (f >= frames.length) { stop(); return; }
      show(f);
    }, 1000 / data.fps);
  });
  range.addEventListener("input", function () { stop(); show(Number(range.value)); });
})();
"""


def script_json(data) -> str:
    """``data`` as JSON that a ``<script>`` element holds whole: no ``<``, ``>`` or ``&``."""
    text = json.dumps(data, separators=(",", ":"))
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def content_policy(script: str) -> str:
    """The page's Content-Security-Policy: nothing from the network, only ``script`` (by
    its hash) runs, inline styles and data: images and fonts."""
    digest = base64.b64encode(hashlib.sha256(script.encode()).digest()).decode()
    return (f"default-src 'none'; script-src 'sha256-{digest}'; style-src 'unsafe-inline'; "
            f"img-src data:; font-src data:")


def replay(chart, count: int = REPLAY_FRAMES) -> dict:
    """``{"frames": [[x, y, angle, sx, sy per unit]...], "box": [bw, bh per unit]}``."""
    units, frames = chart.laid.units, chart.laid.frames
    frames = resample(frames, min(count, len(frames)))
    box = units.box_size
    sx = 2 * units.half_w[None] * frames[:, :, 3] / box[None, :, 0]
    sy = 2 * units.half_h[None] * frames[:, :, 3] / box[None, :, 1]
    per = np.stack([frames[:, :, 0], frames[:, :, 1], frames[:, :, 2], sx, sy], axis=2)
    rounded = [np.round(per[:, :, :3], 2), np.round(per[:, :, 3:], 5)]
    per = np.concatenate(rounded, axis=2).reshape(len(frames), -1)
    return {"frames": per.tolist(), "box": np.round(box, 4).reshape(-1).tolist()}


def page(svg: str, title: str | None, frames: dict, fps: float = 20.0) -> str:
    """The HTML text of the page holding ``svg`` (the sanitised export) and ``frames``."""
    data = script_json({"svg": svg, "fps": fps, **frames})
    policy = content_policy(SCRIPT)
    return (f'<!DOCTYPE html>\n<html><head><meta charset="utf-8">'
            f'<meta http-equiv="Content-Security-Policy" content="{policy}">'
            f'<title>{escape(title or "Unit chart")}</title>'
            f'<style>body{{font-family:sans-serif;margin:16px}}#chart svg{{max-width:100%;height:auto}}'
            f'#controls{{margin-top:8px}}</style></head><body>'
            f'<div id="chart"></div><div id="controls"><button id="play" type="button">Play</button> '
            f'<input id="scrub" type="range" min="0" max="0" step="1" aria-label="settling frame">'
            f'</div><script type="application/json" id="chart-data">{data}</script>'
            f'<script>{SCRIPT}</script></body></html>\n')
