"""The Qt side of app/dialogs.py: file dialogs, message boxes and the status line of a window."""

from __future__ import annotations

from PySide6.QtWidgets import QDialog, QFileDialog, QMainWindow, QMessageBox

from app.dialogs import CANCEL, DISCARD, SAVE
from widgets.raw_dialog import RawHeightDialog

Button = QMessageBox.StandardButton


class QtDialogs:
    def __init__(self, window: QMainWindow) -> None:
        self.window = window

    def save_path(self, title: str, suggested: str, filters: str) -> str | None:
        path, _ = QFileDialog.getSaveFileName(self.window, title, suggested, filters)
        return path or None

    def open_path(self, title: str, filters: str) -> str | None:
        path, _ = QFileDialog.getOpenFileName(self.window, title, "", filters)
        return path or None

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

    def raw_height_options(self, name: str, size: int) -> dict | None:
        dialog = RawHeightDialog(name, size, self.window)
        if dialog.exec() != QDialog.DialogCode.Accepted:
            return None
        return dialog.values()
