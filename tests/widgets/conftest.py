"""A designer window under Xvfb for the widget tests, and helpers to read its image."""

import numpy as np
import pytest
from PySide6.QtCore import QSettings

from app.designer import DesignerWindow
from app.scenes import get_scene


@pytest.fixture(autouse=True)
def no_leaked_windows(request):
    """A test leaves no window of its own open (napari / ndv do the same): dialogs it opened
    are closed, windows it made are closed."""
    if "qapp" not in request.fixturenames and "qtbot" not in request.fixturenames:
        yield
        return
    from PySide6.QtWidgets import QApplication

    before = set(QApplication.topLevelWidgets())
    yield
    leaked = [
        w
        for w in QApplication.topLevelWidgets()
        if w not in before and w.isWindow() and w.isVisible()
    ]
    assert not leaked, f"windows left open: {[type(w).__name__ for w in leaked]}"


@pytest.fixture
def window(qtbot, tmp_path, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    QSettings.setPath(QSettings.Format.NativeFormat, QSettings.Scope.UserScope, str(tmp_path))
    # closing with unsaved edits asks; a test answers "discard" unless it says otherwise
    monkeypatch.setattr(QMessageBox, "question", lambda *a, **k: QMessageBox.StandardButton.Discard)
    scene = get_scene("patch-grid")
    scene = type(scene)(**{**scene.__dict__, "params": scene.params.replace(blade_count=600)})
    win = DesignerWindow(scene)
    win.autosave.directory = tmp_path / "autosave"
    qtbot.addWidget(win)
    win.resize(1300, 640)
    win.show()
    qtbot.waitExposed(win)
    qtbot.waitUntil(lambda: win.patch is not None, timeout=20000)
    yield win
    win.close()


def grab(win) -> np.ndarray:
    img = win.viewport.grabFramebuffer().convertToFormat(
        win.viewport.grabFramebuffer().Format.Format_RGB888
    )
    ptr = img.constBits()
    arr = np.frombuffer(ptr, dtype=np.uint8, count=img.sizeInBytes())
    return (
        arr.reshape(img.height(), img.bytesPerLine())[:, : img.width() * 3]
        .reshape(img.height(), img.width(), 3)
        .copy()
    )


def wait_for_slices(window, qtbot):
    qtbot.waitUntil(
        lambda: not window.viewport.slices.busy and not window.viewport.pipeline.needs_slices,
        timeout=30000,
    )
