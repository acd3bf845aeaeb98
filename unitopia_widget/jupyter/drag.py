"""Live drag: a mark or a point force dragged with the Select tool reflows the layout while
the pointer moves.

The front end sends ``{"type": "drag", ...}`` with the dragged marks' position, or
``{"type": "force", ...}`` with a dragged point force's, at most every 100 ms, and a last
message on the drop (``{"type": "pin", ...}``; a "force" one with ``final``; docs/protocol.md).
Each message pins the marks there (or moves the force) and starts a warm run, which a pin
change answers with the local reflow (``layout/reflow.py``) and a moved force with the full
warm run on the last run's problem (``reflow.resumed``: no problem built), streaming
its frames. One worker thread takes the messages in turn and keeps only the newest waiting
one: a message arriving while a run goes ends that run once it has taken ``DRAG_STEPS``
steps (it keeps its frame so far, the next run starts from it), so the latest position wins
and no queue builds up: a moved force, which changes what every mark feels, gets a few
warm steps per message. The drop's run is not cut short by anything but a new drag: it
ends with the usual final layout (status "done", the static image refreshed); the drag's
runs skip that image. The worker's runs keep the kernel's CPU priority (``Runner``: a
layout run otherwise yields to every other process): the user waits on each.
"""
from __future__ import annotations

import math
import threading

from ..design.forces import PointForce

DRAG_STEPS = 4   # steps a drag's run takes before a newer position may end it


class LiveDrag:
    """``UnitoPia``'s live drag; needs ``_chart``, ``_pin_units``, ``run`` and ``_on_error``;
    its runs go through ``_supersedable``."""

    _dragging = False   # a drag's run (not the drop's) is going: ``_on_done`` skips the static image

    @property
    def _answering(self) -> bool:
        """Whether the caller is the drag worker: its runs (a drag's or the drop's) are not niced."""
        return threading.current_thread() is self._drag_worker

    def _drag(self, index, x, y, final: bool) -> None:
        """Pin units ``index`` at ``x, y`` px and reflow; ``final``: the drop."""
        self._live(lambda: self._pin_units(index, x, y), final)

    def _drag_force(self, layer, index, x, y, final: bool) -> None:
        """Move point force ``index`` of layer ``layer`` (an index) to ``x, y`` px and lay out
        warm; ``final``: the drop."""
        self._live(lambda: self._move_force(layer, index, x, y), final)

    def _move_force(self, layer, index, x, y) -> None:
        layers = self._chart.layers
        if not (isinstance(layer, int) and 0 <= layer < len(layers)):
            raise ValueError(f"force message: layer must be a layer index under {len(layers)}, "
                             f"got {layer!r:.40}")
        forces = list(layers[layer].forces)
        if not (isinstance(index, int) and 0 <= index < len(forces)
                and isinstance(forces[index], PointForce)):
            raise ValueError(f"force message: index must be the index of a point force of layer "
                             f"{layers[layer].name!r:.60} (its forces: {forces!r:.80}), got {index!r:.40}")
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in (x, y)):
            raise ValueError(f"force message: x and y must be finite numbers (canvas px), got "
                             f"{x!r:.40}, {y!r:.40}")
        forces[index] = PointForce(float(x), float(y), forces[index].strength)
        layers[layer].set(forces=forces)

    def _live(self, apply, final: bool) -> None:
        """Run ``apply()`` (a change to the chart) and lay out warm; ``final``: the drop.
        Supersedes the waiting message and cancels the running run of an earlier one."""
        with self._drag_lock:
            self._drag_next = (apply, final)
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
            apply, final = job
            try:
                self._dragging = not final
                apply()
                self._chart.start_from_last()   # the superseded reflow's marks, as shown
                self.run(wait=True)
            except Exception as exc:   # a drop outside the container: reported, the drag goes on
                self._on_error(exc)
            finally:
                self._dragging = False

    def _init_drag(self) -> None:
        self._drag_lock = threading.Lock()
        self._drag_next = None     # (apply, final) waiting for the worker
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
