"""Undo and redo reach the document's history from a focused field (a spin box of a panel, a
parameter's editor), unless the field has an edit of its own to undo: Qt offers Ctrl+Z to a
line edit first, and a field that has nothing to undo would swallow it."""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject
from PySide6.QtGui import QKeySequence
from PySide6.QtWidgets import QAbstractSpinBox, QApplication, QLineEdit


def _line_edit(widget) -> QLineEdit | None:
    if isinstance(widget, QLineEdit):
        return widget
    if isinstance(widget, QAbstractSpinBox):
        return widget.findChild(QLineEdit)
    return None


class HistoryKeys(QObject):
    """An application event filter: a focused field that cannot undo (redo) lets the window's
    Undo (Redo) shortcut have the key."""

    def eventFilter(self, obj, event) -> bool:
        if event.type() != QEvent.Type.ShortcutOverride:
            return False
        edit = _line_edit(QApplication.focusWidget())
        if edit is None:
            return False
        if event.matches(QKeySequence.StandardKey.Undo):
            return not edit.isUndoAvailable()  # handled here: the shortcut is not overridden
        if event.matches(QKeySequence.StandardKey.Redo):
            return not edit.isRedoAvailable()
        return False
