"""resvg in a worker process, where a time limit and Ctrl-C can stop it.

resvg holds the calling thread until it is done, and a ``KeyboardInterrupt`` cannot fire
inside it: a mark whose filters cost minutes held the kernel for minutes. Here one
long-lived child process per Python process renders (it imports resvg alone, so it starts
in about 0.1 s); the parent waits in short slices, so Ctrl-C stops the wait at once, and a
render past ``RENDER_SECONDS`` or an interrupt kills the child, which starts again on the
next render. Platforms without ``select`` on pipes (Windows) render in-process.
"""
from __future__ import annotations

import atexit
import os
import pickle
import select
import struct
import subprocess
import sys
import threading
import time

RENDER_SECONDS = 8.0   # one render at most; a mark needing longer is refused
_SLICE = 0.1           # s: how often the wait checks the clock (Ctrl-C stops it at once)
_HEAD = struct.Struct("<Q")
_SERVE = r"""
import pickle, signal, struct, sys
signal.signal(signal.SIGINT, signal.SIG_IGN)   # the parent decides; it kills this process
import resvg_py
head, inp, out = struct.Struct("<Q"), sys.stdin.buffer, sys.stdout.buffer
while True:
    size = inp.read(8)
    if len(size) < 8:
        break
    kwargs = pickle.loads(inp.read(head.unpack(size)[0]))
    try:
        reply = (True, bytes(resvg_py.svg_to_bytes(**kwargs)))
    except BaseException as exc:   # resvg panics surface as BaseException
        reply = (False, f"{type(exc).__name__}: {exc}")
    data = pickle.dumps(reply)
    out.write(head.pack(len(data)) + data)
    out.flush()
"""


class RenderTimeout(Exception):
    """resvg ran past its time limit and was stopped."""


class _Worker:
    """The child process and the lock that gives it one render at a time."""

    def __init__(self):
        self.lock = threading.Lock()
        self.proc = None
        self.owner = None   # the pid that started it: a forked child starts its own

    def render(self, seconds: float, kwargs: dict) -> bytes:
        with self.lock:
            if self.proc is None or self.proc.poll() is not None or self.owner != os.getpid():
                self.proc = subprocess.Popen([sys.executable, "-c", _SERVE], stdin=subprocess.PIPE,
                                             stdout=subprocess.PIPE, start_new_session=True)
                self.owner = os.getpid()
            try:
                data = pickle.dumps(kwargs)
                self.proc.stdin.write(_HEAD.pack(len(data)) + data)
                self.proc.stdin.flush()
                deadline = time.monotonic() + seconds
                size = _HEAD.unpack(self._read(_HEAD.size, deadline))[0]
                ok, value = pickle.loads(self._read(size, deadline))
            except BaseException:   # a timeout, Ctrl-C, a dead child: never leave it running
                self.stop()
                raise
        if not ok:
            raise ValueError(value)
        return value

    def _read(self, size: int, deadline: float) -> bytes:
        fd, parts, got = self.proc.stdout.fileno(), [], 0
        while got < size:
            left = deadline - time.monotonic()
            if left <= 0:
                raise RenderTimeout()
            ready, _, _ = select.select([fd], [], [], min(_SLICE, left))
            if ready:
                chunk = os.read(fd, min(size - got, 1 << 20))
                if not chunk:
                    raise ValueError("the SVG renderer stopped unexpectedly")
                parts.append(chunk)
                got += len(chunk)
        return b"".join(parts)

    def stop(self) -> None:
        """Kill the child (a render in flight, an interrupt, the interpreter's exit)."""
        if self.proc is not None and self.owner == os.getpid():   # not a parent's child
            self.proc.kill()
            self.proc.wait()
            self.proc.stdin.close()
            self.proc.stdout.close()
            self.proc = None


_WORKER = _Worker()
atexit.register(_WORKER.stop)


def svg_to_png(seconds: float, **kwargs) -> bytes:
    """PNG bytes of ``resvg_py.svg_to_bytes(**kwargs)``, rendered within ``seconds``
    (RenderTimeout past them); ValueError when resvg fails."""
    if os.name == "nt":
        import resvg_py
        return bytes(resvg_py.svg_to_bytes(**kwargs))
    return _WORKER.render(seconds, kwargs)
