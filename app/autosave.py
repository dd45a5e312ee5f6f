"""Autosave and recovery: while there are unsaved changes the project is saved every minute
(the window's timer calls `save_now`) to a file of its own, never over the person's project;
closing normally removes it. If Sward did not close normally, the next start offers to recover
that work. Qt-free (app/dialogs.py); `default_directory` asks Qt where application data goes."""

from __future__ import annotations

import time
from pathlib import Path

from app.dialogs import Dialogs, History, Settings
from app.project_actions import ProjectActions
from core.project_file import ProjectError, load_project, save_project

INTERVAL_MS = 60_000
NAME = "autosave.sward"


def default_directory() -> Path:
    from PySide6.QtCore import QStandardPaths

    location = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.AppDataLocation)
    return Path(location or Path.home() / ".sward")


class Autosave:
    def __init__(
        self,
        directory: Path,
        projects: ProjectActions,
        history: History,
        dialogs: Dialogs,
        settings: Settings,
    ) -> None:
        self.directory = Path(directory)
        self.projects = projects
        self.history = history
        self.dialogs = dialogs
        self.settings = settings

    @property
    def path(self) -> Path:
        return self.directory / NAME

    def save_now(self) -> bool:
        """Save the unsaved work (nothing to do when the project is clean)."""
        if self.history.isClean():
            return False
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            save_project(self.path, self.projects.document())
        except (OSError, ProjectError) as exc:
            self.dialogs.status(f"autosave failed: {exc}", 6000)
            return False
        project = self.projects.path
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
        if not self.dialogs.ask_yes(
            f"Sward did not close normally. Recover the unsaved work autosaved at {when}?"
        ):
            self.discard()
            return False
        try:
            document = load_project(self.path)
        except ProjectError as exc:
            self.dialogs.warn(f"the autosave cannot be read: {exc}")
            self.discard()
            return False
        self.projects.open_document(document)
        original = self.settings.value("autosave/project", "")
        self.projects.path = Path(original) if original else None
        self.history.resetClean()  # recovered work is not saved anywhere yet
        self.dialogs.status("recovered the autosaved work: save it", 8000)
        return True
