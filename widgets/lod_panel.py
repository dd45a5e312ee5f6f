"""The LOD zone editor: per grass type a table of levels — representation, slices per
direction, begin, end (the transition zones lie between one level's end and the next one's
begin), macro-cell maximum — with add, remove and reorder, and the instances each level drew in
the last frame. Edits are reported as whole LodConfigs; impossible ones show the reason."""

from __future__ import annotations

from dataclasses import replace

from PySide6.QtCore import QTimer, Signal
from PySide6.QtWidgets import (
    QAbstractItemView,
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from core.document import Document
from core.lod import REPRESENTATIONS, LodConfig
from core.lod_edit import append_level, move_level, remove_level, set_field, set_view_heights
from core.params import SLICE_COUNTS
from core.stats import FrameStats

COLUMNS = ("representation", "slices", "begin", "end", "macro", "instances")
HEADERS = ("Drawn as", "Slices", "Begin", "End", "Macro", "Count")
MACROS = (1, 2, 4, 8, 16, 32, 64, 128, 256, 512)
HORIZON = 100000.0
WIDTHS = (
    92,
    48,
    62,
    62,
    56,
)  # pixels: representation, slices, begin, end, macro  # the end spin box of the last level shows "horizon"


class LodPanel(QWidget):
    lod_edited = Signal(int, object)  # grass type, LodConfig
    view_height_edited = Signal(object, str)  # every grass type's LodConfig, what changed
    zones_toggled = Signal(bool)
    tune_requested = Signal()

    def __init__(self, document: Document, parent=None) -> None:
        super().__init__(parent)
        self.document = document
        self.type_box = QComboBox()
        self.type_box.currentIndexChanged.connect(self.refresh)
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(list(HEADERS))
        self.table.horizontalHeaderItem(5).setToolTip("instances (cells, macro-cells) drawn")
        self.table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.table.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        self.table.verticalHeader().setVisible(False)
        self.table.horizontalHeader().setMinimumSectionSize(36)
        buttons = QHBoxLayout()
        self.add_button = QPushButton("Add")
        self.remove_button = QPushButton("Remove")
        self.up_button = QPushButton("Up")
        self.down_button = QPushButton("Down")
        for button in (self.add_button, self.remove_button, self.up_button, self.down_button):
            buttons.addWidget(button)
        self.add_button.clicked.connect(lambda: self._edit(append_level))
        self.remove_button.clicked.connect(lambda: self._edit(remove_level, self._row()))
        self.up_button.clicked.connect(lambda: self._move(-1))
        self.down_button.clicked.connect(lambda: self._move(1))
        self.view_box = QSpinBox(minimum=0, maximum=16384, singleStep=10)
        self.view_box.setSpecialValueText("world units")
        self.view_box.setSuffix(" px tall")
        self.view_box.setKeyboardTracking(False)  # a typed number applies on Enter
        self.view_box.setToolTip(
            "Every grass type's distances hold for a view this many pixels tall (50° field of "
            "view); a taller or zoomed-in view draws every zone farther out in proportion. "
            "0: world units."
        )
        self.view_box.valueChanged.connect(self._view_height)
        view_row = QHBoxLayout()
        view_row.addWidget(QLabel("Distances for a view"))
        view_row.addWidget(self.view_box, 1)
        self.segments_box = QDoubleSpinBox(minimum=0.0, maximum=8.0, singleStep=0.125, decimals=3)
        self.segments_box.setSpecialValueText("all segments")
        self.segments_box.setSuffix(" px")
        self.segments_box.setKeyboardTracking(False)
        self.segments_box.setToolTip(
            "Blades far away are drawn with fewer segments while their curve strays from the "
            "straight pieces by at most this much on screen. 0: every blade with all its segments."
        )
        self.segments_box.valueChanged.connect(
            lambda px: self._edit(lambda c: replace(c, segment_tolerance=px))
        )
        segments_row = QHBoxLayout()
        segments_row.addWidget(QLabel("Fewer blade segments within"))
        segments_row.addWidget(self.segments_box, 1)
        self.zones_box = QCheckBox("Show zones on the terrain (Z)")
        self.zones_box.toggled.connect(self.zones_toggled)
        self.tune_button = QPushButton("Tune…")
        self.tune_button.setToolTip(
            "search the zones for a frame budget or a quality against all-geometry"
        )
        self.tune_button.clicked.connect(self.tune_requested)
        self.message = QLabel()
        self.message.setWordWrap(True)
        layout = QVBoxLayout(self)
        layout.addWidget(self.type_box)
        layout.addWidget(self.table, 1)
        layout.addLayout(buttons)
        layout.addLayout(view_row)
        layout.addLayout(segments_row)
        layout.addWidget(self.zones_box)
        layout.addWidget(self.tune_button)
        layout.addWidget(self.message)
        document.events.lod.connect(self._on_lod_changed)
        self.set_document(document)

    def set_document(self, document: Document) -> None:
        if document is not self.document:
            self.document.events.lod.disconnect(self._on_lod_changed)
            document.events.lod.connect(self._on_lod_changed)
            self.document = document
        self.type_box.blockSignals(True)
        self.type_box.clear()
        self.type_box.addItems(document.grass_names)
        self.type_box.blockSignals(False)
        self.refresh()

    def closeEvent(self, event) -> None:
        self.document.events.lod.disconnect(self._on_lod_changed)
        super().closeEvent(event)

    @property
    def grass_type(self) -> int:
        return max(self.type_box.currentIndex(), 0)

    @property
    def config(self) -> LodConfig:
        return self.document.lod(self.grass_type)

    def _row(self) -> int:
        rows = self.table.selectionModel().selectedRows()
        return rows[0].row() if rows else self.table.rowCount() - 1

    # -- model -> widgets --------------------------------------------------------------------
    def _on_lod_changed(self, index: int, _config) -> None:
        if index == self.grass_type:
            self.refresh()

    def refresh(self) -> None:
        """Show the levels. Rows are made once and then only set (with their signals held),
        so a box that reported an edit is never deleted while it reports it."""
        row = self._row() if self.table.rowCount() else 0
        levels = self.config.levels
        old = self.table.rowCount()
        self.table.setRowCount(len(levels))
        for i in range(old, len(levels)):
            self._make_row(i)
        for i, level in enumerate(levels):
            rep, slices, begin, end, macro = (self.table.cellWidget(i, c) for c in range(5))
            for w in (rep, slices, begin, end, macro):
                w.blockSignals(True)
            rep.setCurrentText(level.representation)
            slices.setCurrentText(str(level.slices))
            slices.setEnabled(level.representation == "volume")
            begin.setValue(level.begin)
            begin.setEnabled(i > 0)
            last = level.end is None
            end.setMinimum(HORIZON if last else 0.0)
            end.setSpecialValueText("horizon" if last else "")
            end.setValue(HORIZON if last else level.end)
            end.setEnabled(not last)
            macro.setCurrentText(str(level.macro))
            macro.setEnabled(level.representation != "geometry")
            for w in (rep, slices, begin, end, macro):
                w.blockSignals(False)
        for box, value in (
            (self.view_box, round(self.config.view_height or 0)),
            (self.segments_box, self.config.segment_tolerance),
        ):
            box.blockSignals(True)
            box.setValue(value)
            box.blockSignals(False)
        self.table.resizeColumnsToContents()
        self.table.selectRow(min(row, len(levels) - 1))

    def _make_row(self, i: int) -> None:
        rep = QComboBox()
        rep.addItems(REPRESENTATIONS)
        rep.currentTextChanged.connect(lambda v, i=i: self._field(i, "representation", v))
        slices = QComboBox()
        slices.addItems([str(n) for n in SLICE_COUNTS])
        slices.currentTextChanged.connect(lambda v, i=i: self._field(i, "slices", int(v)))
        begin = self._distance()
        begin.valueChanged.connect(lambda v, i=i: self._field(i, "begin", v))
        end = self._distance()
        end.valueChanged.connect(lambda v, i=i: self._field(i, "end", v))
        macro = QComboBox()
        macro.addItems([str(m) for m in MACROS])
        macro.currentTextChanged.connect(lambda v, i=i: self._field(i, "macro", int(v)))
        for column, widget in enumerate((rep, slices, begin, end, macro)):
            widget.setMaximumWidth(WIDTHS[column])  # the table fits a docked panel
            self.table.setCellWidget(i, column, widget)
        self.table.setItem(i, 5, QTableWidgetItem("–"))

    @staticmethod
    def _distance() -> QDoubleSpinBox:
        box = QDoubleSpinBox(minimum=0.0, maximum=HORIZON, decimals=2, singleStep=0.5)
        box.setButtonSymbols(QDoubleSpinBox.ButtonSymbols.NoButtons)  # wheel and keys step
        box.setKeyboardTracking(False)  # typed numbers apply on Enter, not per digit
        return box

    def show_counts(self, stats: FrameStats) -> None:
        """Instances each level drew in the last frame (levels sharing a renderer share it)."""
        for i, level in enumerate(self.config.levels):
            slices = level.slices if level.representation == "volume" else 0
            n = stats.level_count(self.grass_type, level.representation, slices)
            item = self.table.item(i, 5)
            if item is not None:
                item.setText(f"{n:,}")

    def end_box(self, level: int) -> QDoubleSpinBox:
        return self.table.cellWidget(level, 3)

    # -- widgets -> edits --------------------------------------------------------------------
    def _field(self, index: int, name: str, value) -> None:
        self._edit(set_field, index, name, value)

    def _view_height(self, pixels: int) -> None:
        """One view height for every grass type: the distances of all of them hold for it."""
        try:
            configs = set_view_heights(self.document.lods, pixels)
        except ValueError as exc:
            self.message.setText(str(exc))
            QTimer.singleShot(0, self.refresh)
            return
        self.message.clear()
        what = f"a view {pixels} px tall" if pixels else "world units"
        self.view_height_edited.emit(configs, f"LOD distances for {what}")

    def _move(self, step: int) -> None:
        row = self._row()
        self._edit(move_level, row, step)
        self.table.selectRow(min(max(row + step, 0), self.table.rowCount() - 1))

    def _edit(self, fn, *args) -> None:
        try:
            config = fn(self.config, *args)
        except ValueError as exc:
            self.message.setText(str(exc))
            QTimer.singleShot(0, self.refresh)  # show the levels as they are
            return
        self.message.clear()
        self.lod_edited.emit(self.grass_type, config)
