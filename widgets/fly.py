"""Fly mode of the viewport: W A S D move, Q E sink and rise, at a speed in world units a
second that follows the scene's size (its longer side crossed in CROSSING_S) and that the wheel
makes faster or slower while flying."""

from __future__ import annotations

from typing import ClassVar

from PySide6.QtCore import QObject, Qt, QTimer, Signal

CROSSING_S = 30.0  # seconds to fly across the terrain's longer side at the starting speed
STEP_MS = 30
WHEEL_FACTOR = 1.25  # speed × this per notch of the wheel


class Fly(QObject):
    changed = Signal()  # switched on or off, or a new speed
    KEYS: ClassVar[frozenset] = frozenset(
        {Qt.Key.Key_W, Qt.Key.Key_A, Qt.Key.Key_S, Qt.Key.Key_D, Qt.Key.Key_Q, Qt.Key.Key_E}
    )

    def __init__(self, viewport) -> None:
        super().__init__(viewport)
        self.viewport = viewport
        self.on = False
        self.speed = 1.0  # world units a second
        self._held: set[int] = set()
        self._timer = QTimer(self, interval=STEP_MS)
        self._timer.timeout.connect(self._step)

    def set_scene(self, extent: float) -> None:
        """The terrain's longer side in world units: the starting speed crosses it in
        CROSSING_S."""
        self.speed = max(extent, 1.0) / CROSSING_S
        self.changed.emit()

    def toggle(self) -> None:
        self.on = not self.on
        self._held.clear()
        self._timer.stop()
        self.changed.emit()

    def press(self, key: int, repeat: bool) -> bool:
        """A key went down: whether fly mode took it."""
        if not (self.on and key in self.KEYS):
            return False
        if not repeat:
            self._held.add(key)
        if not self._timer.isActive():
            self._timer.start()
        return True

    def release(self, key: int, repeat: bool) -> None:
        if not repeat:
            self._held.discard(key)
        if not self._held and self._timer.isActive():
            self._timer.stop()

    def wheel(self, notches: float) -> None:
        self.speed *= WHEEL_FACTOR**notches
        self.changed.emit()

    def _step(self) -> None:
        k, held = Qt.Key, self._held
        forward = (k.Key_W in held) - (k.Key_S in held)
        strafe = (k.Key_D in held) - (k.Key_A in held)
        rise = (k.Key_E in held) - (k.Key_Q in held)
        if forward or strafe or rise:
            move = self.speed * STEP_MS / 1000.0
            self.viewport.camera.fly(forward * move, strafe * move, rise * move)
            self.viewport.camera_changed.emit()
            self.viewport.request_frame()
