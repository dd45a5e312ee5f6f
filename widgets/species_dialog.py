"""Paint → Grass types from colours…: each kind's rule before an image places them
(Papavasiliou §3.3, core/species.py): a reference colour (the design's unless the person picks
one), a weight for hue, saturation and value, and the exponent that sharpens the borders."""

from __future__ import annotations

import colorsys

from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QColorDialog,
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QGridLayout,
    QLabel,
    QPushButton,
    QToolButton,
    QVBoxLayout,
)

from core.species import Species, SpeciesTuning

HSV = tuple[float, float, float]


class _KindRow:
    """One kind's controls in the dialog's grid."""

    def __init__(self, grid: QGridLayout, row: int, name: str, derived: HSV, tuning) -> None:
        self.derived, self.reference = derived, tuning.reference
        self.colour = QPushButton()
        self.colour.setToolTip(f"{name}'s reference colour: click to pick one")
        self.colour.clicked.connect(self._pick)
        self.reset = QToolButton(text="↺")
        self.reset.setToolTip("Back to the colour the design gives (the blades' mean, the soil's)")
        self.reset.clicked.connect(lambda: self._set_reference(None))
        self.weights = [
            QDoubleSpinBox(minimum=0.0, maximum=100.0, singleStep=0.25, value=w)
            for w in tuning.weights
        ]
        self.exponent = QDoubleSpinBox(
            minimum=0.1, maximum=32.0, singleStep=0.5, value=tuning.exponent
        )
        self.exponent.setToolTip("Larger: sharper borders between kinds")
        for column, widget in enumerate(
            [QLabel(name), self.colour, self.reset, *self.weights, self.exponent]
        ):
            grid.addWidget(widget, row, column)
        self._set_reference(tuning.reference)

    def _set_reference(self, reference: HSV | None) -> None:
        self.reference = reference
        r, g, b = colorsys.hsv_to_rgb(*(reference or self.derived))
        self.colour.setText("own" if reference else "design")
        self.colour.setStyleSheet(
            f"background: rgb({r * 255:.0f}, {g * 255:.0f}, {b * 255:.0f});"
            f" color: {'black' if max(r, g, b) > 0.55 else 'white'}"
        )
        self.reset.setEnabled(reference is not None)

    def _pick(self) -> None:
        start = QColor.fromHsvF(*(self.reference or self.derived))
        colour = QColorDialog.getColor(start, self.colour, "Reference colour")
        if colour.isValid():
            self.set_colour(colour)

    def set_colour(self, colour: QColor) -> None:
        h, s, v, _a = colour.getHsvF()
        self._set_reference((max(h, 0.0), s, v))  # hue −1: a grey

    def tuning(self) -> SpeciesTuning:
        weights = tuple(box.value() for box in self.weights)
        return SpeciesTuning(weights, self.exponent.value(), self.reference)  # type: ignore[arg-type]

    def weighs(self) -> bool:
        """Whether some component counts (a rule of three zero weights scores nothing)."""
        return any(box.value() > 0 for box in self.weights)


class SpeciesDialog(QDialog):
    def __init__(self, names: list[str], derived: list[HSV], species: Species, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Grass types from colours")
        intro = QLabel(
            "Each point of the colour image goes to the kind whose reference colour it is "
            "nearest; where two score alike they mix, where the soil wins it stays bare. "
            "Then choose the image."
        )
        intro.setWordWrap(True)
        grid = QGridLayout()
        for column, title in enumerate(
            ["", "Reference", "", "Hue", "Saturation", "Value", "Exponent"]
        ):
            grid.addWidget(QLabel(title), 0, column)
        tunings = [species.kind(i) for i in range(len(names) - 1)] + [species.soil]
        self.rows = [
            _KindRow(grid, row + 1, name, ref, tuning)
            for row, (name, ref, tuning) in enumerate(zip(names, derived, tunings, strict=True))
        ]
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Cancel)
        self.place_button = buttons.addButton(
            "Choose image…", QDialogButtonBox.ButtonRole.AcceptRole
        )
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        for row in self.rows:
            for box in row.weights:
                box.valueChanged.connect(self._check)
        layout = QVBoxLayout(self)
        layout.addWidget(intro)
        layout.addLayout(grid)
        layout.addWidget(buttons)

    def _check(self) -> None:
        ok = all(row.weighs() for row in self.rows)
        self.place_button.setEnabled(ok)
        self.place_button.setToolTip("" if ok else "Each kind needs a weight above 0")

    def species(self) -> Species:
        *kinds, soil = (row.tuning() for row in self.rows)
        return Species(tuple(kinds), soil)
