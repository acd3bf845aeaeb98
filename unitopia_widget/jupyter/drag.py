"""Live drag: a mark dragged with the Select tool reflows the layout while the pointer moves.

The front end sends ``{"type": "drag", ...}`` with the dragged marks' position at most every
100 ms and ``{"type": "pin", ...}`` on the drop (docs/protocol.md). Each message pins the
marks there and starts a warm run, which a pin change answers with the local reflow
(``layout/reflow.py``), streaming its frames. One worker thread takes the messages in turn
and keeps only the newest waiting one: a message arriving while a run goes ends that run once
it has taken ``DRAG_STEPS`` steps (it keeps its frame so far, the next run starts from it), so
the latest position wins and no queue builds up. The drop's run is not cut short by anything
but a new drag: it ends with the usual final layout (status "done", the static image
refreshed); the drag's runs skip that image.
"""
from __future__ import annotations

import threading

DRAG_STEPS = 4   # steps a drag's run takes before a newer position may end it


class LiveDrag:
    """``UnitoPia``'s live drag; needs ``_pin_units``, ``run`` and ``_on_error``; its runs go
    through ``_supersedable``."""

    _dragging = False   # a drag's run (not the drop's) is going: ``_on_done`` skips the static image

    def _drag(self, index, x, y, final: bool) -> None:
        """Pin units ``index`` at ``x, y`` px and reflow; ``final``: the drop. Supersedes the
        waiting message and cancels the running run of an earlier one."""
        with self._drag_lock:
            self._drag_next = (index, x, y, final)
            if self._drag_worker is not None:   # its run ends soon (``_supersedable``)
                return
            self._drag_worker = threading.Thread(target=self._drag_loop, name="unitopia-drag",
                                                 daemon=True)
            self._drag_worker.start()

    def _drag_loop(self) -> None:
        while True:
            with self._drag_lock:
                job, self._drag_next = self._drag_next, None
                if job is None:
                    self._drag_worker = None
                    return
            index, x, y, final = job
            try:
                self._dragging = not final
                self._pin_units(index, x, y)
                self._chart.start_from_last()   # the superseded reflow's marks, as shown
                self.run(wait=True)
            except Exception as exc:   # a drop outside the container: reported, the drag goes on
                self._on_error(exc)
            finally:
                self._dragging = False

    def _init_drag(self) -> None:
        self._drag_lock = threading.Lock()
        self._drag_next = None     # (units, x, y, final) waiting for the worker
        self._drag_worker = None   # the worker thread, None when idle

    def _supersedable(self, on_frame, cancel):
        """``(on_frame, cancel)`` for a run: it also ends when a newer drag or drop waits, once
        it has taken ``DRAG_STEPS`` steps (offered as many frames): its setup is not wasted,
        and each position the pointer passes moves the marks around it."""
        steps = [0]

        def counted(*frame):
            steps[0] += 1
            on_frame(*frame)
        return counted, lambda: cancel() or (steps[0] >= DRAG_STEPS and self._drag_next is not None)
