"""Paint dock → Only where: the brush takes only where the ground's slope and height lie in the
ranges set here (core/paint_rule.py), with a soft edge; Fill by rule paints the whole map
there. The rule is the document's (saved with the project); the Map dock shows where it holds."""

from __future__ import annotations

from PySide6.QtCore import Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QDoubleSpinBox,
    QGridLayout,
    QGroupBox,
    QLabel,
    QPushButton,
)

from core.paint_rule import PaintRule


class RuleBox(QGroupBox):
    rule_edited = Signal(object)  # the PaintRule the person set
    fill_requested = Signal()

    def __init__(self, parent=None) -> None:
        super().__init__("Only where", parent)
        self.slope_check = QCheckBox("Slope")
        self.slope_min = self._box(0.0, 90.0, 1.0, 0.0, "°")
        self.slope_max = self._box(0.0, 90.0, 1.0, 30.0, "°")
        self.height_check = QCheckBox("Height")
        self.height_min = self._box(-1e4, 1e4, 0.1, 0.0, "")
        self.height_max = self._box(-1e4, 1e4, 0.1, 1.0, "")
        self.soft_slope = self._box(0.0, 45.0, 0.5, 2.0, "°")
        self.soft_height = self._box(0.0, 1e4, 0.05, 0.1, "")
        self.soft_slope.setToolTip("how far past the slope range the brush fades out")
        self.soft_height.setToolTip("how far past the height range the brush fades out")
        self.fill_button = QPushButton("Fill by rule")
        self.fill_button.setToolTip(
            "the chosen map takes the brush's value wherever the rule holds (one undo step)"
        )
        self.fill_button.clicked.connect(self.fill_requested)
        grid = QGridLayout(self)
        for row, (check, low, high) in enumerate(
            (
                (self.slope_check, self.slope_min, self.slope_max),
                (self.height_check, self.height_min, self.height_max),
            )
        ):
            grid.addWidget(check, row, 0)
            grid.addWidget(low, row, 1)
            grid.addWidget(QLabel("to"), row, 2)
            grid.addWidget(high, row, 3)
        grid.addWidget(QLabel("Soft edge"), 2, 0)
        grid.addWidget(self.soft_slope, 2, 1)
        grid.addWidget(self.soft_height, 2, 3)
        grid.addWidget(self.fill_button, 3, 0, 1, 4)
        self.message = QLabel()
        self.message.setWordWrap(True)
        grid.addWidget(self.message, 4, 0, 1, 4)
        for check in (self.slope_check, self.height_check):
            check.toggled.connect(self._edited)
        for box in self._boxes:
            box.valueChanged.connect(self._edited)
        self.set_rule(PaintRule())

    @staticmethod
    def _box(low: float, high: float, step: float, value: float, suffix: str) -> QDoubleSpinBox:
        box = QDoubleSpinBox(minimum=low, maximum=high, singleStep=step, value=value)
        box.setSuffix(suffix)
        box.setKeyboardTracking(False)  # a typed number applies on Enter
        return box

    @property
    def _boxes(self) -> tuple[QDoubleSpinBox, ...]:
        return (
            self.slope_min,
            self.slope_max,
            self.height_min,
            self.height_max,
            self.soft_slope,
            self.soft_height,
        )

    def rule(self) -> PaintRule:
        """The rule the controls show (ValueError where a range is upside down)."""
        return PaintRule(
            (self.slope_min.value(), self.slope_max.value())
            if self.slope_check.isChecked()
            else None,
            (self.height_min.value(), self.height_max.value())
            if self.height_check.isChecked()
            else None,
            self.soft_slope.value(),
            self.soft_height.value(),
        )

    def set_rule(self, rule: PaintRule) -> None:
        """Show the document's rule (no edit is reported)."""
        widgets = (self.slope_check, self.height_check, *self._boxes)
        for widget in widgets:
            widget.blockSignals(True)
        self.slope_check.setChecked(rule.slope is not None)
        self.height_check.setChecked(rule.height is not None)
        if rule.slope is not None:
            self.slope_min.setValue(rule.slope[0])
            self.slope_max.setValue(rule.slope[1])
        if rule.height is not None:
            self.height_min.setValue(rule.height[0])
            self.height_max.setValue(rule.height[1])
        self.soft_slope.setValue(rule.soft_slope)
        self.soft_height.setValue(rule.soft_height)
        for widget in widgets:
            widget.blockSignals(False)
        self.fill_button.setEnabled(rule.active)

    def _edited(self) -> None:
        try:
            rule = self.rule()
        except ValueError as exc:
            self.message.setText(str(exc))
            return
        self.message.clear()
        self.fill_button.setEnabled(rule.active)
        self.rule_edited.emit(rule)
