"""The Qt side of app/dialogs.py: file dialogs, message boxes and the status line of a window."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QSettings, QStandardPaths
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QFormLayout,
    QInputDialog,
    QLineEdit,
    QMainWindow,
    QMessageBox,
)

from app.dialogs import CANCEL, DISCARD, SAVE
from core.species import Species
from widgets.raw_dialog import RawHeightDialog
from widgets.species_dialog import SpeciesDialog

Button = QMessageBox.StandardButton
DialogButton = QDialogButtonBox.StandardButton
FOLDER_KEY = "dialogs/folder"  # the folder the last file was opened or saved in


class QtDialogs:
    """File dialogs open in the folder a file was last opened or saved in (kept in the
    settings, across runs), at first in the user's documents folder, not wherever the
    designer was started from."""

    def __init__(self, window: QMainWindow) -> None:
        self.window = window

    @property
    def folder(self) -> str:
        documents = QStandardPaths.writableLocation(
            QStandardPaths.StandardLocation.DocumentsLocation
        )
        kept = QSettings("Sward", "Sward").value(FOLDER_KEY, "", type=str)
        return kept if kept and Path(kept).is_dir() else documents or str(Path.home())

    def _chosen(self, path: str) -> str | None:
        if path:
            QSettings("Sward", "Sward").setValue(FOLDER_KEY, str(Path(path).parent))
        return path or None

    def save_path(self, title: str, suggested: str, filters: str) -> str | None:
        start = str(Path(self.folder) / suggested)
        return self._chosen(QFileDialog.getSaveFileName(self.window, title, start, filters)[0])

    def open_path(self, title: str, filters: str) -> str | None:
        return self._chosen(
            QFileDialog.getOpenFileName(self.window, title, self.folder, filters)[0]
        )

    def ask_unsaved(self, text: str) -> str:
        answer = QMessageBox.question(
            self.window, "Sward", text, Button.Save | Button.Discard | Button.Cancel
        )
        return {Button.Save: SAVE, Button.Discard: DISCARD}.get(answer, CANCEL)

    def ask_yes(self, text: str) -> bool:
        answer = QMessageBox.question(self.window, "Sward", text, Button.Yes | Button.No)
        return answer == Button.Yes

    def warn(self, text: str) -> None:
        QMessageBox.warning(self.window, "Sward", text)

    def status(self, text: str, ms: int = 5000) -> None:
        self.window.statusBar().showMessage(text, ms)

    def ask_text(self, title: str, label: str) -> str | None:
        """One line of text, or None if cancelled; the dialog is wide enough for its title
        (a window manager cuts a title wider than the window)."""
        # QInputDialog sets its own minimum width when shown: a plain dialog keeps ours
        dialog = QDialog(self.window)
        dialog.setWindowTitle(title)
        field = QLineEdit()
        buttons = QDialogButtonBox(DialogButton.Ok | DialogButton.Cancel)
        buttons.accepted.connect(dialog.accept)
        buttons.rejected.connect(dialog.reject)
        layout = QFormLayout(dialog)
        layout.addRow(label, field)
        layout.addRow(buttons)
        dialog.setMinimumWidth(max(dialog.fontMetrics().horizontalAdvance(title) + 160, 360))
        if dialog.exec() != QDialog.DialogCode.Accepted:
            return None
        return field.text()

    def ask_number(
        self, title: str, label: str, value: float, low: float, high: float, unit: str = ""
    ) -> float | None:
        """A number in low … high, or None if cancelled."""
        number, ok = QInputDialog.getDouble(
            self.window, title, f"{label} ({low:g} … {high:g}{unit})", value, low, high, 1
        )
        return number if ok else None

    def raw_height_options(self, name: str, size: int) -> dict | None:
        dialog = RawHeightDialog(name, size, self.window)
        if dialog.exec() != QDialog.DialogCode.Accepted:
            return None
        return dialog.values()

    def species_rules(self, names: list[str], derived: list[tuple], species: Species):
        dialog = SpeciesDialog(names, derived, species, self.window)
        if dialog.exec() != QDialog.DialogCode.Accepted:
            return None
        return dialog.species()
