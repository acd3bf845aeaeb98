"""Marks cost what they look like: filter primitives whose rendering time grows with a
radius, a kernel or a count are capped relative to the SVG's view box.

resvg spends ``(2r + 1)^2`` operations per pixel on an ``feMorphology`` of radius ``r`` px,
and more for huge ``feGaussianBlur`` deviations, large ``feConvolveMatrix`` kernels and
many ``feTurbulence`` octaves; a 170-byte mark with ``radius="5"`` in a 100-unit view box
held the kernel for four minutes at the 1,024 px a mark is measured at, and an interrupt
cannot stop resvg. Capped here, on the sanitised tree every mark, design file, story
and upload goes through, each with one warning naming the mark's element and the cap.
"""
from __future__ import annotations

import re
import warnings
import xml.etree.ElementTree as ET

MORPHOLOGY_SHARE = 0.0025  # feMorphology radius: at most this share of the view box's long side
BLUR_SHARE = 0.1           # feGaussianBlur / feDropShadow stdDeviation: at most this share
MAX_KERNEL_ORDER = 5       # feConvolveMatrix order (kernel side): larger kernels are dropped
MAX_OCTAVES = 8            # feTurbulence numOctaves (more add nothing an 8-bit pixel shows)
MAX_COSTLY = 32            # costly primitives in one SVG: the ones after are dropped
DEFAULT_VIEW = 100.0       # resvg's size of an SVG without a viewBox, width or height
_COSTLY = {"femorphology", "fegaussianblur", "fedropshadow", "feconvolvematrix", "feturbulence"}
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def view_side(root: ET.Element) -> float:
    """The long side of the root's view box (its width/height without one), user units."""
    numbers = _numbers(root.get("viewBox", ""))
    if len(numbers) == 4 and min(numbers[2:]) > 0:
        return max(numbers[2:])
    sides = [n[0] for n in (_numbers(root.get(k, "")) for k in ("width", "height")) if n]
    return max(sides) if sides and max(sides) > 0 else DEFAULT_VIEW


def cap_filters(root: ET.Element) -> None:
    """Cap, in place, the costly filter primitives of a sanitised tree (local tag names),
    warning once per element changed or dropped."""
    side = view_side(root)
    count = 0
    for parent in list(root.iter()):
        for el in list(parent):
            kind = el.tag.lower() if isinstance(el.tag, str) else ""
            if kind not in _COSTLY:
                continue
            count += 1
            # primitiveUnits="objectBoundingBox": lengths are shares of the element's box
            share = 1.0 if parent.get("primitiveUnits") == "objectBoundingBox" else side
            if count > MAX_COSTLY:
                _drop(parent, el, f"more than {MAX_COSTLY} costly filter primitives")
            elif kind == "femorphology":
                _cap(el, "radius", MORPHOLOGY_SHARE * share)
            elif kind in ("fegaussianblur", "fedropshadow"):
                _cap(el, "stdDeviation", BLUR_SHARE * share)
            elif kind == "feconvolvematrix":
                order = _numbers(el.get("order", "3"))
                if not order or max(order) > MAX_KERNEL_ORDER or min(order) < 1:
                    _drop(parent, el, f"order {el.get('order')!r} is over {MAX_KERNEL_ORDER}")
            else:
                octaves = _numbers(el.get("numOctaves", "1"))
                if not octaves or octaves[0] > MAX_OCTAVES:
                    _warn(el, f"numOctaves {el.get('numOctaves')!r} capped at {MAX_OCTAVES}")
                    el.set("numOctaves", str(MAX_OCTAVES))


def _numbers(text: str) -> list[float]:
    return [float(n) for n in _NUMBER.findall(text or "")]


def _cap(el: ET.Element, name: str, limit: float) -> None:
    """Each number of attribute ``name`` at most ``limit``; a value that is not numbers
    (or not finite) is taken as over the cap."""
    values = _numbers(el.get(name, "0"))
    if values and all(abs(v) <= limit for v in values):
        return
    capped = " ".join(f"{min(abs(v), limit):.6g}" for v in values) or f"{limit:.6g}"
    _warn(el, f"{name} {el.get(name)!r} capped at {capped} ({limit:.6g}: a share of the "
              f"view box that renders in bounded time)")
    el.set(name, capped)


def _drop(parent: ET.Element, el: ET.Element, why: str) -> None:
    _warn(el, f"dropped: {why}")
    parent.remove(el)


def _warn(el: ET.Element, what: str) -> None:
    warnings.warn(f"SVG mark: <{el.tag}> {what}", stacklevel=6)
