"""File → Export…: where to, which format, what to write, and the export's progress. The
export itself runs in another process (app/export_job.py); this dialog only asks and shows."""

from __future__ import annotations

from PySide6.QtCore import Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDialog,
    QFileDialog,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QProgressBar,
    QPushButton,
    QVBoxLayout,
)

PARTS = {  # what `sward export --what` names: the label a person reads
    "patch": "Patch meshes (blades, colours, density thresholds)",
    "slices": "Slices: PNG atlases, every mip level, their layout",
    "instances": "Instances over the terrain (in blocks)",
    "terrain": "Terrain mesh with the colour map",
    "maps": "Design maps (16-bit PNG, EXR, r16)",
    "lod": "Settings: grass types, LOD levels, light (JSON)",
}
FORMATS = {"gltf": "glTF 2.0 (instancing)", "usd": "USD (point instancers)"}


class ExportDialog(QDialog):
    export_requested = Signal()
    cancel_requested = Signal()

    def __init__(self, folder: str, parent=None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Export the design")
        self.folder = QLineEdit(folder)
        browse = QPushButton("Choose…")
        browse.clicked.connect(self._browse)
        where = QHBoxLayout()
        where.addWidget(self.folder)
        where.addWidget(browse)
        self.format = QComboBox()
        for key, label in FORMATS.items():
            self.format.addItem(label, key)
        self.parts = {key: QCheckBox(label) for key, label in PARTS.items()}
        form = QFormLayout()
        form.addRow("Folder", where)
        form.addRow("Format", self.format)
        for box in self.parts.values():
            box.setChecked(True)
            form.addRow("", box)
        self.progress = QProgressBar()
        self.progress.setRange(0, 100)
        self.progress.setValue(0)
        self.message = QLabel("")
        self.message.setWordWrap(True)
        self.export_button = QPushButton("Export")
        self.export_button.setDefault(True)
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setEnabled(False)
        close = QPushButton("Close")
        self.export_button.clicked.connect(self.export_requested)
        self.cancel_button.clicked.connect(self.cancel_requested)
        close.clicked.connect(self.reject)
        buttons = QHBoxLayout()
        buttons.addStretch(1)
        for b in (self.export_button, self.cancel_button, close):
            buttons.addWidget(b)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.progress)
        layout.addWidget(self.message)
        layout.addLayout(buttons)

    def chosen(self) -> tuple[str, str, list[str]]:
        """The folder, the format and the parts ticked."""
        parts = [key for key, box in self.parts.items() if box.isChecked()]
        return self.folder.text().strip(), self.format.currentData(), parts

    def running(self, on: bool) -> None:
        self.export_button.setEnabled(not on)
        self.cancel_button.setEnabled(on)

    def _browse(self) -> None:
        folder = QFileDialog.getExistingDirectory(self, "Export into", self.folder.text())
        if folder:
            self.folder.setText(folder)
