"""The narrow interfaces the designer's controllers talk to instead of the window: questions
and messages for the person (`Dialogs`), the undo history's saved mark (`History`) and stored
settings (`Settings`). The window passes Qt implementations (app/qt_dialogs.py, QUndoStack,
QSettings); tests pass mocks made from these specs, without Qt."""

from __future__ import annotations

from typing import Any, Protocol

SAVE, DISCARD, CANCEL = "save", "discard", "cancel"


class Dialogs(Protocol):
    def save_path(self, title: str, suggested: str, filters: str) -> str | None:
        """A file name to write, or None when the person cancelled."""
        ...

    def open_path(self, title: str, filters: str) -> str | None:
        """A file to read, or None when the person cancelled."""
        ...

    def ask_unsaved(self, text: str) -> str:
        """SAVE, DISCARD or CANCEL."""
        ...

    def ask_yes(self, text: str) -> bool: ...

    def warn(self, text: str) -> None: ...

    def status(self, text: str, ms: int = 5000) -> None: ...

    def ask_text(self, title: str, label: str) -> str | None:
        """One line of text, or None when the person cancelled."""
        ...

    def ask_number(
        self, title: str, label: str, value: float, low: float, high: float, unit: str = ""
    ) -> float | None:
        """A number in low … high, or None when the person cancelled."""
        ...

    def raw_height_options(self, name: str, size: int) -> dict | None:
        """Width, height, byte order and range of a raw height file, or None (cancelled)."""
        ...

    def species_rules(self, names: list[str], derived: list[tuple], species: Any) -> Any:
        """Each kind's species rule (the grass types', then the soil's) as the person set them
        from `species` (core/species.py Species; `derived` the references the design gives, in
        HSV), or None (cancelled)."""
        ...


class History(Protocol):
    def isClean(self) -> bool: ...

    def setClean(self) -> None: ...

    def resetClean(self) -> None: ...


class Settings(Protocol):
    def value(self, key: str, default: Any = None) -> Any: ...

    def setValue(self, key: str, value: Any) -> None: ...
