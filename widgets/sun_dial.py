"""The sun dial of the Light dock: the sky seen from above, the sun a dot to drag. The centre
is straight overhead, the rim the horizon, the top the way the view looks; the grass relights
while the dot moves (core/sun_dial.py has the geometry)."""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF, QSize, Qt, Signal
from PySide6.QtGui import QBrush, QColor, QPainter, QPen, QPolygonF, QRadialGradient
from PySide6.QtWidgets import QSizePolicy, QWidget

from core.sun_dial import dial_point, dial_sun

TEXT_H = 18  # the line under the disk that reads the sun's elevation and azimuth


class SunDial(QWidget):
    sun_moved = Signal(float, float)  # elevation, azimuth (degrees), while dragged or stepped

    def __init__(self, elevation: float, azimuth: float, parent=None) -> None:
        super().__init__(parent)
        self.elevation, self.azimuth = elevation, azimuth
        self.heading = 0.0  # azimuth the view looks along
        self.drag: int | None = None  # which drag the moves belong to, while the button is down
        self._drags = 0
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.setMinimumSize(150, 150 + TEXT_H)
        self.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
        self.setToolTip(
            "Drag the sun. The centre is straight overhead, the rim the horizon, the top the "
            "way the view looks (a sun there lights the grass from behind).\n"
            "Arrow keys: ← → turn it 5°, ↑ ↓ raise or lower it 1°."
        )

    def sizeHint(self) -> QSize:
        return QSize(200, 180 + TEXT_H)

    def set_sun(self, elevation: float, azimuth: float) -> None:
        self.elevation, self.azimuth = elevation, azimuth
        self.update()

    def set_heading(self, heading: float) -> None:
        self.heading = heading
        self.update()

    # -- geometry --------------------------------------------------------------------------
    def _disk(self) -> tuple[QPointF, float]:
        side = min(self.width(), self.height() - TEXT_H) - 8
        return QPointF(self.width() / 2, (self.height() - TEXT_H) / 2), max(side / 2, 10.0)

    def point_of(self, elevation: float, azimuth: float) -> QPointF:
        """Where a sun of this elevation and azimuth is drawn."""
        centre, radius = self._disk()
        x, y = dial_point(elevation, azimuth, self.heading)
        return QPointF(centre.x() + x * radius, centre.y() - y * radius)

    def _move_to(self, pos: QPointF) -> None:
        centre, radius = self._disk()
        x, y = (pos.x() - centre.x()) / radius, (centre.y() - pos.y()) / radius
        self._emit(*dial_sun(x, y, self.heading))

    def _emit(self, elevation: float, azimuth: float) -> None:
        elevation = min(max(elevation, 0.0), 90.0)
        azimuth %= 360.0
        if (elevation, azimuth) != (self.elevation, self.azimuth):
            self.set_sun(elevation, azimuth)
            self.sun_moved.emit(elevation, azimuth)

    # -- input -----------------------------------------------------------------------------
    def mousePressEvent(self, event) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            self._drags += 1
            self.drag = self._drags
            self._move_to(event.position())

    def mouseMoveEvent(self, event) -> None:
        if event.buttons() & Qt.MouseButton.LeftButton:
            self._move_to(event.position())

    def mouseReleaseEvent(self, event) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            self.drag = None

    def keyPressEvent(self, event) -> None:
        steps = {
            Qt.Key.Key_Left: (0.0, 5.0),  # azimuth grows towards the view's left
            Qt.Key.Key_Right: (0.0, -5.0),
            Qt.Key.Key_Up: (1.0, 0.0),
            Qt.Key.Key_Down: (-1.0, 0.0),
        }
        step = steps.get(Qt.Key(event.key()))
        if step is None:
            super().keyPressEvent(event)
            return
        self._emit(self.elevation + step[0], self.azimuth + step[1])

    # -- drawing ---------------------------------------------------------------------------
    def paintEvent(self, _event) -> None:
        p = QPainter(self)
        p.setRenderHint(QPainter.RenderHint.Antialiasing)
        centre, radius = self._disk()
        sky = QRadialGradient(centre, radius)
        sky.setColorAt(0.0, QColor(110, 160, 225))
        sky.setColorAt(1.0, QColor(205, 225, 240))
        p.setBrush(QBrush(sky))
        p.setPen(QPen(QColor(90, 110, 130), 1.5))
        p.drawEllipse(centre, radius, radius)
        p.setBrush(Qt.BrushStyle.NoBrush)
        p.setPen(QPen(QColor(255, 255, 255, 140), 1.0, Qt.PenStyle.DashLine))
        for elevation in (30.0, 60.0):  # rings of equal height above the horizon
            r = radius * (1.0 - elevation / 90.0)
            p.drawEllipse(centre, r, r)
        # the view: a wedge at the top, the way the camera looks
        top = QPointF(centre.x(), centre.y() - radius)
        p.setBrush(QColor(60, 70, 80))
        p.setPen(Qt.PenStyle.NoPen)
        p.drawPolygon(
            QPolygonF([top + QPointF(0, 12), top + QPointF(-7, 26), top + QPointF(7, 26)])
        )
        p.setPen(QColor(60, 70, 80))
        p.drawText(
            QRectF(centre.x() - 40, top.y() + 26, 80, 16), Qt.AlignmentFlag.AlignCenter, "view"
        )
        sun = self.point_of(self.elevation, self.azimuth)
        p.setPen(QPen(QColor(150, 95, 0), 1.5))
        p.setBrush(QColor(255, 205, 40))
        p.drawEllipse(sun, 8.0, 8.0)
        if self.hasFocus():
            p.setBrush(Qt.BrushStyle.NoBrush)
            p.setPen(QPen(self.palette().highlight().color(), 1.5))
            p.drawEllipse(sun, 12.0, 12.0)
        p.setPen(self.palette().windowText().color())
        p.drawText(
            QRectF(0, self.height() - TEXT_H, self.width(), TEXT_H),
            Qt.AlignmentFlag.AlignCenter,
            f"sun {self.elevation:g}° above the horizon · azimuth {self.azimuth:g}°",
        )
        p.end()
