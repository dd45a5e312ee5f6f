"""The designer's project actions: new from a built-in scene, open, save, save as, recent
files, and the question about unsaved changes. Files go through core/project_file.py.

Qt-free: the person is asked through `Dialogs`, the saved mark is the undo history's
(`History`), recent files live in `Settings` (app/dialogs.py)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from app.dialogs import DISCARD, SAVE, Dialogs, History, Settings
from core.document import Document
from core.project_file import SUFFIX, ProjectError, load_project, save_project

RECENT = 8
FILTER = f"Sward project (*{SUFFIX})"


class ProjectActions:
    def __init__(
        self,
        document: Callable[[], Document],
        open_document: Callable[[Document], None],
        history: History,
        dialogs: Dialogs,
        settings: Settings,
        recent_changed: Callable[[], None] = lambda: None,
    ) -> None:
        """`document()` is the open project; `open_document(doc)` shows another one."""
        self.document = document
        self.open_document = open_document
        self.history = history
        self.dialogs = dialogs
        self.settings = settings
        self.recent_changed = recent_changed
        # after a save: the autosave holds nothing newer than the file any more (app/autosave.py)
        self.saved: Callable[[], None] = lambda: None
        self.titled: Callable[[str], None] = lambda name: None  # the window shows the file's name
        self.path: Path | None = None

    def save(self) -> bool:
        return self.save_as(self.path) if self.path is not None else self.save_as()

    def save_as(self, path: Path | str | None = None) -> bool:
        if path is None:
            path = self.dialogs.save_path("Save project", f"{self.document().name}{SUFFIX}", FILTER)
            if not path:
                return False
        path = Path(path)
        try:
            save_project(path, self.document())
        except ProjectError as exc:
            self.dialogs.warn(str(exc))
            return False
        self.path = path
        self.titled(path.name)
        self.history.setClean()
        self.saved()
        self._remember(path)
        self.dialogs.status(f"saved {path}", 4000)
        return True

    def open(self, path: Path | str | None = None) -> bool:
        """Open a project; a file that cannot be read leaves the open one as it was."""
        if not self.confirm_discard():
            return False
        if path is None:
            path = self.dialogs.open_path("Open project", FILTER)
            if not path:
                return False
        path = Path(path)
        try:
            document = load_project(path)
        except ProjectError as exc:
            self.dialogs.warn(str(exc))
            return False
        self.open_document(document)
        self.path = path
        self.titled(path.name)
        self._remember(path)
        return True

    def new(self, document: Document) -> bool:
        """Start from a built-in scene (not yet a file)."""
        if not self.confirm_discard():
            return False
        self.open_document(document)
        self.path = None
        return True

    def confirm_discard(self) -> bool:
        """True when there are no unsaved changes, or the person saved or dropped them."""
        if self.history.isClean():
            return True
        answer = self.dialogs.ask_unsaved("The project has unsaved changes. Save them first?")
        if answer == SAVE:
            return self.save()
        return answer == DISCARD

    # -- recent files ------------------------------------------------------------------------
    def recent(self) -> list[str]:
        value = self.settings.value("recent", [])
        return [value] if isinstance(value, str) else list(value or [])

    def _remember(self, path: Path) -> None:
        text = str(path.resolve())
        files = [text] + [p for p in self.recent() if p != text]
        self.settings.setValue("recent", files[:RECENT])
        self.recent_changed()
