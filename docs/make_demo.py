"""Regenerate ``docs/demo.png``, the README's picture: ``python docs/make_demo.py``.

It lays out the built-in demo (``python -m unitopia_widget demo``: stars settling in a
jar) and renders its SVG export at 1 canvas px = 1 image px over white. The PNG carries
the demo's fingerprint (a hash of its design and data) in a text chunk, so a test can tell
cheaply, without a layout, whether the picture still shows what the demo draws.
"""
from __future__ import annotations

import hashlib
import io
import json
import pathlib
import sys

import numpy as np
from PIL import Image, PngImagePlugin

from unitopia_widget.demo import demo_chart
from unitopia_widget.io.images import load_image
from unitopia_widget.output.export import svg_size, to_png

OUT = pathlib.Path(__file__).resolve().parent / "demo.png"
KEY = "unitopia-demo"   # the PNG text chunk that holds the fingerprint


def fingerprint(chart) -> str:
    """sha256 of the chart's design JSON and its rows, the background as its pixels (a PNG's
    bytes vary with the zlib that wrote it): what the demo draws, known before layout."""
    design = chart.design()
    background = design.pop("background")
    pixels = b"" if background is None else \
        np.asarray(load_image(background["image"]).convert("RGBA")).tobytes()
    digest = hashlib.sha256(json.dumps(design, sort_keys=True).encode())
    digest.update(chart.df.to_csv().encode())
    digest.update(pixels)
    return digest.hexdigest()


def main(out=OUT) -> pathlib.Path:
    chart = demo_chart()
    chart.layout()
    svg = chart.to_svg()
    image = Image.open(io.BytesIO(to_png(svg, svg_size(svg), 1.0))).convert("RGBA")
    flat = Image.new("RGBA", image.size, "white")
    flat.alpha_composite(image)
    info = PngImagePlugin.PngInfo()
    info.add_text(KEY, fingerprint(chart))
    flat.convert("RGB").save(out, pnginfo=info, optimize=True)
    return pathlib.Path(out)


if __name__ == "__main__":
    print(f"wrote {main(*sys.argv[1:2])}")
