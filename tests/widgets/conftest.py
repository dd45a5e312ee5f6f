"""A designer window under Xvfb for the widget tests, and helpers to read its image."""

import os
import sys
import time

import numpy as np
import pytest
from PySide6.QtCore import QSettings

from app.designer import DesignerWindow
from app.scenes import get_scene

# Designer windows are closed after their test and never deleted: deleting one destroys its
# pyqtgraph parameter trees in C++, and a later object born at a freed address was seen to come
# back from shiboken as the dead tree item (a TypeError deep in a new window's SpinBox, once in
# a dozen runs). Deleted all at the end of the session they cost more time than the process's
# exit does, so they go with the process.
_windows: list = []


def keep(window):
    """Hold a designer window until the process ends (instead of qtbot.addWidget)."""
    _windows.append(window)
    return window


_exit_status = [0]


def pytest_sessionfinish(session, exitstatus):
    _exit_status[0] = int(exitstatus)


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config):
    """A run that made windows ends here, once pytest has reported and every plugin has
    finished: at the interpreter's exit Qt would tear down every kept window's widgets and
    native windows one by one, work that grows with the windows kept, for a process about to
    end anyway. Their render processes ended when the windows closed; Xvfb is stopped as its
    plugin would at exit, and the exit status is pytest's."""
    if not _windows:
        return
    import pytest_xvfb

    sys.stdout.flush()
    sys.stderr.flush()
    pytest_xvfb.shutdown_xvfb()
    os._exit(_exit_status[0])


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


# a small viewport beside the docks: a test's frames cost what its pixels cost on llvmpipe,
# and most tests need a picture, not a large one (those that need room make their own)
WINDOW_SIZE = (1000, 520)


@pytest.fixture
def window(qtbot, tmp_path, monkeypatch):
    """The designer as a person meets it: shown, its first frames still on their way (a test
    that needs a picture waits for it: grab, wait_full; one that edits first spares the
    render processes a full frame nobody looks at)."""
    from PySide6.QtWidgets import QMessageBox

    QSettings.setPath(QSettings.Format.NativeFormat, QSettings.Scope.UserScope, str(tmp_path))
    # closing with unsaved edits asks; a test answers "discard" unless it says otherwise
    monkeypatch.setattr(QMessageBox, "question", lambda *a, **k: QMessageBox.StandardButton.Discard)
    # a modal message nobody answers would hang the run: fail at once instead (tests that
    # expect a message replace this)
    monkeypatch.setattr(
        QMessageBox, "warning", lambda *a, **k: pytest.fail(f"unexpected message: {a[2]}")
    )
    scene = get_scene("patch-grid")
    scene = type(scene)(**{**scene.__dict__, "params": scene.params.replace(blade_count=600)})
    win = keep(DesignerWindow(scene.document()))
    win.autosave.directory = tmp_path / "autosave"
    win.resize(*WINDOW_SIZE)
    win.show()
    qtbot.waitExposed(win)
    yield win
    win.close()


def wait_full(win, timeout_s: float = 120.0) -> None:
    """Until a full-quality frame of the newest state is on screen (the render processes
    draw a draft first)."""
    from PySide6.QtWidgets import QApplication

    start = time.monotonic()
    while win.viewport.settling:
        QApplication.processEvents()
        time.sleep(0.005)
        if time.monotonic() - start > timeout_s:
            raise AssertionError("no full-quality frame of the newest state in time")


def grab(win) -> np.ndarray:
    """The full-quality frame of the newest state, (h, w, 3) uint8."""
    wait_full(win)
    return win.viewport.frame_image()


def wait_for_slices(window, qtbot):
    """The full-quality renderer converts slices before it draws: its frame has them all."""
    wait_full(window)


def field(tree, name: str):
    """The editing widget of the parameter `name` in a panel's ParameterTree."""
    for item in tree.listAllItems():
        if getattr(item, "param", None) is not None and item.param.name() == name:
            return item.widget
    raise LookupError(name)


def type_into(box, text: str) -> None:
    """Type into a parameter's spin box as a person does: select all, type, Enter."""
    from PySide6.QtCore import Qt
    from PySide6.QtTest import QTest

    box.setFocus()
    box.lineEdit().selectAll()
    QTest.keyClicks(box.lineEdit(), text)
    QTest.keyClick(box.lineEdit(), Qt.Key.Key_Return)
