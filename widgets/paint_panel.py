"""The brush panel: which map is painted (density per grass type, colour, ambient, diffuse,
height, trampled grass), the mode and the brush (size, strength, target value, falloff, spacing). It shows the
brush and reports edits; strokes are made by the designer's paint controller."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QCheckBox,
    QColorDialog,
    QComboBox,
    QDoubleSpinBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from core.brush import ALL_TYPES, FALLOFFS, MODES, Brush
from core.trample import brush_value, decode
from core.wind import MAX_LEAN
from widgets.rule_box import RuleBox

SCALAR_LAYERS = {  # map -> (value label, maximum)
    "density": ("Density", 1.0),
    "ambient": ("Ambient light", 2.0),
    "diffuse": ("Diffuse light", 2.0),
    "height": ("Height", 1.0),
    "trample": ("Lay over", MAX_LEAN),  # the tips' displacement, a fraction of the blades' length
}


TRAMPLE_DEFAULT = 0.5  # a trodden path's first lean: the blades half laid over


class PaintPanel(QWidget):
    brush_changed = Signal()
    import_requested = Signal()
    export_requested = Signal()
    species_requested = Signal()

    def __init__(self, grass_names: list[str], parent=None) -> None:
        super().__init__(parent)
        form = QFormLayout()
        self.layer_box = QComboBox()
        self.set_grass_names(grass_names)
        form.addRow("Map", self.layer_box)
        self.mode_box = QComboBox()
        self.mode_box.addItems(MODES)
        self.mode_box.setToolTip("Ctrl while painting: erase · Shift: smooth")
        form.addRow("Mode", self.mode_box)
        self.size_box = QSpinBox(minimum=1, maximum=1024, value=24, suffix=" texels")
        self.size_box.setToolTip("[ smaller · ] bigger")
        form.addRow("Size", self.size_box)
        self.strength_box = QDoubleSpinBox(minimum=0.0, maximum=1.0, singleStep=0.1, value=0.8)
        self.strength_box.setToolTip("- weaker · = stronger")
        form.addRow("Strength", self.strength_box)
        # paint adds (full density, light, height); Ctrl or the erase mode takes away
        self.value_box = QDoubleSpinBox(minimum=0.0, maximum=1.0, singleStep=0.05, value=1.0)
        self.value_label = QLabel("Density")
        form.addRow(self.value_label, self.value_box)
        self.color = QColor(235, 200, 40)
        self.color_button = QPushButton()
        self.color_button.clicked.connect(self._choose_color)
        self.alpha_box = QDoubleSpinBox(minimum=0.0, maximum=1.0, singleStep=0.05, value=0.9)
        self.alpha_box.setToolTip("how strongly the colour replaces the blades' own (eq. 6.8)")
        colour_row = QHBoxLayout()
        colour_row.addWidget(self.color_button, 1)
        colour_row.addWidget(QLabel("weight"))
        colour_row.addWidget(self.alpha_box)
        self.color_row = QWidget()
        self.color_row.setLayout(colour_row)
        colour_row.setContentsMargins(0, 0, 0, 0)
        form.addRow("Colour", self.color_row)
        # trampled grass: the way the blades lie, or the way the stroke goes (a path walked)
        self.direction_box = QDoubleSpinBox(minimum=0.0, maximum=360.0, wrapping=True, suffix="°")
        self.direction_box.setToolTip("the way the blades lie: 0° along +x, 90° along +z")
        self.along_box = QCheckBox("along the stroke")
        self.along_box.setChecked(True)
        self.along_box.setToolTip("lay the blades the way the brush moves, as feet would")
        self.along_box.toggled.connect(lambda on: self.direction_box.setEnabled(not on))
        self.direction_box.setEnabled(False)
        way_row = QHBoxLayout()
        way_row.addWidget(self.direction_box, 1)
        way_row.addWidget(self.along_box)
        way_row.setContentsMargins(0, 0, 0, 0)
        self.way_row = QWidget()
        self.way_row.setLayout(way_row)
        form.addRow("Direction", self.way_row)
        self.form = form
        self.falloff_box = QComboBox()
        self.falloff_box.addItems(FALLOFFS)
        form.addRow("Falloff", self.falloff_box)
        self.spacing_box = QDoubleSpinBox(minimum=0.05, maximum=4.0, singleStep=0.05, value=0.25)
        self.spacing_box.setToolTip("distance between dabs, in brush sizes")
        form.addRow("Spacing", self.spacing_box)
        buttons = QHBoxLayout()
        self.import_button = QPushButton("Import map…")
        self.export_button = QPushButton("Export map…")
        self.import_button.clicked.connect(self.import_requested)
        self.export_button.clicked.connect(self.export_requested)
        buttons.addWidget(self.import_button)
        buttons.addWidget(self.export_button)
        self.species_button = QPushButton("Grass types from colours…")
        self.species_button.setToolTip(
            "each grass type grows where a terrain colour image is nearest its blades' colour, "
            "none where it is nearest the soil's (one undo step)"
        )
        self.species_button.clicked.connect(self.species_requested)
        self.hint = QLabel(
            "B: paint in the viewport (left drag paints, right drag orbits, middle pans) · "
            "I: pick a value · Ctrl: erase · Shift: smooth"
        )
        self.hint.setWordWrap(True)
        self.message = QLabel()
        self.message.setWordWrap(True)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addLayout(buttons)
        layout.addWidget(self.species_button)
        self.rule_box = RuleBox()
        layout.addWidget(self.rule_box)
        layout.addWidget(self.hint)
        layout.addWidget(self.message)
        layout.addStretch(1)
        # each map keeps its own brush: what it was last painted with
        self._brushes: dict[tuple, dict] = {}
        self._brush_of = self.target
        self.layer_box.currentIndexChanged.connect(self._switch_map)
        for box in (self.layer_box, self.mode_box, self.falloff_box):
            box.currentIndexChanged.connect(self._changed)
        for box in (
            self.size_box,
            self.strength_box,
            self.value_box,
            self.alpha_box,
            self.spacing_box,
            self.direction_box,
        ):
            box.valueChanged.connect(self._changed)
        self.along_box.toggled.connect(self._changed)
        self._changed()

    def set_grass_names(self, names: list[str]) -> None:
        self.layer_box.blockSignals(True)
        self.layer_box.clear()
        if len(names) > 1:
            self.layer_box.addItem("density — all grass types", ("density", ALL_TYPES))
        for i, name in enumerate(names):
            self.layer_box.addItem(f"density — {name}", ("density", i))
        self.layer_box.addItem("colour (RGB + weight)", ("color", None))
        self.layer_box.addItem("ambient light", ("ambient", None))
        self.layer_box.addItem("diffuse light", ("diffuse", None))
        self.layer_box.addItem("height", ("height", None))
        self.layer_box.addItem("trampled grass", ("trample", None))
        self.layer_box.blockSignals(False)
        self._brush_of = self.target

    # -- what the brush is -------------------------------------------------------------------
    @property
    def target(self) -> tuple[str, int | None]:
        """(map name, density channel or None)."""
        data = self.layer_box.currentData()
        return tuple(data) if data else ("density", 0)

    @property
    def target_label(self) -> str:
        """The chosen map as the Map box names it (for the undo history)."""
        return self.layer_box.currentText()

    def show_message(self, text: str) -> None:
        self.message.setText(text)

    def select(self, layer: str, channel: int | None = None) -> None:
        """Paint this map next (channel: a grass type's density, or ALL_TYPES)."""
        for i in range(self.layer_box.count()):
            if tuple(self.layer_box.itemData(i)) == (layer, channel):
                self.layer_box.setCurrentIndex(i)
                return
        raise KeyError(f"no map {layer!r} (channel {channel}) to paint")

    def value(self) -> tuple[float, ...]:
        layer, _ = self.target
        if layer == "color":
            return (
                self.color.redF(),
                self.color.greenF(),
                self.color.blueF(),
                self.alpha_box.value(),
            )
        v = self.value_box.value()
        if layer == "trample":
            return brush_value(v, self.direction_box.value())
        return (v, v, v) if layer in ("ambient", "diffuse") else (v,)

    @property
    def follows(self) -> bool:
        """Whether strokes turn the brush's lean the way they go (the trample map)."""
        return self.target[0] == "trample" and self.along_box.isChecked()

    def brush(self, mode: str | None = None) -> Brush:
        return Brush(
            size=float(self.size_box.value()),
            strength=self.strength_box.value(),
            value=self.value(),
            falloff=self.falloff_box.currentText(),
            spacing=self.spacing_box.value(),
            mode=mode or self.mode_box.currentText(),
        )

    def set_value(self, values) -> None:
        """The eyedropper's pick: the map's value under the cursor becomes the target."""
        layer, _ = self.target
        if layer == "color":
            r, g, b, a = (float(v) for v in values[:4])
            self.color = QColor.fromRgbF(min(r, 1.0), min(g, 1.0), min(b, 1.0))
            self.alpha_box.setValue(a)
        elif layer == "trample":
            x, z = decode(np.asarray(values[:2], np.float64))
            self.value_box.setValue(float(np.hypot(x, z)))
            self.direction_box.setValue(float(np.degrees(np.arctan2(z, x))) % 360.0)
            self.along_box.setChecked(False)  # the picked direction, not the stroke's
        else:
            self.value_box.setValue(float(values[0]))
        self._changed()

    # -- one brush per map -------------------------------------------------------------------
    def _settings(self) -> dict:
        return {
            "mode": self.mode_box.currentIndex(),
            "size": self.size_box.value(),
            "strength": self.strength_box.value(),
            "value": self.value_box.value(),
            "color": QColor(self.color),
            "alpha": self.alpha_box.value(),
            "falloff": self.falloff_box.currentIndex(),
            "spacing": self.spacing_box.value(),
            "direction": self.direction_box.value(),
            "along": self.along_box.isChecked(),
        }

    def _switch_map(self, *_) -> None:
        """Keep the brush of the map left; take up the brush the chosen map had."""
        self._brushes[self._brush_of] = self._settings()
        self._brush_of = self.target
        kept = self._brushes.get(self._brush_of)
        layer, _ = self._brush_of
        boxes = (self.mode_box, self.size_box, self.strength_box, self.value_box,
                 self.alpha_box, self.falloff_box, self.spacing_box, self.direction_box,
                 self.along_box)  # fmt: skip
        for box in boxes:
            box.blockSignals(True)
        try:
            if layer in SCALAR_LAYERS:
                self.value_box.setMaximum(SCALAR_LAYERS[layer][1])
            if kept is None and layer == "trample":
                self.value_box.setValue(TRAMPLE_DEFAULT)
            if kept is not None:
                self.mode_box.setCurrentIndex(kept["mode"])
                self.size_box.setValue(kept["size"])
                self.strength_box.setValue(kept["strength"])
                self.value_box.setValue(kept["value"])
                self.color = QColor(kept["color"])
                self.alpha_box.setValue(kept["alpha"])
                self.falloff_box.setCurrentIndex(kept["falloff"])
                self.spacing_box.setValue(kept["spacing"])
                self.direction_box.setValue(kept["direction"])
                self.along_box.setChecked(kept["along"])
        finally:
            for box in boxes:
                box.blockSignals(False)

    # -- edits -------------------------------------------------------------------------------
    def scale_size(self, factor: float) -> None:
        self.size_box.setValue(max(1, round(self.size_box.value() * factor)))

    def add_strength(self, delta: float) -> None:
        self.strength_box.setValue(round(self.strength_box.value() + delta, 2))

    def _choose_color(self) -> None:
        chosen = QColorDialog.getColor(self.color, self, "Brush colour")
        if chosen.isValid():
            self.color = chosen
            self._changed()

    def _changed(self, *_) -> None:
        layer, _ = self.target
        is_color = layer == "color"
        self.form.setRowVisible(self.color_row, is_color)
        self.form.setRowVisible(self.value_box, not is_color)
        self.form.setRowVisible(self.way_row, layer == "trample")
        if not is_color:
            label, high = SCALAR_LAYERS[layer]
            self.value_label.setText(label)
            self.value_box.setMaximum(high)
        self.color_button.setStyleSheet(f"background: {self.color.name()}")
        self.color_button.setText(self.color.name())
        self.brush_changed.emit()
