"""The 2D map view: the design map chosen in the paint panel as an image (pyqtgraph), painted
with the same brush as the viewport — left drag paints, a click paints one dab (or picks with
the eyedropper), the wheel zooms, right or middle drag moves the view. A circle shows the
brush. The colour map shows its tint over grey by its weight (grey: the blades keep their own
colour). The image follows every edit of its map, at most every 40 ms."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QTimer, Signal
from PySide6.QtWidgets import QGraphicsEllipseItem, QVBoxLayout, QWidget

from core.design_maps import DesignMaps

LEVELS = {"ambient": (0.0, 2.0), "diffuse": (0.0, 2.0)}


class _PaintableImage(pg.ImageItem):
    """An image whose left drags and clicks are brush strokes in texel coordinates."""

    def __init__(self, view: MapView) -> None:
        super().__init__(axisOrder="row-major")
        self.view = view
        self.setAcceptHoverEvents(True)

    def mouseDragEvent(self, ev) -> None:
        if ev.button() != pg.QtCore.Qt.MouseButton.LeftButton:
            ev.ignore()
            return
        ev.accept()
        pos = ev.pos()
        if ev.isStart():
            start = ev.buttonDownPos()
            self.view.paint_pressed.emit(start.x(), start.y(), ev.modifiers())
        self.view.paint_moved.emit(pos.x(), pos.y())
        if ev.isFinish():
            self.view.paint_released.emit()
        self.view.show_brush(pos.x(), pos.y())

    def mouseClickEvent(self, ev) -> None:
        if ev.button() != pg.QtCore.Qt.MouseButton.LeftButton:
            ev.ignore()
            return
        ev.accept()
        pos = ev.pos()
        self.view.paint_pressed.emit(pos.x(), pos.y(), ev.modifiers())
        self.view.paint_released.emit()

    def hoverEvent(self, ev) -> None:
        if not ev.isExit():
            self.view.show_brush(ev.pos().x(), ev.pos().y())


class MapView(QWidget):
    paint_pressed = Signal(float, float, object)  # texel column, row, keyboard modifiers
    paint_moved = Signal(float, float)
    paint_released = Signal()

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.plot = pg.GraphicsLayoutWidget()
        self.box = self.plot.addViewBox(lockAspect=True, invertY=True)
        self.image = _PaintableImage(self)
        self.box.addItem(self.image)
        # where the paint rule does not hold, shaded over the map (core/paint_rule.py)
        self.mask = pg.ImageItem()
        self.mask.setZValue(1)
        self.box.addItem(self.mask)
        self.brush = QGraphicsEllipseItem()
        self.brush.setPen(pg.mkPen((255, 255, 255), width=0))
        self.box.addItem(self.brush)
        self.brush_size = 24.0
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.plot)
        self.maps: DesignMaps | None = None
        self.layer, self.channel = "density", 0
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(40)
        self._timer.timeout.connect(self.refresh)

    def set_maps(self, maps: DesignMaps) -> None:
        if self.maps is not None:
            self.maps.changed.disconnect(self._on_changed)
        self.maps = maps
        maps.changed.connect(self._on_changed)
        self.refresh()
        self.box.autoRange(padding=0.02)

    def show_layer(self, layer: str, channel: int | None) -> None:
        if (layer, channel) != (self.layer, self.channel):
            self.layer, self.channel = layer, channel
            self.refresh()

    def show_brush(self, x: float, y: float) -> None:
        r = self.brush_size / 2.0
        self.brush.setRect(x - r, y - r, 2 * r, 2 * r)

    def _on_changed(self, name: str, _rect) -> None:
        if name == self.layer and not self._timer.isActive():
            self._timer.start()

    def refresh(self) -> None:
        if self.maps is None:
            return
        values = np.asarray(self.maps.layer(self.layer))
        if self.channel is not None:
            values = values[..., max(self.channel, 0)]
        elif values.shape[2] == 1:
            values = values[..., 0]
        elif self.layer == "color":  # the tint over grey by its weight: grey = no tint
            weight = values[..., 3:4]
            values = values[..., :3] * weight + 0.5 * (1.0 - weight)
        elif self.layer == "trample":  # a flow map: red, green the lean's x, z; grey upright
            values = np.concatenate([values, np.full_like(values[..., :1], 0.5)], axis=2)
        self.image.setImage(values, levels=LEVELS.get(self.layer, (0.0, 1.0)), autoLevels=False)

    def show_mask(self, mask: np.ndarray | None) -> None:
        """Shade where the paint rule's weights (rows, columns, 0 … 1) fall short; None: no
        rule, nothing shaded. Laid out as the map's values are."""
        if mask is None:
            self.mask.clear()
            self.mask.setVisible(False)
            return
        shade = np.zeros((*mask.shape, 4), np.uint8)
        shade[..., 2] = 90  # a dark blue veil: the map shows through it
        shade[..., 3] = np.round((1.0 - np.clip(mask, 0.0, 1.0)) * 170).astype(np.uint8)
        self.mask.setImage(shade, levels=(0, 255), autoLevels=False)
        self.mask.setVisible(True)

    def displayed(self) -> np.ndarray:
        """What the image shows (for tests)."""
        return np.asarray(self.image.image)
