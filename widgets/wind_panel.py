"""The wind panel (issue: wind): on/off, the direction on a dial, a preset (core/wind.py
PRESETS), and the gusts' and the turbulence's strength and size — a dial above a pyqtgraph
ParameterTree that shows a Wind and reports edits as a new one. While the wind is on, the
viewport animates (widgets/viewport.py)."""

from __future__ import annotations

import dataclasses

from pyqtgraph.parametertree import Parameter, ParameterTree
from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDial,
    QHBoxLayout,
    QLabel,
    QVBoxLayout,
    QWidget,
)

from core.wind import PRESETS, RANGES, Wind, preset_of
from widgets.unit_number import fit_names, report_bad_text

# (field, title, step, suffix); the limits are core/wind.py's
NUMBERS = (
    ("speed", "Gust speed", 0.25, " units/s"),
    ("gust_strength", "Gust strength", 0.05, " × length"),
    ("gust_scale", "Gust size", 0.5, " units"),
    ("turbulence_strength", "Turbulence strength", 0.01, " × length"),
    ("turbulence_scale", "Turbulence size", 0.1, " units"),
    ("blade_reach", "Blades reach while blowing", 0.05, " ×"),
)
CUSTOM = "(custom)"  # the preset box's entry for values of no preset
TIPS = {
    "blade_reach": "while the wind blows, the volume begins this many times as far out as the "
    "LOD zones say, and the blades run on 5 % past it (1: the zones as in still air)",
}


class WindPanel(QWidget):
    wind_edited = Signal(object)  # Wind

    def __init__(self, wind: Wind, parent=None) -> None:
        super().__init__(parent)
        self.enabled_box = QCheckBox("Wind blows (animates the view)")
        # the dial points where the wind blows, seen from above with -z up (the Map dock's
        # way): QDial counts clockwise from its bottom, so +z (down) is 0, +x (right) 270
        self.dial = QDial()
        self.dial.setRange(0, 359)
        self.dial.setWrapping(True)
        self.dial.setNotchesVisible(True)
        self.dial.setNotchTarget(15.0)
        self.dial.setFixedSize(96, 96)
        self.dial.setToolTip("the direction the wind blows towards, seen from above")
        self.direction_label = QLabel()
        self.preset_box = QComboBox()
        self.preset_box.addItems([CUSTOM, *PRESETS])
        self.preset_box.setToolTip(
            "how the gusts and the turbulence move; the direction stays (one undo step)"
        )
        children = [
            {
                "name": name,
                "title": title,
                "type": "float",
                "limits": RANGES[name],
                "step": step,
                "suffix": suffix,
                "value": getattr(wind, name),
                "tip": TIPS.get(name, ""),
            }
            for name, title, step, suffix in NUMBERS
        ]
        self.root = Parameter.create(name="wind", type="group", children=children)
        self.tree = ParameterTree(showHeader=False)
        self.tree.setParameters(self.root, showTop=False)
        fit_names(self.tree)
        self.message = QLabel()
        self.message.setWordWrap(True)
        dial_row = QHBoxLayout()
        dial_row.addWidget(self.dial)
        dial_row.addWidget(self.direction_label, 1, Qt.AlignmentFlag.AlignVCenter)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.enabled_box)
        layout.addLayout(dial_row)
        preset_row = QHBoxLayout()
        preset_row.addWidget(QLabel("Preset"))
        preset_row.addWidget(self.preset_box, 1)
        layout.addLayout(preset_row)
        layout.addWidget(self.tree)
        layout.addWidget(self.message)
        report_bad_text(self.tree, self.message)
        self.wind = wind
        self._updating = False
        self.show_wind(wind)
        self.enabled_box.toggled.connect(self._on_edited)
        self.dial.valueChanged.connect(self._on_edited)
        self.root.sigTreeStateChanged.connect(self._on_edited)
        self.preset_box.activated.connect(self._on_preset)

    @staticmethod
    def dial_value(direction: float) -> int:
        """The dial's position of a wind direction (core/wind.py: 0 ° = +x, 90 ° = +z)."""
        return round(direction + 270.0) % 360

    @staticmethod
    def direction_of(dial: int) -> float:
        value = (dial - 270.0) % 360.0
        return value - 360.0 if value > 180.0 else value

    def show_wind(self, wind: Wind) -> None:
        """Model -> widgets (an undo, a newly opened project)."""
        self.wind = wind
        self._updating = True
        try:
            self.enabled_box.setChecked(wind.enabled)
            self.dial.setValue(self.dial_value(wind.direction))
            for name, *_ in NUMBERS:
                self.root.child(name).setValue(getattr(wind, name))
            self.direction_label.setText(f"towards {wind.direction:.0f} °")
            self.preset_box.setCurrentText(preset_of(wind) or CUSTOM)
        finally:
            self._updating = False

    def _on_preset(self, index: int) -> None:
        """A preset picked: its values in one edit (the tree follows through show_wind)."""
        values = PRESETS.get(self.preset_box.itemText(index))
        if values is None:  # "(custom)": nothing to set
            self.preset_box.setCurrentText(preset_of(self.wind) or CUSTOM)
            return
        wind = self.wind.replace(**values)
        if wind == self.wind:
            return
        self.show_wind(wind)  # the numbers show the preset's
        self.message.clear()
        self.wind_edited.emit(wind)

    def _on_edited(self, *_) -> None:
        if self._updating:
            return
        values = {name: float(self.root.child(name).value()) for name, *_ in NUMBERS}
        values["enabled"] = self.enabled_box.isChecked()
        values["direction"] = self.direction_of(self.dial.value())
        try:
            wind = dataclasses.replace(self.wind, **values)
        except ValueError as exc:
            self.message.setText(str(exc))
            return
        self.message.clear()
        self.direction_label.setText(f"towards {wind.direction:.0f} °")
        self.preset_box.setCurrentText(preset_of(wind) or CUSTOM)
        if wind != self.wind:
            self.wind = wind
            self.wind_edited.emit(wind)
