"""Runs layouts in a background thread: one at a time, cancellable, throttled frames.

Starting a run while one is going cancels the old one first, so two runs
started in a row leave exactly one layout, the second's. Frames reach
``on_frame`` at most ``fps`` times a second (the last frame always).

``stop()`` reaches the current run and every run requested before it (a ``ticket``
from ``request()`` that has not started yet never starts). A run that does not end
within ``stop``'s patience (a long step of its setup) is let go: its callbacks are not
called, and the next run waits for its thread before starting.

The layout thread runs at a lower CPU priority (``nice``, Linux): where the browser
drawing the frames shares the kernel's cores, the browser comes first and the layout
takes the rest, so the animation is not starved by the run it shows. A run that answers
the pointer (``start(..., nice=0)``: a live drag's) keeps the caller's priority instead:
its runs are short, and at a lower priority any other busy process on the machine (a
build, a second kernel) would starve the reflow the user is waiting for.
"""
from __future__ import annotations

import os
import sys
import threading
import time
from typing import Callable

BACKGROUND_NICE = 10   # added to the layout thread's nice value: nice(1)'s default step


def lower_priority(step: int) -> None:
    """Raise the calling thread's nice value by ``step`` (threads it starts later, such as
    torch's OpenMP workers, inherit it). Linux only, where a thread id names one thread;
    elsewhere, or when refused, the thread keeps its priority."""
    if step <= 0 or not sys.platform.startswith("linux"):
        return
    tid = threading.get_native_id()
    try:
        os.setpriority(os.PRIO_PROCESS, tid, min(19, os.getpriority(os.PRIO_PROCESS, tid) + step))
    except OSError:
        pass


class Runner:
    """Owns the worker thread of one chart."""

    def __init__(self, fps: float = 30.0, nice: int = BACKGROUND_NICE):
        self.min_interval = 1.0 / fps
        self.nice = nice
        self._thread: threading.Thread | None = None
        self._cancel = threading.Event()
        self._ended = threading.Event()   # set when the current run's thread has finished
        self._lock = threading.Lock()
        self._starting = threading.Lock()   # concurrent start() calls (front-end messages) queue up
        self.generation = 0
        self.error: BaseException | None = None
        self._requests = 0       # tickets handed out
        self._stopped_upto = 0   # tickets up to this one were stopped
        self._let_go: list[threading.Thread] = []   # runs stop() stopped waiting for

    @property
    def running(self) -> bool:
        return self._thread is not None and not self._ended.is_set()

    def request(self) -> int:
        """A ticket for a run about to start; a ``stop()`` after it cancels that run."""
        with self._lock:
            self._requests += 1
            return self._requests

    def start(self, job: Callable, on_frame: Callable, on_done: Callable, on_error: Callable,
              ticket: int | None = None, nice: int | None = None) -> bool:
        """Run ``job(on_frame=..., cancel=...)`` in a thread, replacing any current run.

        ``on_done(result)`` or ``on_error(exc)`` is called from the thread, only
        for the newest run. Returns False (and runs nothing) when a ``stop()`` came after
        ``ticket`` was handed out. ``nice``: this run's step of the thread's nice value
        (None: the runner's).
        """
        ticket = self.request() if ticket is None else ticket
        with self._starting:
            return self._start(job, on_frame, on_done, on_error, ticket,
                               self.nice if nice is None else nice)

    def _start(self, job, on_frame, on_done, on_error, ticket, nice) -> bool:
        self.end_current()
        with self._lock:
            if ticket <= self._stopped_upto:
                return False
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
            lower_priority(nice)
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
        return True

    def stop(self, patience: float | None = None) -> bool:
        """Cancel the current run (it keeps its last frame) and every requested one, and
        wait up to ``patience`` s (None: until it ends). Returns False when the run was
        let go instead: it had not ended, and none of its callbacks will be called."""
        with self._lock:
            self._stopped_upto = self._requests
        return self.end_current(patience)

    def end_current(self, patience: float | None = None) -> bool:
        """Cancel the current run only (``stop`` without reaching requested ones); with
        ``patience=None`` also wait for the runs let go before."""
        with self._lock:
            thread, ended = self._thread, self._ended
            self._cancel.set()
        if patience is None:
            for old in self._let_go:
                old.join()
            self._let_go = []
        if thread is None or thread is threading.current_thread():
            return True
        # the run's own end signal: a join() cut short by a KeyboardInterrupt can leave
        # CPython's thread state saying "ended" while the thread still finishes
        if not ended.wait(patience):
            with self._lock:
                if self._thread is thread:
                    self.generation += 1   # its callbacks no longer match: it is let go
                    self._thread = None
                    self._let_go.append(thread)
            return False
        thread.join()
        return True

    def wait(self, timeout: float | None = None) -> None:
        """Block until the current run ends; re-raise its error, if any."""
        thread = self._thread
        if thread is not None:
            thread.join(timeout)
        if self.error is not None:
            raise self.error
