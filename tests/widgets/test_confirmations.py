"""A person who writes a file is told where it went: an exported map, a saved image, the
recorded timings (each through its real action, the file dialog answered)."""

import pytest

from core.stats import FrameStats

pytestmark = pytest.mark.gui


def test_each_file_written_is_confirmed_in_the_status_line(window, qtbot, tmp_path, monkeypatch):
    answers = iter([tmp_path / "height.png", tmp_path / "view.png", tmp_path / "times.csv"])
    monkeypatch.setattr(window.dialogs, "save_path", lambda *a: str(next(answers)))
    monkeypatch.setattr(
        "app.image_output.QInputDialog.getItem", lambda _w, _t, _l, items, *a: (items[0], True)
    )
    status = window.statusBar()
    window.paint_panel.select("height")
    window.paint_panel.export_button.click()
    assert (tmp_path / "height.png").is_file()
    assert status.currentMessage() == f"exported height to {tmp_path / 'height.png'}"
    from PySide6.QtGui import QAction

    next(a for a in window.findChildren(QAction) if a.text() == "Save &image…").trigger()
    assert (tmp_path / "view.png").is_file()
    assert status.currentMessage().startswith("saved ") and "view.png" in status.currentMessage()
    window.profile_panel.record_button.setChecked(True)
    window.profile_panel.add(FrameStats(t_a_ms=12.0))
    window.profile_panel.record_button.setChecked(False)  # "Stop and save…"
    assert (tmp_path / "times.csv").is_file()
    assert status.currentMessage() == f"wrote 1 frame to {tmp_path / 'times.csv'}"
