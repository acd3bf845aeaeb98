"""A story as one self-contained HTML page: its slides as vector SVG with tooltips,
previous / next buttons, the arrow keys, and the transitions animated.

As ``output.html``: the page needs no kernel and no network; the slides' sanitised SVG
exports travel inside a JSON string that the browser's XML parser reads, so the HTML
parser never reads user content, and a Content Security Policy allows only the page's
own script (by hash), inline styles and data: images. The script is the story player
bundled from ``js/src/story-page.js`` (``static/story-page.js``).
"""
from __future__ import annotations

import pathlib
from xml.sax.saxutils import escape

from .html import content_policy, script_json

SCRIPT = pathlib.Path(__file__).parent.parent / "static" / "story-page.js"
STYLE = ("body{font-family:system-ui,sans-serif;margin:0;padding:16px;color:#222;background:#fff}"
         "#story{max-width:100%;margin:0 auto;outline:none}"
         ".story-stage{margin:0 auto}"
         ".story-controls{display:flex;flex-wrap:wrap;align-items:center;gap:8px;justify-content:center;"
         "margin-top:10px;font-size:14px}"
         ".story-controls button{font:inherit;padding:4px 12px;border:1px solid #bbb;border-radius:4px;"
         "background:#f6f6f6;cursor:pointer}.story-controls button:disabled{opacity:.4;cursor:default}"
         ".story-count{min-width:3em;text-align:center}")


def page(data: dict, title: str | None) -> str:
    """The HTML text of the page playing ``data`` (``Story.player()``)."""
    script = SCRIPT.read_text(encoding="utf-8")
    if "</script" in script.lower():
        raise RuntimeError(f"{SCRIPT} holds '</script', which would end the page's script early")
    text = script_json(data)
    policy = content_policy(script)
    return (f'<!DOCTYPE html>\n<html><head><meta charset="utf-8">'
            f'<meta http-equiv="Content-Security-Policy" content="{policy}">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f'<title>{escape(title or "Unit story")}</title><style>{STYLE}</style></head><body>'
            f'<div id="story"></div>'
            f'<script type="application/json" id="story-data">{text}</script>'
            f'<script>{script}</script></body></html>\n')
