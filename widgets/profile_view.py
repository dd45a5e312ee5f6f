"""Live profiling (thesis ch. 7): a timing overlay on the viewport with the thesis's table
(fps, t_a, t_q, t_g, t_v, t_i, t_m, c_g, c_v, c_i) as average / min / max over the last 60
frames, and a dock with a live plot of the frame time split by technique, a "redraw
continuously" switch and a record button whose frames are saved as CSV or JSON (the formats
`sward profile --out` writes)."""

from __future__ import annotations

from collections import deque
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QFont
from PySide6.QtWidgets import (
    QCheckBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSizePolicy,
    QVBoxLayout,
    QWidget,
)

from core.profile import WINDOW, frames_csv, frames_json, overlay_text
from core.stats import FrameStats

# (stats field, label, colour): the technique colours of the thesis's figures
PARTS = (
    ("t_g_ms", "geometry", (230, 60, 50)),
    ("t_v_ms", "volume", (240, 200, 30)),
    ("t_i_ms", "image", (70, 120, 255)),
    ("t_q_ms", "LOD selection", (170, 170, 170)),
    ("t_m_ms", "ground, props", (120, 200, 120)),
    ("t_s_ms", "blade shadows", (90, 70, 60)),
)
PLOT_FRAMES = 300


class ProfileOverlay(QLabel):
    """The timing table drawn over the top-left corner of the viewport."""

    def __init__(self, parent: QWidget) -> None:
        super().__init__(parent)
        font = QFont("monospace")
        font.setStyleHint(QFont.StyleHint.Monospace)
        font.setPointSize(8)
        self.setFont(font)
        self.setStyleSheet(
            "color: white; background: rgba(0, 0, 0, 150); padding: 4px; border-radius: 3px"
        )
        self.setAttribute(Qt.WidgetAttribute.WA_TransparentForMouseEvents)
        self.frames: deque[FrameStats] = deque(maxlen=WINDOW)
        self.move(6, 6)
        self.hide()

    def add(self, stats: FrameStats) -> None:
        self.frames.append(stats)
        if self.isVisible():
            self._show_text()

    def setVisible(self, visible: bool) -> None:
        super().setVisible(visible)
        if visible:
            self._show_text()

    def _show_text(self) -> None:
        self.setText(overlay_text(list(self.frames)))
        self.adjustSize()


class ProfilePanel(QWidget):
    continuous_toggled = Signal(bool)
    recorded = Signal(list)  # the frames of a finished recording

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.plot = pg.PlotWidget(background="w")
        self.plot.setLabel("left", "ms")
        self.plot.setLabel("bottom", "frame")
        # top right, where the frames reach last; two columns: all five fit the dock's height
        self.plot.addLegend(offset=(-5, 5), colCount=2)
        self.curves = {
            name: self.plot.plot([], [], pen=pg.mkPen(colour, width=2), name=label)
            for name, label, colour in PARTS
        }
        self.total = self.plot.plot([], [], pen=pg.mkPen((0, 0, 0), width=1), name="frame t_a")
        self.history: deque[FrameStats] = deque(maxlen=PLOT_FRAMES)
        self.recording: list[FrameStats] | None = None
        self.continuous_box = QCheckBox("Redraw continuously")
        self.continuous_box.setToolTip("draw frames one after another to watch the timings")
        self.continuous_box.toggled.connect(self.continuous_toggled)
        self.record_button = QPushButton("Record")
        self.record_button.setCheckable(True)
        self.record_button.toggled.connect(self._on_record)
        self.label = QLabel()
        # "recording: 12345 frames" must not widen the dock: the label takes the room left
        self.label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        row = QHBoxLayout()
        row.addWidget(self.continuous_box)
        row.addWidget(self.record_button)
        row.addWidget(self.label, 1)
        layout = QVBoxLayout(self)
        layout.addWidget(self.plot, 1)
        layout.addLayout(row)
        self._count = 0
        # the frame axis spans the frames the plot holds (_draw), not pyqtgraph's -0.5 … 0.5
        # around the first frame, which shows as a bare axis labelled "× 0.001"
        self.plot.getViewBox().enableAutoRange(x=False)
        self.plot.setXRange(0, PLOT_FRAMES, padding=0)

    def add(self, stats: FrameStats) -> None:
        self.history.append(stats)
        self._count += 1
        if self.recording is not None:
            self.recording.append(stats)
            self.label.setText(f"recording: {len(self.recording)} frames")
        if self.isVisible():
            self._draw()

    def showEvent(self, event) -> None:
        # frames that came while the dock was hidden or behind another tab
        super().showEvent(event)
        self._draw()

    def _draw(self) -> None:
        if not self.history:
            return
        x = np.arange(self._count - len(self.history), self._count)
        for name, curve in self.curves.items():
            curve.setData(x, [getattr(s, name) for s in self.history])
        self.total.setData(x, [s.t_a_ms for s in self.history])
        first = max(self._count - PLOT_FRAMES, 0)
        self.plot.setXRange(first, first + PLOT_FRAMES, padding=0)

    def _on_record(self, on: bool) -> None:
        self.record_button.setText("Stop and save…" if on else "Record")
        if on:
            self.recording = []
            self.label.setText("recording: 0 frames")
        else:
            frames, self.recording = self.recording or [], None
            self.label.setText(f"recorded {len(frames)} frames")
            self.recorded.emit(frames)

    def save(self, path: Path, frames: list[FrameStats], **about) -> str:
        """Write recorded frames: .csv a row per frame, otherwise JSON. Returns a message."""
        path = Path(path)
        text = frames_csv(frames) if path.suffix.lower() == ".csv" else frames_json(frames, **about)
        path.write_text(text)
        return f"wrote {len(frames)} frame{'' if len(frames) == 1 else 's'} to {path}"
