"""SVG and raster safety: hostile inputs are refused fast or cleaned."""
import base64
import io
import struct
import time
import re
import zlib
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import resvg_py
from PIL import Image

from unitopia_widget.io import images, svgsafe
from unitopia_widget.design.marks import Mark

DATA = Path(__file__).parent / "data" / "marks"
SVG = 'xmlns="http://www.w3.org/2000/svg"'


def png_header_only(width: int, height: int) -> bytes:
    """A PNG whose header claims ``width x height`` but whose pixel data is a few bytes."""
    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
            + chunk(b"IDAT", zlib.compress(b"\x00" * 64)) + chunk(b"IEND", b""))


def red_png_file(tmp_path: Path) -> Path:
    path = tmp_path / "secret.png"
    Image.new("RGBA", (8, 8), (255, 0, 0, 255)).save(path)
    return path


# --- XML level ---------------------------------------------------------------

def test_billion_laughs_is_refused_fast():
    start = time.perf_counter()
    with pytest.raises(ValueError, match=r"SVG .*entity"):
        svgsafe.sanitize_svg((DATA / "billion_laughs.svg").read_text())
    assert time.perf_counter() - start < 0.2


def test_external_entity_is_refused():
    text = (f'<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
            f'<svg {SVG}><text>&x;</text></svg>')
    with pytest.raises(ValueError, match="entity"):
        svgsafe.sanitize_svg(text)


def test_plain_doctype_without_entities_is_accepted():
    clean = svgsafe.sanitize_svg((DATA / "hostile.svg").read_text())
    assert clean.startswith("<svg") and "DOCTYPE" not in clean


@pytest.mark.parametrize("text, message", [
    ("<svg><g></svg>", "not well-formed"),
    ("", "not well-formed"),
    ("<html><body/></html>", "root element is <html>"),
    ("<svg", "not well-formed"),
])
def test_malformed_or_non_svg_is_refused(text, message):
    with pytest.raises(ValueError, match=message):
        svgsafe.sanitize_svg(text)


def test_size_cap_names_the_limit():
    text = f"<svg {SVG}><desc>{'x' * (svgsafe.MAX_SVG_BYTES + 10)}</desc></svg>"
    with pytest.raises(ValueError, match="5,000,000 bytes"):
        svgsafe.sanitize_svg(text)


def test_element_cap_names_the_limit():
    text = f"<svg {SVG}>" + "<g/>" * svgsafe.MAX_SVG_ELEMENTS + "</svg>"
    with pytest.raises(ValueError, match="50,000 elements"):
        svgsafe.sanitize_svg(text)


def test_deep_nesting_is_refused():
    text = f"<svg {SVG}>" + "<g>" * 500 + "</g>" * 500 + "</svg>"
    with pytest.raises(ValueError, match="deeper than"):
        svgsafe.sanitize_svg(text)


# --- active content and external references ---------------------------------

def test_hostile_content_is_removed_and_design_kept():
    clean = svgsafe.sanitize_svg((DATA / "hostile.svg").read_text())
    lowered = clean.lower()
    for bad in ("script", "onload", "onclick", "foreignobject", "javascript", "file:",
                "/etc/hosts", "/etc/passwd", "evil.example", "@import", "inkscape"):
        assert bad not in lowered, bad
    assert ".body { fill: #3366cc; }" in clean          # styles kept
    assert 'id="grad"' in clean and 'fill="url(#grad)"' in clean   # gradients kept
    assert clean.count("<rect") == 2                     # the wrapped shape survives its <a>
    assert svgsafe.sanitize_svg(clean) == clean          # idempotent


def test_external_image_references_are_never_read(tmp_path):
    secret = red_png_file(tmp_path)
    text = (f'<svg {SVG} xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 100 100">'
            f'<rect x="40" y="40" width="20" height="20" fill="#000"/>'
            f'<image href="file://{secret}" x="0" y="0" width="100" height="30"/>'
            f'<image xlink:href="{secret}" x="0" y="70" width="100" height="30"/></svg>')
    # control: resvg itself would load the absolute path if handed the raw text
    raw = np.asarray(Image.open(io.BytesIO(bytes(resvg_py.svg_to_bytes(svg_string=text)))))
    assert raw[85, 50, 3] == 255 and raw[85, 50, 0] == 255
    clean = svgsafe.sanitize_svg(text)
    assert str(secret) not in clean and "href" not in clean
    mark = Mark.svg(text)
    assert mark.box_size == pytest.approx((20, 20), rel=0.01)   # the images contribute nothing


def test_etc_hosts_and_passwd_hrefs_are_dropped():
    text = (f'<svg {SVG} xmlns:xlink="http://www.w3.org/1999/xlink">'
            '<image href="file:///etc/passwd" width="9" height="9"/>'
            '<image xlink:href="/etc/hosts" width="9" height="9"/>'
            '<use href="#ok"/><rect id="ok" width="1" height="1"/></svg>')
    clean = svgsafe.sanitize_svg(text)
    assert "etc" not in clean
    assert '<use href="#ok"' in clean


def test_css_urls_other_than_fragments_and_data_images_are_removed():
    dot = images.image_data_url(Image.new("RGBA", (2, 2), (0, 0, 255, 255)))
    text = (f'<svg {SVG}><style>@import "x.css"; .a {{ fill: url(#g) }} '
            f'.b {{ fill: url(http://evil.example/x) }} .c {{ background: url("{dot}") }} '
            f'.d {{ fill: u\\72l(http://evil.example/y) }} .e {{ mask: image-set("m.png" 1x) }}'
            '</style><rect style="fill: url(  \'//evil.example/z\' )" width="1" height="1"/></svg>')
    clean = svgsafe.sanitize_svg(text)
    assert "evil" not in clean and "x.css" not in clean and "m.png" not in clean
    assert "url(#g)" in clean and dot in clean


def test_data_image_bomb_and_nested_svg_script_are_cleaned():
    bomb = "data:image/png;base64," + base64.b64encode(png_header_only(100_000, 100_000)).decode()
    inner = f'<svg {SVG}><script>alert(1)</script><rect width="5" height="5"/></svg>'
    nested = "data:image/svg+xml;base64," + base64.b64encode(inner.encode()).decode()
    text = (f'<svg {SVG}><image href="{bomb}" width="9" height="9"/>'
            f'<image href="{nested}" width="9" height="9"/></svg>')
    clean = svgsafe.sanitize_svg(text)
    assert bomb not in clean
    payload = clean.split("data:image/svg+xml;base64,")[1].split('"')[0]
    inner_clean = base64.b64decode(payload).decode()
    assert "<rect" in inner_clean and "script" not in inner_clean


def test_animation_cannot_set_href_or_handlers():
    text = (f'<svg {SVG}><a><set attributeName="href" to="javascript:alert(1)"/>'
            '<animate attributeName="onclick" values="alert(1)"/>'
            '<animate attributeName="opacity" values="0;1"/><rect width="1" height="1"/></a></svg>')
    clean = svgsafe.sanitize_svg(text)
    assert "javascript" not in clean and "onclick" not in clean
    assert 'attributeName="opacity"' in clean


# --- raster safety -----------------------------------------------------------

@pytest.mark.parametrize("side", [100_000, 20_000, 7_000])
def test_decompression_bomb_is_refused_before_decoding(tmp_path, side):
    path = tmp_path / "bomb.png"
    path.write_bytes(png_header_only(side, side))
    start = time.perf_counter()
    with pytest.raises(ValueError, match=r"too large.*40,000,000 pixels"):
        images.load_image(path)
    with pytest.raises(ValueError, match="too large"):
        Mark.image(str(path))
    assert time.perf_counter() - start < 0.5


def test_huge_array_is_refused_by_shape():
    arr = np.broadcast_to(np.zeros(1, np.uint8), (8000, 8000))
    with pytest.raises(ValueError, match="8000 x 8000.*40,000,000"):
        images.load_image(arr)


def test_unreadable_image_names_the_path(tmp_path):
    missing = tmp_path / "nope.png"
    with pytest.raises(ValueError, match="nope.png"):
        images.load_image(missing)
    junk = tmp_path / "junk.png"
    junk.write_bytes(b"not an image at all")
    with pytest.raises(ValueError, match="junk.png"):
        images.load_image(junk)


def test_data_urls_only_png_or_jpeg():
    url = images.image_data_url(Image.new("RGBA", (3, 2), (1, 2, 3, 4)))
    assert url.startswith("data:image/png;base64,")
    assert images.decode_data_url(url)[:8] == b"\x89PNG\r\n\x1a\n"
    assert images.load_image(url).getpixel((0, 0)) == (1, 2, 3, 4)
    for bad in ("data:image/svg+xml;base64,PHN2Zy8+", "data:text/html;base64,PGI+",
                "https://example.com/a.png", "data:image/png;base64,@@@"):
        with pytest.raises(ValueError):
            images.decode_data_url(bad)


def test_render_uses_only_sanitised_trees():
    root = svgsafe.parse_svg(f'<svg {SVG} viewBox="0 0 4 2"><rect width="2" height="2"/></svg>')
    rgba = svgsafe.render_svg(root, 40, 20)
    assert rgba.shape == (20, 40, 4) and rgba.dtype == np.uint8
    assert rgba[10, 5, 3] == 255 and rgba[10, 35, 3] == 0
    assert "width" not in root.attrib                     # the tree is left unchanged


HOSTILE_CSS = ("@charset 'x'; @layer x { .jp-Cell { color: red } } "
               "@container (min-width: 1px) { .jp-Cell { color: red } } "
               "@scope (.jp-Cell) { :scope { color: red } } @font-face { font-family: q } "
               "@layer a, b; @media print { @supports (color: red) { .jp-Cell { color: red } } } "
               ".body { fill: #00ff00; & .jp-Cell { color: red } .inner { fill: blue } } "
               "#dot { fill: #0000ff }")


def test_every_rule_is_scoped_or_dropped_at_any_depth():
    from unitopia_widget.io.svgsafe import _blocks
    root = svgsafe.parse_svg(f'<svg {SVG} viewBox="0 0 2 1"><style><![CDATA[{HOSTILE_CSS}]]></style>'
                             '<rect class="body" width="1" height="1"/>'
                             '<rect id="dot" x="1" width="1" height="1"/></svg>')
    svgsafe.scope(root, "m")
    css = root.find("style").text
    assert "@scope" not in css and "@font-face" not in css and "@charset" not in css

    def selectors(text, nested=False):
        for head, body in _blocks(text):
            if body is None:
                continue
            if head.startswith("@"):
                yield from selectors(body, nested)
            else:
                for s in head.split(","):
                    yield s.strip(), nested
                yield from selectors(body, True)
    found = list(selectors(css))
    assert len(found) == 7
    for selector, nested in found:      # top level under #m; nested ones relative to their rule
        assert nested or selector.startswith("#m "), selector
        assert re.search(r"[.#](?!m\b)(?!m-)", selector) is None, selector
    assert "#m #m-dot" in css and 'id="m-dot"' in svgsafe.serialize(root)


def test_id_selectors_follow_ids_renamed_in_a_page():
    from unitopia_widget.jupyter.notebook import prefix_ids
    root = svgsafe.parse_svg(f'<svg {SVG} viewBox="0 0 2 1"><style>#dot {{ fill: #0000ff }} '
                             '.body > rect { fill: #00ff00 }</style>'
                             '<g class="body"><rect width="1" height="1"/></g>'
                             '<rect id="dot" x="1" width="1" height="1"/></svg>')
    svgsafe.scope(root, "u0m0")
    doc = ET.Element("svg", viewBox="0 0 2 1")
    group = ET.SubElement(doc, "g", id="u0m0")
    group.append(root)
    text = prefix_ids(ET.tostring(doc, encoding="unicode"), "c1234")
    assert "#c1234-u0m0 #c1234-u0m0-dot" in text and "#0000ff" in text
    pixels = svgsafe.render_svg(svgsafe.parse_svg(text), 20, 10)
    assert tuple(pixels[5, 5, :3]) == (0, 255, 0) and tuple(pixels[5, 15, :3]) == (0, 0, 255)
