"""The docks as a person resizes and uses them: the Map grows with its dock, recording does
not widen the Timings dock, the bookmark dialog shows its whole title."""

import pytest
from PySide6.QtCore import Qt, QTimer

from core.stats import FrameStats

pytestmark = pytest.mark.gui


def test_the_map_grows_when_its_dock_is_made_taller(window, qtbot):
    window.resize(1300, 640)  # room for the dock to grow into
    window.map_dock.raise_()
    qtbot.waitUntil(window.map_view.isVisible)
    before = window.map_view.height()
    window.resizeDocks([window.patch_dock, window.map_dock], [10, 90], Qt.Orientation.Vertical)
    # the panels above scroll instead of holding the height
    qtbot.waitUntil(lambda: window.map_view.height() > before + 150)
    # and the map fills its view: as wide as the dock
    qtbot.waitUntil(
        lambda: window.map_view.image.sceneBoundingRect().height() >= 0.8 * window.map_view.width()
    )


def test_recording_frames_leaves_the_timings_dock_as_wide_as_it_was(window, qtbot):
    window.profile_dock.raise_()
    panel = window.profile_panel
    qtbot.waitUntil(panel.isVisible)
    width = window.profile_dock.width()
    panel.record_button.setChecked(True)
    for _ in range(12345):
        panel.recording.append(FrameStats())
    panel.add(FrameStats(t_a_ms=10.0))
    assert panel.label.text() == "recording: 12346 frames"
    qtbot.wait(50)
    assert window.profile_dock.width() == width
    panel.recording = []
    window.profile_panel.recorded.disconnect()  # no save dialog for this test's frames
    panel.record_button.setChecked(False)


def test_the_bookmark_dialog_is_wide_enough_for_its_title(window, qtbot):
    from PySide6.QtWidgets import QApplication, QDialog, QLineEdit

    seen = {}

    def answer():
        dialog = next(
            w for w in QApplication.topLevelWidgets() if isinstance(w, QDialog) and w.isVisible()
        )
        seen["title"], seen["width"] = dialog.windowTitle(), dialog.width()
        seen["needed"] = dialog.fontMetrics().horizontalAdvance(dialog.windowTitle())
        dialog.findChild(QLineEdit).setText("from the dialog")
        dialog.accept()

    QTimer.singleShot(200, answer)
    assert window.bookmark_view()
    assert seen["title"] == "Bookmark this view" and seen["width"] >= seen["needed"] + 150
    assert "from the dialog" in window.document.cameras
