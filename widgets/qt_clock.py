"""Qt's side of the frame schedule (core/frame_schedule.py): its clock, and waiting for an
answer from the render processes while the window goes on handling events."""

from __future__ import annotations

from collections.abc import Callable
from time import monotonic

from PySide6.QtCore import QEventLoop, QTimer
from PySide6.QtWidgets import QWidget


def wait_until(done: Callable[[], bool], timeout_s: float) -> None:
    """Handle the window's events until `done()` or the timeout (a nested event loop)."""
    loop = QEventLoop()
    timer = QTimer(interval=20, timeout=lambda: done() and loop.quit())
    timer.start()
    QTimer.singleShot(int(timeout_s * 1000), loop.quit)
    loop.exec()
    timer.stop()


class QtClock:
    """The frame schedule's clock: monotonic time and Qt's single-shot timers."""

    def __init__(self, parent: QWidget) -> None:
        self.parent = parent

    def now(self) -> float:
        return monotonic()

    def call_later(self, seconds: float, callback: Callable[[], None]) -> QTimer:
        timer = QTimer(self.parent, singleShot=True, interval=int(seconds * 1000))
        timer.timeout.connect(callback)
        timer.timeout.connect(timer.deleteLater)
        timer.start()
        return timer

    def cancel(self, handle: QTimer) -> None:
        handle.stop()
        handle.deleteLater()
