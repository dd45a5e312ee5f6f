"""The designer's project actions: new from a built-in scene, open, save, save as, recent
files, and the question about unsaved changes. Files go through app/project.py."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from PySide6.QtCore import QObject, QSettings
from PySide6.QtWidgets import QFileDialog, QMessageBox

from app.project import SUFFIX, ProjectError, load_project, save_project

RECENT = 8
FILTER = f"Sward project (*{SUFFIX})"


class ProjectActions(QObject):
    def __init__(self, window) -> None:
        super().__init__(window)
        self.window = window
        self.path: Path | None = None
        self.settings = QSettings("Sward", "Sward")

    # -- what is saved -----------------------------------------------------------------------
    def current_scene(self):
        w = self.window
        return dataclasses.replace(
            w.scene,
            params=w.design.params,
            density=w.design.density,
            slices=w.design.slices,
            stack=w.maps.stack,
            lod=w.lods[0],
            grass=tuple(
                dataclasses.replace(kind, lod=w.lods[i + 1], params=w.designs[i + 1].params)
                for i, kind in enumerate(w.scene.grass)
            ),
        )

    # -- actions -----------------------------------------------------------------------------
    def save(self) -> bool:
        return self.save_as(self.path) if self.path is not None else self.save_as()

    def save_as(self, path: Path | str | None = None) -> bool:
        if path is None:
            chosen, _ = QFileDialog.getSaveFileName(
                self.window, "Save project", f"{self.window.scene.name}{SUFFIX}", FILTER
            )
            if not chosen:
                return False
            path = chosen
        path = Path(path)
        try:
            save_project(path, self.current_scene(), self.window.maps)
        except ProjectError as exc:
            QMessageBox.warning(self.window, "Sward", str(exc))
            return False
        self.path = path
        self.window.undo_stack.setClean()
        self._remember(path)
        self.window.statusBar().showMessage(f"saved {path}", 4000)
        return True

    def open(self, path: Path | str | None = None) -> bool:
        """Open a project; a file that cannot be read leaves the open one as it was."""
        if not self.confirm_discard():
            return False
        if path is None:
            chosen, _ = QFileDialog.getOpenFileName(self.window, "Open project", "", FILTER)
            if not chosen:
                return False
            path = chosen
        path = Path(path)
        try:
            scene = load_project(path)
        except ProjectError as exc:
            QMessageBox.warning(self.window, "Sward", str(exc))
            return False
        self.window.open_scene(scene)
        self.path = path
        self._remember(path)
        return True

    def new(self, scene) -> bool:
        """Start from a built-in scene (not yet a file)."""
        if not self.confirm_discard():
            return False
        self.window.open_scene(scene)
        self.path = None
        return True

    def confirm_discard(self) -> bool:
        """True when there are no unsaved changes, or the person saved or dropped them."""
        if self.window.undo_stack.isClean():
            return True
        answer = QMessageBox.question(
            self.window,
            "Sward",
            "The project has unsaved changes. Save them first?",
            QMessageBox.StandardButton.Save
            | QMessageBox.StandardButton.Discard
            | QMessageBox.StandardButton.Cancel,
        )
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard

    # -- recent files ------------------------------------------------------------------------
    def recent(self) -> list[str]:
        value = self.settings.value("recent", [])
        return [value] if isinstance(value, str) else list(value or [])

    def _remember(self, path: Path) -> None:
        text = str(path.resolve())
        files = [text] + [p for p in self.recent() if p != text]
        self.settings.setValue("recent", files[:RECENT])
        self.window.fill_recent_menu()
