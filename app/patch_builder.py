"""Generating patches off the GUI thread (a QThreadPool of one): only the newest request per
grass type is delivered, so dragging a slider never queues up stale patches."""

from __future__ import annotations

from PySide6.QtCore import QObject, QRunnable, Qt, QThreadPool, Signal

from core.params import PatchParams
from core.patch import GrassPatch, generate_patch


class _Done(QObject):
    finished = Signal(int, int, object)  # grass type, request id, GrassPatch


class _Generate(QRunnable):
    def __init__(self, grass_type: int, request: int, params: PatchParams, done: _Done) -> None:
        super().__init__()
        self.grass_type, self.request, self.params, self.done = grass_type, request, params, done

    def run(self) -> None:
        self.done.finished.emit(self.grass_type, self.request, generate_patch(self.params))


class PatchBuilder(QObject):
    """Generates patches off the GUI thread; only the newest request per grass type is
    delivered."""

    ready = Signal(int, object)  # grass type, GrassPatch
    busy = Signal(bool)

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.pool = QThreadPool(self)
        self.pool.setMaxThreadCount(1)
        self._done = _Done()
        self._done.finished.connect(self._on_finished, Qt.ConnectionType.QueuedConnection)
        self._count = 0
        self._latest: dict[int, int] = {}

    def request(self, grass_type: int, params: PatchParams) -> None:
        self._count += 1
        self._latest[grass_type] = self._count
        self.busy.emit(True)
        self.pool.start(_Generate(grass_type, self._count, params, self._done))

    def _on_finished(self, grass_type: int, request: int, patch: GrassPatch) -> None:
        if request == self._latest.get(grass_type):
            self.busy.emit(False)
            self.ready.emit(grass_type, patch)

    def wait(self) -> None:
        self.pool.waitForDone()
