"""Render the gallery thumbnails in docs/gallery/ from the notebooks' SVG results.

Run the notebooks first (they write notebooks/out/*.svg), then, from the repository root:
    python notebooks/make_gallery.py
Each thumbnail is about 400 px wide, a palette PNG well under 150 KB.
"""
import io
import re
import sys
from pathlib import Path

import resvg_py
from PIL import Image

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "notebooks" / "out"
GALLERY = ROOT / "docs" / "gallery"
WIDTH = 400

# thumbnail name -> the notebook result(s) it shows (several are placed side by side)
THUMBS = {
    "01-quickstart": ["01-quickstart.svg"],
    "02-dear-data": ["02-dear-data.svg"],
    "03-organic-trees": ["03-organic-trees.svg"],
    "04-sedimentation": ["04-sedimentation.svg", "04-sedimentation-no-emitter.svg"],
    "05-bottle-of-dreams": ["05-bottle-of-dreams.svg"],
    "06-timeline": ["06-timeline.svg"],
    "07-storytelling": ["07-slide-1-jar.svg", "07-slide-2-piles.svg", "07-slide-3-timeline.svg"],
    "08-gallery": ["08-gallery.png"],
    "09-mark-groups": ["09-mark-groups.svg", "09-mark-set.svg"],
    "10-story": ["10-story-1.svg", "10-story-2.svg", "10-story-3.svg"],
    "12-beeswarm-waffle": ["12-beeswarm.svg", "12-waffle.svg"],
    "13-isotype": ["13-isotype.svg"],
    "14-piles": ["14-piles.svg", "14-piles-columns.svg"],
}


def render(path: Path, width: int) -> Image.Image:
    if path.suffix == ".png":
        img = Image.open(path).convert("RGB")
        return img.resize((width, round(img.height * width / img.width)), Image.LANCZOS)
    svg = path.read_text()
    # exported charts keep a padding around the canvas: the viewBox starts at -pad, -pad
    w, h = (float(v) for v in re.search(r'viewBox="[-\d.]+ [-\d.]+ ([\d.]+) ([\d.]+)"', svg).groups())
    png = resvg_py.svg_to_bytes(svg_string=svg, width=2 * width, height=round(2 * width * h / w))
    img = Image.open(io.BytesIO(bytes(png))).convert("RGBA")
    flat = Image.new("RGBA", img.size, "white")
    flat.alpha_composite(img)
    return flat.convert("RGB").resize((width, round(width * h / w)), Image.LANCZOS)


def main(names) -> None:
    GALLERY.mkdir(parents=True, exist_ok=True)
    for name in names:
        files = THUMBS[name]
        missing = [f for f in files if not (OUT / f).exists()]
        if missing:
            print(f"{name}: skipped, run its notebook first (missing {', '.join(missing)})")
            continue
        cols = min(len(files), 2)            # several results: a grid two tiles wide
        rows = -(-len(files) // cols)
        part = (WIDTH - 8 * (cols - 1)) // cols
        tiles = [render(OUT / f, part) for f in files]
        tall = max(t.height for t in tiles)
        thumb = Image.new("RGB", (WIDTH, rows * tall + 8 * (rows - 1)), "white")
        for i, t in enumerate(tiles):
            thumb.paste(t, ((i % cols) * (part + 8), (i // cols) * (tall + 8)))
        target = GALLERY / f"{name}.png"
        thumb.quantize(colors=128, method=Image.MEDIANCUT, dither=Image.NONE).save(target, optimize=True)
        print(f"{target.relative_to(ROOT)}: {thumb.width}x{thumb.height}, "
              f"{target.stat().st_size / 1024:.0f} KB")


if __name__ == "__main__":
    main(sys.argv[1:] or list(THUMBS))
