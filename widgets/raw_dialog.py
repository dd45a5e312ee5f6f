"""Asks how to read a raw 16-bit height file (.r16 / .raw have no header): its size, byte order
and the height range its values span; a square size is proposed from the file's length."""

from __future__ import annotations

import math

from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QFormLayout,
    QLabel,
    QSpinBox,
)


class RawHeightDialog(QDialog):
    def __init__(self, name: str, size_bytes: int, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"Read {name}")
        side = max(1, math.isqrt(size_bytes // 2))
        form = QFormLayout(self)
        form.addRow(QLabel(f"{name}: {size_bytes:,} bytes of 16-bit values"))
        self.width_box = QSpinBox(minimum=1, maximum=65536, value=side)
        self.height_box = QSpinBox(minimum=1, maximum=65536, value=side)
        self.order_box = QComboBox()
        self.order_box.addItems(["little-endian (PC, most terrain tools)", "big-endian (Mac)"])
        self.low_box = QDoubleSpinBox(minimum=0.0, maximum=1.0, singleStep=0.05, value=0.0)
        self.high_box = QDoubleSpinBox(minimum=0.0, maximum=1.0, singleStep=0.05, value=1.0)
        for box in (self.low_box, self.high_box):
            box.setToolTip("0 … 1 of the scene's height scale that values 0 and 65535 become")
        form.addRow("Width", self.width_box)
        form.addRow("Height", self.height_box)
        form.addRow("Byte order", self.order_box)
        form.addRow("Value 0 becomes", self.low_box)
        form.addRow("Value 65535 becomes", self.high_box)
        buttons = QDialogButtonBox(
            QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel
        )
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def values(self) -> dict:
        return {
            "width": self.width_box.value(),
            "height": self.height_box.value(),
            "big_endian": self.order_box.currentIndex() == 1,
            "low": self.low_box.value(),
            "high": self.high_box.value(),
        }
