"""Paint → Grass types from colours…: the rules dialog, then a terrain colour image places the
grass through the panel's button; the rules are kept in the document, and both are one undo
step."""

import numpy as np
import pytest
from PIL import Image
from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QApplication

from core.patch import generate_patch
from widgets.species_dialog import SpeciesDialog

pytestmark = pytest.mark.gui


def test_the_rules_and_the_colour_image_place_the_grass_and_undo_takes_them_back(
    window, qtbot, tmp_path, monkeypatch
):
    document = window.document
    w, h = document.maps.size
    image = np.zeros((h, w, 3))
    image[:, : w // 2] = generate_patch(document.params(0)).vertices["color"].mean(axis=0)
    image[:, w // 2 :] = document.light.soil_color
    path = tmp_path / "colours.png"
    Image.fromarray(np.round(image * 255).astype(np.uint8)).save(path)
    monkeypatch.setattr(window.dialogs, "open_path", lambda *a: str(path))
    before, species_before = document.maps.layer("density").copy(), document.species
    steps = window.undo_stack.count()
    seen = {}

    def answer():
        dialog = QApplication.activeModalWidget()
        assert isinstance(dialog, SpeciesDialog)
        first, soil = dialog.rows[0], dialog.rows[-1]
        seen["rows"] = len(dialog.rows)
        # the soil's exponent up, typed as a person types it; every weight 0 blocks the dialog
        soil.exponent.selectAll()
        qtbot.keyClicks(soil.exponent, "8")
        for box in first.weights:
            box.selectAll()
            qtbot.keyClicks(box, "0")
        seen["blocked"] = not dialog.place_button.isEnabled()
        first.weights[0].selectAll()
        qtbot.keyClicks(first.weights[0], "2")
        qtbot.mouseClick(dialog.place_button, Qt.MouseButton.LeftButton)

    QTimer.singleShot(100, answer)
    qtbot.mouseClick(window.paint_panel.species_button, Qt.MouseButton.LeftButton)
    assert seen == {"rows": len(document.grass_types) + 1, "blocked": True}
    assert document.species.soil.exponent == 8.0
    assert document.species.kind(0).weights == (2.0, 0.0, 0.0)
    density = document.maps.layer("density")[..., document.grass_types[0].channel]
    assert density[:, 4 : w // 2 - 4].mean() > 0.9  # the grass's own colour: grass
    assert density[:, w // 2 + 4 : -4].max() < 0.05  # the soil's colour: bare
    assert window.undo_stack.count() == steps + 1
    assert window.undo_stack.text(steps) == "grass types from colours.png"
    window.undo_stack.undo()
    assert np.array_equal(document.maps.layer("density"), before)
    assert document.species == species_before


def test_a_cancelled_rules_dialog_changes_nothing(window, qtbot, monkeypatch):
    opened = []
    monkeypatch.setattr(window.dialogs, "open_path", lambda *a: opened.append(a))
    steps = window.undo_stack.count()
    QTimer.singleShot(100, lambda: QApplication.activeModalWidget().reject())
    qtbot.mouseClick(window.paint_panel.species_button, Qt.MouseButton.LeftButton)
    assert opened == [] and window.undo_stack.count() == steps
