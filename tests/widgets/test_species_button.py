"""Paint → Grass types from colours…: a terrain colour image places the grass through the
panel's button, as one undo step."""

import numpy as np
import pytest
from PIL import Image
from PySide6.QtCore import Qt

from core.patch import generate_patch

pytestmark = pytest.mark.gui


def test_the_colour_image_places_the_grass_and_undo_takes_it_back(
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
    before = document.maps.layer("density").copy()
    steps = window.undo_stack.count()

    qtbot.mouseClick(window.paint_panel.species_button, Qt.MouseButton.LeftButton)
    density = document.maps.layer("density")[..., document.grass_types[0].channel]
    assert density[:, 4 : w // 2 - 4].mean() > 0.9  # the grass's own colour: grass
    assert density[:, w // 2 + 4 : -4].max() < 0.05  # the soil's colour: bare
    assert window.undo_stack.count() == steps + 1
    assert window.undo_stack.text(steps) == "grass types from colours.png"
    window.undo_stack.undo()
    assert np.array_equal(document.maps.layer("density"), before)
