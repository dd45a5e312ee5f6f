"""Autosave and recovery: while there are unsaved changes the project is saved every minute
(the window's timer calls `save_now`) to a file of this designer's own — never over the
person's project, never over another running designer's autosave (each holds a lock on its
own); closing normally removes it, and so does saving the project. If a designer did not close
normally, the next start offers to recover its work, unless the project file is newer.
Qt-free (app/dialogs.py); `default_directory` asks Qt where application data goes."""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import time
from pathlib import Path

from app.dialogs import Dialogs, History
from app.project_actions import ProjectActions
from core.project_file import ProjectError, load_project, save_project

INTERVAL_MS = 60_000
PREFIX = "autosave-"


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
        name: str | None = None,
    ) -> None:
        """`name` tells this designer's files apart (by default its process id)."""
        self.directory = Path(directory)
        self.projects = projects
        self.history = history
        self.dialogs = dialogs
        self.name = name or str(os.getpid())
        self._lock: int | None = None  # a descriptor holding flock on our lock file

    @property
    def path(self) -> Path:
        return self.directory / f"{PREFIX}{self.name}.sward"

    def _meta(self, sward: Path) -> Path:
        return sward.with_suffix(".json")

    def _lockfile(self, sward: Path) -> Path:
        return sward.with_suffix(".lock")

    def _hold_lock(self) -> None:
        if self._lock is None:
            self.directory.mkdir(parents=True, exist_ok=True)
            fd = os.open(self._lockfile(self.path), os.O_RDWR | os.O_CREAT, 0o600)
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            self._lock = fd

    def save_now(self) -> bool:
        """Save the unsaved work (nothing to do when the project is clean)."""
        if self.history.isClean():
            return False
        try:
            self._hold_lock()
            save_project(self.path, self.projects.document())
            project = self.projects.path
            meta = {"project": str(project) if project else "", "time": time.strftime("%H:%M")}
            self._meta(self.path).write_text(json.dumps(meta))
        except (OSError, ProjectError) as exc:
            self.dialogs.status(f"autosave failed: {exc}", 6000)
            return False
        return True

    def discard(self) -> None:
        """A save or a normal close: the autosave holds nothing the project file lacks."""
        for path in (self.path, self._meta(self.path)):
            path.unlink(missing_ok=True)

    def close(self) -> None:
        """A normal close: no autosave, no lock left."""
        self.discard()
        if self._lock is not None:
            os.close(self._lock)
            self._lock = None
            self._lockfile(self.path).unlink(missing_ok=True)

    def _orphans(self) -> list[Path]:
        """Autosaves of designers that are gone (nobody holds their lock), newest first."""
        found = []
        for sward in self.directory.glob(f"{PREFIX}*.sward"):
            if sward == self.path:
                continue
            fd = os.open(self._lockfile(sward), os.O_RDWR | os.O_CREAT, 0o600)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                continue  # a running designer's
            finally:
                os.close(fd)
            found.append(sward)
        return sorted(found, key=lambda p: p.stat().st_mtime, reverse=True)

    def _forget(self, sward: Path) -> None:
        for path in (sward, self._meta(sward), self._lockfile(sward)):
            path.unlink(missing_ok=True)

    def recover_if_any(self) -> bool:
        """At start: offer the newest work a designer that did not close normally left,
        unless its project file was saved after it. Returns whether it was recovered (it then
        shows as unsaved, with its original file name if it had one)."""
        if not self.directory.is_dir():
            return False
        self._hold_lock()
        for sward in self._orphans():
            try:
                meta = json.loads(self._meta(sward).read_text(encoding="utf-8"))
            except (OSError, ValueError):
                meta = {}
            project = Path(meta["project"]) if meta.get("project") else None
            with contextlib.suppress(OSError):
                if project is not None and project.stat().st_mtime >= sward.stat().st_mtime:
                    self._forget(sward)  # the saved file is newer: nothing to recover
                    continue
            when = meta.get("time", "an earlier session")
            if not self.dialogs.ask_yes(
                f"Sward did not close normally. Recover the unsaved work autosaved at {when}?"
            ):
                self._forget(sward)
                return False
            try:
                document = load_project(sward)
            except ProjectError as exc:
                self.dialogs.warn(f"the autosave cannot be read: {exc}")
                self._forget(sward)
                return False
            self.projects.open_document(document)
            self.projects.path = project
            self.history.resetClean()  # recovered work is not saved anywhere yet
            self._forget(sward)  # from now on it is this designer's own autosave's
            self.save_now()
            self.dialogs.status("recovered the autosaved work: save it", 8000)
            return True
        return False
