"""Safe raster loading, data URLs and the pixel operations raster marks need.

Images are PIL images in RGBA mode; arrays are ``(H, W)``, ``(H, W, 3)`` or
``(H, W, 4)``, uint8 or float in [0, 1]. Every entry point checks the pixel
count against :data:`MAX_PIXELS` from the header, before any decoding.
"""
from __future__ import annotations

import base64
import binascii
import io
import os
import re
import urllib.parse
import warnings

import numpy as np
from PIL import Image, ImageColor
from scipy import ndimage

MAX_PIXELS = 40_000_000
MAX_DATA_URL_CHARS = 64_000_000
FORMATS = ("PNG", "JPEG", "GIF", "WEBP")
_DATA_URL = re.compile(r"^data:([\w.+-]+/[\w.+-]+)?((?:;[^,;]*)*),", re.I | re.S)


def check_pixels(width: int, height: int, what: str = "image") -> None:
    """Raise ValueError if ``width * height`` exceeds :data:`MAX_PIXELS`."""
    if width * height > MAX_PIXELS:
        raise ValueError(
            f"{what} is too large: {width} x {height} = {width * height:,} pixels "
            f"exceeds the cap of {MAX_PIXELS:,} pixels")


def parse_data_url(url: str) -> tuple[str, bytes]:
    """Split a ``data:`` URL into (lower-case MIME type, payload bytes)."""
    if not isinstance(url, str):
        raise ValueError(f"expected a data URL string, got {type(url).__name__}")
    if len(url) > MAX_DATA_URL_CHARS:
        raise ValueError(f"data URL longer than {MAX_DATA_URL_CHARS:,} characters")
    match = _DATA_URL.match(url.strip())
    if not match:
        raise ValueError(f"not a data URL: {url[:40]!r}")
    mime = (match.group(1) or "text/plain").lower()
    body = url.strip()[match.end():]
    if ";base64" in match.group(2).lower():
        try:
            return mime, base64.b64decode(re.sub(r"\s+", "", body), validate=True)
        except (binascii.Error, ValueError) as exc:
            raise ValueError(f"data URL has invalid base64: {exc}") from None
    return mime, urllib.parse.unquote_to_bytes(body)


def decode_data_url(url: str) -> bytes:
    """Bytes of a ``data:image/png|jpeg;base64,...`` URL; anything else -> ValueError."""
    if not isinstance(url, str) or not re.match(r"^\s*data:image/(png|jpeg|jpg);base64,", url, re.I):
        raise ValueError(
            f"expected a data:image/png or data:image/jpeg base64 URL, got {str(url)[:40]!r}")
    return parse_data_url(url)[1]


def image_data_url(img: Image.Image) -> str:
    """A ``data:image/png;base64,...`` URL of ``img``."""
    buf = io.BytesIO()
    img.save(buf, format="PNG")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def probe_size(data: bytes) -> tuple[int, int] | None:
    """(width, height) read from an encoded image's header, or None if unreadable."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            with Image.open(io.BytesIO(data), formats=FORMATS) as img:
                return img.size
    except Image.DecompressionBombError:
        return (MAX_PIXELS + 1, 1)
    except Exception:
        return None


def _open(fp, name: str) -> Image.Image:
    """Open an encoded image, check its header size, then decode to RGBA."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            img = Image.open(fp, formats=FORMATS)
    except Image.DecompressionBombError as exc:
        raise ValueError(f"{name} is too large ({exc}); the cap is {MAX_PIXELS:,} pixels") from None
    except (OSError, ValueError, SyntaxError) as exc:
        raise ValueError(f"cannot read {name} as a PNG/JPEG image: {exc}") from None
    with img:
        check_pixels(*img.size, what=name)
        try:
            img.load()
            return _rgba(img)
        except (OSError, ValueError, SyntaxError, Image.DecompressionBombError) as exc:
            raise ValueError(f"cannot decode {name}: {exc}") from None


def _rgba(img: Image.Image) -> Image.Image:
    """``img`` in RGBA. Grey of 16 bits a sample (``I;16`` or ``I``, as Pillow opens a 16-bit
    grey PNG) is scaled to 8 bits first, its tRNS grey value becoming transparency: Pillow's
    own conversion clips every value past 255, so mid-grey turned white."""
    if img.mode not in ("I", "I;16", "I;16B", "I;16L"):
        return img.convert("RGBA")
    grey = np.asarray(img).astype(np.int64)
    out = np.empty(grey.shape + (4,), np.uint8)
    out[..., :3] = np.clip((grey + 128) // 257, 0, 255)[..., None]
    key = img.info.get("transparency")
    out[..., 3] = 255 if key is None else np.where(grey == key, 0, 255)
    return Image.fromarray(out, "RGBA")


def _from_array(arr: np.ndarray) -> Image.Image:
    if arr.ndim not in (2, 3) or (arr.ndim == 3 and arr.shape[2] not in (3, 4)):
        raise ValueError(f"expected an (H, W), (H, W, 3) or (H, W, 4) array, got {arr.shape}")
    check_pixels(arr.shape[1], arr.shape[0], what="array image")
    if arr.dtype == np.bool_:
        arr = arr.astype(np.uint8) * 255
    elif np.issubdtype(arr.dtype, np.floating):
        if not np.isfinite(arr).all():
            raise ValueError("float image array contains NaN or infinity")
        arr = np.round(np.clip(arr, 0.0, 1.0) * 255.0).astype(np.uint8)
    elif arr.dtype != np.uint8:
        raise ValueError(f"expected a uint8 or float image array, got dtype {arr.dtype}")
    return Image.fromarray(np.ascontiguousarray(arr)).convert("RGBA")


def load_image(source) -> Image.Image:
    """An RGBA PIL image from a path, bytes, data URL, ndarray or PIL image."""
    if isinstance(source, Image.Image):
        check_pixels(*source.size, what="PIL image")
        return _rgba(source) if source.mode != "RGBA" else source.copy()
    if isinstance(source, np.ndarray):
        return _from_array(source)
    if isinstance(source, (bytes, bytearray, memoryview)):
        return _open(io.BytesIO(bytes(source)), "image bytes")
    if isinstance(source, str) and source.lstrip()[:5].lower() == "data:":
        return _open(io.BytesIO(decode_data_url(source)), "image data URL")
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        try:
            with open(path, "rb") as fp:
                return _open(io.BytesIO(fp.read(MAX_DATA_URL_CHARS)), f"image file {path!r}")
        except OSError as exc:
            raise ValueError(f"cannot read image file {path!r}: {exc.strerror or exc}") from None
    raise ValueError(f"cannot load an image from {type(source).__name__}")


def has_transparency(img: Image.Image) -> bool:
    """True if some pixel of an RGBA image is not fully opaque."""
    return img.getextrema()[3][0] < 255


def key_background(img: Image.Image, key: str = "auto", tolerance: float = 0.1) -> Image.Image:
    """Make a uniform background transparent.

    ``key="auto"``: the background is the median border colour, used only if at
    least 90% of border pixels lie within ``tolerance`` (max channel difference,
    in [0, 1]); only pixels of that colour connected to the border are removed,
    so same-coloured details inside the figure stay. ``key`` a CSS colour: every
    pixel within ``tolerance`` of it is removed. If every pixel matches,
    nothing is removed.
    """
    rgba = np.asarray(img.convert("RGBA")).copy()
    rgb = rgba[..., :3].astype(np.int16)
    if key == "auto":
        border = np.concatenate([rgb[0], rgb[-1], rgb[:, 0], rgb[:, -1]])
        colour = np.median(border, axis=0)
        near_border = np.abs(border - colour).max(axis=1) <= tolerance * 255
        if near_border.mean() < 0.9:
            return Image.fromarray(rgba)
    else:
        try:
            colour = np.array(ImageColor.getrgb(key)[:3])
        except ValueError:
            raise ValueError(f"key must be 'auto', None or a CSS colour, got {key!r}") from None
    near = np.abs(rgb - colour).max(axis=2) <= tolerance * 255
    if key == "auto":
        labels, _ = ndimage.label(near)
        edge = np.unique(np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]]))
        near = np.isin(labels, edge[edge > 0])
    if not near.all():  # a uniform image is a swatch, not a background: keep it
        rgba[near, 3] = 0
    return Image.fromarray(rgba)


def crop_to_alpha(img: Image.Image) -> Image.Image:
    """Tight crop to the pixels with alpha > 0; ValueError if there are none."""
    box = img.getchannel("A").getbbox()
    if box is None:
        raise ValueError("image mark is empty: every pixel is transparent")
    return img.crop(box)


def resize_alpha(img: Image.Image, size: tuple[int, int]) -> np.ndarray:
    """float32 (h, w) alpha in [0, 1] of ``img`` resized to ``size = (w, h)``.

    Area averaging when shrinking, bilinear when enlarging.
    """
    alpha = img.getchannel("A").convert("F")
    shrink = size[0] <= img.width and size[1] <= img.height
    out = alpha.resize(size, Image.Resampling.BOX if shrink else Image.Resampling.BILINEAR)
    return np.clip(np.asarray(out, dtype=np.float32) / 255.0, 0.0, 1.0)


def tint(img: Image.Image, color: str) -> Image.Image:
    """Recolour an RGBA image to ``color``, keeping alpha and luminance detail.

    Luminance is normalised over the visible pixels; the brightest become the
    colour itself, the darkest 45% of it. A flat image becomes the flat colour.
    """
    rgba = np.asarray(img.convert("RGBA")).astype(np.float32)
    target = np.array(ImageColor.getrgb(color)[:3], dtype=np.float32)
    lum = rgba[..., :3] @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
    visible = rgba[..., 3] > 0
    lo, hi = (np.percentile(lum[visible], [1, 99]) if visible.any() else (0.0, 0.0))
    rel = np.clip((lum - lo) / (hi - lo), 0.0, 1.0) if hi - lo > 8 else np.ones_like(lum)
    out = rgba.copy()
    out[..., :3] = target * (0.45 + 0.55 * rel)[..., None]
    return Image.fromarray(np.round(out).astype(np.uint8))
