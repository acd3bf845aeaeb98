"""Runs layouts in a background thread: one at a time, cancellable, throttled frames.

Starting a run while one is going cancels the old one first, so two runs
started in a row leave exactly one layout, the second's. Frames reach
``on_frame`` at most ``fps`` times a second (the last frame always).
"""
from __future__ import annotations

import threading
import time
from typing import Callable


class Runner:
    """Owns the worker thread of one chart."""

    def __init__(self, fps: float = 30.0):
        self.min_interval = 1.0 / fps
        self._thread: threading.Thread | None = None
        self._cancel = threading.Event()
        self._ended = threading.Event()   # set when the current run's thread has finished
        self._lock = threading.Lock()
        self._starting = threading.Lock()   # concurrent start() calls (front-end messages) queue up
        self.generation = 0
        self.error: BaseException | None = None

    @property
    def running(self) -> bool:
        return self._thread is not None and not self._ended.is_set()

    def start(self, job: Callable, on_frame: Callable, on_done: Callable, on_error: Callable) -> None:
        """Run ``job(on_frame=..., cancel=...)`` in a thread, replacing any current run.

        ``on_done(result)`` or ``on_error(exc)`` is called from the thread, only
        for the newest run.
        """
        with self._starting:
            self._start(job, on_frame, on_done, on_error)

    def _start(self, job, on_frame, on_done, on_error) -> None:
        self.stop()
        with self._lock:
            self.generation += 1
            generation = self.generation
            cancel = self._cancel = threading.Event()
            ended = self._ended = threading.Event()
            self.error = None
        last = [0.0]
        held = [None]   # the newest frame the throttle held back

        def throttled(frame, final: bool = False):
            now = time.monotonic()
            if final or now - last[0] >= self.min_interval:
                last[0], held[0] = now, None
                if generation == self.generation:
                    on_frame(frame)
            else:
                held[0] = frame

        def work():
            try:
                result = job(on_frame=throttled, cancel=cancel.is_set)
            except BaseException as exc:  # reported to the widget and kept for wait()
                if generation == self.generation:
                    self.error = exc
                    on_error(exc)
                return
            else:
                if generation == self.generation:
                    if held[0] is not None:   # the last frame always arrives: it is the layout
                        on_frame(held[0])
                    on_done(result)
            finally:
                ended.set()

        thread = threading.Thread(target=work, name="unitopia-layout", daemon=True)
        thread.start()
        self._thread = thread   # started first: a concurrent stop() may join it at once

    def stop(self) -> None:
        """Cancel the current run (it keeps its last frame) and wait for it to end."""
        thread = self._thread
        self._cancel.set()
        if thread is not None and thread is not threading.current_thread():
            # the run's own end signal: a join() cut short by a KeyboardInterrupt can leave
            # CPython's thread state saying "ended" while the thread still finishes
            self._ended.wait()
            thread.join()

    def wait(self, timeout: float | None = None) -> None:
        """Block until the current run ends; re-raise its error, if any."""
        thread = self._thread
        if thread is not None:
            thread.join(timeout)
        if self.error is not None:
            raise self.error
