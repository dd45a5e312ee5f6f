"""Autosave and recovery: while there are unsaved changes the project is saved every minute to
a file of its own (never over the person's project); closing normally removes it. If Sward did
not close normally, the next start offers to recover that work."""

from __future__ import annotations

import time
from pathlib import Path

from PySide6.QtCore import QObject, QSettings, QStandardPaths, QTimer
from PySide6.QtWidgets import QMessageBox

from app.project import ProjectError, load_project, save_project

INTERVAL_MS = 60_000
NAME = "autosave.sward"


def default_directory() -> Path:
    location = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.AppDataLocation)
    return Path(location or Path.home() / ".sward")


class Autosave(QObject):
    def __init__(self, window, directory: Path | None = None) -> None:
        super().__init__(window)
        self.window = window
        self.directory = Path(directory) if directory is not None else default_directory()
        self.timer = QTimer(self)
        self.timer.setInterval(INTERVAL_MS)
        self.timer.timeout.connect(self.save_now)
        self.timer.start()
        self.settings = QSettings("Sward", "Sward")

    @property
    def path(self) -> Path:
        return self.directory / NAME

    def save_now(self) -> bool:
        """Save the unsaved work (nothing to do when the project is clean)."""
        w = self.window
        if w.undo_stack.isClean():
            return False
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            save_project(self.path, w.projects.current_scene(), w.maps)
        except (OSError, ProjectError) as exc:
            w.statusBar().showMessage(f"autosave failed: {exc}", 6000)
            return False
        project = w.projects.path
        self.settings.setValue("autosave/project", str(project) if project else "")
        self.settings.setValue("autosave/time", time.strftime("%Y-%m-%d %H:%M"))
        return True

    def discard(self) -> None:
        """A normal close: the autosave is not needed."""
        self.path.unlink(missing_ok=True)

    def recover_if_any(self) -> bool:
        """At start: offer the work an earlier session did not save. Returns whether it was
        recovered (it then shows as unsaved, with its original file name if it had one)."""
        if not self.path.exists():
            return False
        when = self.settings.value("autosave/time", "an earlier session")
        answer = QMessageBox.question(
            self.window,
            "Sward",
            f"Sward did not close normally. Recover the unsaved work autosaved at {when}?",
            QMessageBox.StandardButton.Yes | QMessageBox.StandardButton.No,
        )
        if answer != QMessageBox.StandardButton.Yes:
            self.discard()
            return False
        try:
            scene = load_project(self.path)
        except ProjectError as exc:
            QMessageBox.warning(self.window, "Sward", f"the autosave cannot be read: {exc}")
            self.discard()
            return False
        self.window.open_scene(scene)
        original = self.settings.value("autosave/project", "")
        self.window.projects.path = Path(original) if original else None
        self.window.undo_stack.resetClean()  # recovered work is not saved anywhere yet
        self.window.statusBar().showMessage("recovered the autosaved work: save it", 8000)
        return True
