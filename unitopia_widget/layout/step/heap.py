"""The host heap during a layout: freed scratch memory is kept for the next iteration.

Every iteration of a solve makes and frees tensors of several MiB (the coverage slabs,
their shadows, the samples). glibc's ``malloc`` serves blocks that large from fresh pages
(``mmap``), or trims the top of its heap once more than its trim threshold lies free
there, so the next iteration asks the system for the same memory again and the kernel
zeroes every page anew: on a stack of five layers (586 marks, five 637k px slabs) 0.8 to
2 million page faults and a quarter of the layout's time.

``held()`` wraps a layout. While one runs, glibc serves blocks up to ``MMAP_THRESHOLD``
from its heap and keeps up to ``TRIM_HELD`` of freed memory there; when the last layout
ends, the trim threshold goes to ``TRIM_AFTER`` and ``malloc_trim`` hands the freed memory
back to the system, so an idle kernel holds no more than before. Setting a threshold
ends glibc's own adjustment of it; the values after a layout are those that adjustment
reaches once it has seen a large block freed. Elsewhere than glibc ``held()`` does nothing.
"""
from __future__ import annotations

import contextlib
import ctypes
import threading

M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3   # glibc's mallopt parameters
MMAP_THRESHOLD = 32 << 20   # bytes: the largest glibc accepts (half its 64 MiB thread heap)
TRIM_HELD = 1 << 30         # bytes of freed heap kept while a layout runs
TRIM_AFTER = 64 << 20       # bytes: glibc's own trim threshold beside a 32 MiB mmap threshold


def _glibc():
    """The process's glibc through ctypes, or None (another C library, or no ``dlopen``)."""
    try:
        libc = ctypes.CDLL(None)
        libc.gnu_get_libc_version   # noqa: B018  (glibc alone has it)
        return libc
    except (OSError, TypeError, AttributeError):
        return None


_LIBC = _glibc()
_lock = threading.Lock()
_running = 0   # layouts inside held() now, in any thread


@contextlib.contextmanager
def held():
    """Keep freed heap memory for reuse while the body runs (a layout); see the module."""
    global _running
    if _LIBC is None:
        yield
        return
    with _lock:
        if _running == 0:
            _LIBC.mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)
            _LIBC.mallopt(M_TRIM_THRESHOLD, TRIM_HELD)
        _running += 1
    try:
        yield
    finally:
        with _lock:
            _running -= 1
            if _running == 0:
                _LIBC.mallopt(M_TRIM_THRESHOLD, TRIM_AFTER)
                _LIBC.malloc_trim(0)
