"""LOD zones dock → Tune…: the search runs in another process with a progress bar, its front
is plotted, a click on a point shows that setting, Apply is one undo step."""

import pytest
from PySide6.QtCore import Qt

pytestmark = pytest.mark.gui


def click_point(qtbot, dialog, index: int) -> None:
    """A left click on candidate `index`'s point in the plot, as a person's."""
    spot = next(s for s in dialog.points.points() if s.data() == index)
    scene = dialog.plot.getViewBox().mapViewToScene(spot.pos())
    qtbot.mouseClick(
        dialog.plot.viewport(), Qt.MouseButton.LeftButton, pos=dialog.plot.mapFromScene(scene)
    )


def test_tune_plots_the_front_shows_a_clicked_setting_and_applies_it_undoably(window, qtbot):
    window.lod_dock.raise_()
    original = window.document.lods
    qtbot.mouseClick(window.lod_panel.tune_button, Qt.MouseButton.LeftButton)
    job = window.tune_job
    dialog = job.dialog
    qtbot.waitExposed(dialog)
    assert dialog.chosen_cameras() == ["current view"]
    dialog.candidates_box.setValue(4)
    qtbot.mouseClick(dialog.start_button, Qt.MouseButton.LeftButton)
    assert dialog.cancel_button.isEnabled() and not dialog.start_button.isEnabled()
    qtbot.waitUntil(lambda: job.result is not None, timeout=180000)
    assert dialog.progress.value() == dialog.progress.maximum()
    assert len(dialog.points.points()) == len(job.result["candidates"]) >= 3
    other = next(
        i
        for i, c in enumerate(job.result["candidates"])
        if c["knobs"] != job.result["candidates"][0]["knobs"]
    )
    click_point(qtbot, dialog, other)
    assert job.result["chosen"] == other
    assert window.document.lods != original  # the viewport draws the clicked setting
    assert not window.undo_stack.canUndo()  # not an edit yet
    shown = window.document.lods
    qtbot.mouseClick(dialog.apply_button, Qt.MouseButton.LeftButton)
    assert window.document.lods == shown and window.undo_stack.count() == 1
    dialog.close()
    window.undo_stack.undo()
    assert window.document.lods == original


def test_closing_tune_without_apply_puts_the_zones_back(window, qtbot):
    original = window.document.lods
    window.tune_dialog()
    job = window.tune_job
    job.result = {
        "candidates": [
            {"knobs": {}, "cost_ms": 10.0, "flip_quarter": 0.05},
            {"knobs": {"near": 0.8}, "cost_ms": 8.0, "flip_quarter": 0.06},
        ],
        "front": [0, 1],
        "chosen": 0,
    }
    job.show_setting(1)
    assert window.document.lods != original
    job.dialog.close()
    assert window.document.lods == original and not window.undo_stack.canUndo()
