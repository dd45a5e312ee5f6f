"""LOD zones dock → Tune…: a frame budget or a quality to reach, the cameras to tune on, the
search's progress, and the front of frame cost against quality as a plot (pyqtgraph) whose
points show their setting in the viewport when clicked. The search itself runs in another
process (app/tune_job.py); this dialog only shows and asks."""

from __future__ import annotations

import pyqtgraph as pg
from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QButtonGroup,
    QDialog,
    QDoubleSpinBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QProgressBar,
    QPushButton,
    QRadioButton,
    QSpinBox,
    QVBoxLayout,
)

CURRENT_VIEW = "current view"


class TuneDialog(QDialog):
    start_requested = Signal()
    cancel_requested = Signal()
    apply_requested = Signal()
    point_clicked = Signal(int)  # a candidate's index in the search's results

    def __init__(self, cameras: list[str], parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Tune the LOD zones")
        self.budget_button = QRadioButton("Frame budget")
        self.quality_button = QRadioButton("Quality (FLIP at most)")
        self.budget_button.setChecked(True)
        group = QButtonGroup(self)
        group.addButton(self.budget_button)
        group.addButton(self.quality_button)
        # 0: the time today's setting takes in the search's own frames (480 × 270)
        self.budget_box = QDoubleSpinBox(minimum=0.0, maximum=600000.0, decimals=0, suffix=" ms")
        self.budget_box.setSpecialValueText("what today's setting costs")
        self.budget_box.setValue(0.0)
        self.quality_box = QDoubleSpinBox(minimum=0.001, maximum=0.9, decimals=3, singleStep=0.005)
        self.quality_box.setValue(0.05)
        self.candidates_box = QSpinBox(minimum=2, maximum=1000, value=40)
        self.cameras = QListWidget()
        for name in [*cameras, CURRENT_VIEW]:
            item = QListWidgetItem(name)
            item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
            item.setCheckState(
                Qt.CheckState.Checked if name == CURRENT_VIEW else Qt.CheckState.Unchecked
            )
            self.cameras.addItem(item)
        self.cameras.setMaximumHeight(110)
        form = QFormLayout()
        form.addRow(self.budget_button, self.budget_box)
        form.addRow(self.quality_button, self.quality_box)
        form.addRow("Settings to try", self.candidates_box)
        form.addRow("Cameras", self.cameras)
        self.progress = QProgressBar()
        self.message = QLabel("A frame of 480 × 270 at each camera, against all-geometry.")
        self.message.setWordWrap(True)
        self.plot = pg.PlotWidget(background="w")
        self.plot.setLabel("bottom", "frame cost (ms)")
        self.plot.setLabel("left", "FLIP against all-geometry")
        self.plot.setMinimumHeight(240)
        self.points = pg.ScatterPlotItem(size=9, hoverable=True)
        self.points.sigClicked.connect(self._on_clicked)
        self.front_line = pg.PlotDataItem(pen=pg.mkPen((40, 90, 200), width=2))
        self.plot.addItem(self.front_line)
        self.plot.addItem(self.points)
        legend = QLabel(
            "red: today's setting · green: the chosen one · blue: the front (no setting "
            "tried is both cheaper and better)"
        )
        legend.setWordWrap(True)
        self.start_button = QPushButton("Start")
        self.cancel_button = QPushButton("Cancel")
        self.apply_button = QPushButton("Apply")
        self.close_button = QPushButton("Close")
        self.cancel_button.setEnabled(False)
        self.apply_button.setEnabled(False)
        self.start_button.clicked.connect(self.start_requested)
        self.cancel_button.clicked.connect(self.cancel_requested)
        self.apply_button.clicked.connect(self.apply_requested)
        self.close_button.clicked.connect(self.reject)
        buttons = QHBoxLayout()
        for b in (self.start_button, self.cancel_button, self.apply_button, self.close_button):
            buttons.addWidget(b)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.progress)
        layout.addWidget(self.message)
        layout.addWidget(self.plot, 1)
        layout.addWidget(legend)
        layout.addLayout(buttons)
        self.resize(560, 640)

    # -- what the person chose -----------------------------------------------------------------
    def target(self) -> tuple[str, float | None]:
        """("budget", ms; None: what today's setting costs) or ("quality", FLIP)."""
        if self.budget_button.isChecked():
            return "budget", self.budget_box.value() or None
        return "quality", self.quality_box.value()

    def chosen_cameras(self) -> list[str]:
        return [
            self.cameras.item(i).text()
            for i in range(self.cameras.count())
            if self.cameras.item(i).checkState() == Qt.CheckState.Checked
        ]

    # -- what the search says -----------------------------------------------------------------
    def running(self, on: bool) -> None:
        self.start_button.setEnabled(not on)
        self.cancel_button.setEnabled(on)
        if on:
            self.apply_button.setEnabled(False)

    def show_progress(self, done: int, total: int, text: str) -> None:
        self.progress.setRange(0, max(total, 1))
        self.progress.setValue(done)
        self.message.setText(text)

    def show_candidates(
        self, points: list[tuple[float, float]], front: list[int], marks: dict[int, str]
    ) -> None:
        """Every candidate's (cost, FLIP); the front joined; `marks`: index -> "shipped",
        "chosen" or "shown" (drawn red, green, black)."""
        colours = {"shipped": (220, 40, 30), "chosen": (20, 160, 60), "shown": (0, 0, 0)}
        spots = []
        for i, (cost, flip) in enumerate(points):
            mark = marks.get(i)
            spots.append(
                {
                    "pos": (cost, flip),
                    "data": i,
                    "brush": pg.mkBrush(
                        colours.get(mark, (40, 90, 200) if i in front else (170, 170, 170))
                    ),
                    "size": 14 if mark else 9,
                }
            )
        self.points.setData(spots)
        line = sorted(points[i] for i in front)
        self.front_line.setData([p[0] for p in line], [p[1] for p in line])

    def _on_clicked(self, _item, spots, *_) -> None:
        if len(spots):
            self.point_clicked.emit(int(spots[0].data()))
