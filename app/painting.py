"""The paint controller: turns presses and drags on the ground (viewport) or on the 2D map view
into brush strokes on the design maps, one undo step per stroke; the eyedropper; a terrain
rebuild after the height map changed (bounding volumes and ground ranges follow it)."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QObject, Qt, QTimer, Signal

from app.commands import PaintStroke
from core.brush import Stroke
from core.design_maps import DesignMaps


class PaintController(QObject):
    heights_changed = Signal()  # after the height map settled (debounced)

    def __init__(self, window) -> None:
        super().__init__(window)
        self.window = window
        self.stroke: Stroke | None = None
        self.eyedropper = False
        self.maps: DesignMaps | None = None
        self._heights = QTimer(self)
        self._heights.setSingleShot(True)
        self._heights.setInterval(250)
        self._heights.timeout.connect(self._heights_settled)

    @property
    def panel(self):
        return self.window.paint_panel

    def set_maps(self, maps: DesignMaps) -> None:
        if self.maps is not None:
            self.maps.changed.disconnect(self._on_map_changed)
        self.maps = maps
        maps.changed.connect(self._on_map_changed)

    # -- strokes -----------------------------------------------------------------------------
    def press(self, x: float, y: float, modifiers=Qt.KeyboardModifier.NoModifier) -> None:
        """Start a stroke at map texel (x, y); Ctrl erases, Shift smooths."""
        if self.maps is None:
            return
        if self.eyedropper:
            self.pick(x, y)
            return
        mode = None
        if modifiers & Qt.KeyboardModifier.ControlModifier:
            mode = "erase"
        elif modifiers & Qt.KeyboardModifier.ShiftModifier:
            mode = "smooth"
        layer, channel = self.panel.target
        try:
            self.stroke = Stroke(self.maps, layer, self.panel.brush(mode), channel)
        except ValueError as exc:
            self.panel.message.setText(str(exc))
            return
        self.panel.message.clear()
        self.stroke.add(x, y)

    def move(self, x: float, y: float) -> None:
        if self.stroke is not None:
            self.stroke.add(x, y)

    def release(self) -> None:
        stroke, self.stroke = self.stroke, None
        if stroke is None or not stroke.saved:
            return
        stroke.finish()
        label = self.panel.layer_box.currentText()
        self.window.push(PaintStroke(stroke, f"{stroke.brush.mode} {label}"))
        if stroke.layer == "height":
            self._heights.start()

    # -- eyedropper --------------------------------------------------------------------------
    def start_eyedropper(self) -> None:
        self.eyedropper = True
        self.panel.message.setText("click the map to take its value")

    def cancel_eyedropper(self) -> None:
        self.eyedropper = False
        self.panel.message.clear()

    def pick(self, x: float, y: float) -> None:
        self.eyedropper = False
        self.panel.message.clear()
        layer, channel = self.panel.target
        w, h = self.maps.size
        col, row = int(np.clip(x, 0, w - 1)), int(np.clip(y, 0, h - 1))
        values = self.maps.layer(layer)[row, col]
        if channel is not None:
            values = values[[max(channel, 0)]]  # all grass types: show the first one's
        self.panel.set_value(tuple(float(v) for v in values))

    # -- the height map moves the terrain ----------------------------------------------------
    def _on_map_changed(self, name: str, rect) -> None:
        if name == "height" and self.stroke is None:  # undo, redo, import; strokes: release
            self._heights.start()

    def _heights_settled(self) -> None:
        self.heights_changed.emit()
