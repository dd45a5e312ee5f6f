"""Paint dock → trampled grass: strokes in the Map dock lay the blades the way they go (or the
way the Direction box says), the viewport shows the grass laid over, and undo stands it up."""

import numpy as np
import pytest
from PySide6.QtCore import QPointF, Qt

from core.trample import decode
from tests.widgets.conftest import grab
from tests.widgets.test_painting import drag

pytestmark = pytest.mark.gui


def test_a_trample_stroke_lays_the_grass_along_it_and_undo_stands_it_up(window, qtbot):
    window.viewport.set_camera(window.document.camera("top"))
    window.mode_actions["geometry"].trigger()
    before = grab(window)
    window.map_dock.show()
    window.map_dock.raise_()
    view = window.map_view
    qtbot.waitUntil(lambda: view.isVisible())
    panel = window.paint_panel
    panel.layer_box.setCurrentIndex(panel.layer_box.findText("trampled grass"))
    assert panel.target == ("trample", None) and panel.way_row.isVisible()
    assert panel.along_box.isChecked() and not panel.direction_box.isEnabled()
    panel.value_box.selectAll()
    qtbot.keyClicks(panel.value_box, "0.6")
    panel.strength_box.setValue(1.0)
    panel.falloff_box.setCurrentText("constant")
    panel.size_box.setValue(24)
    view.box.autoRange(padding=0.0)

    def at(x, y):
        return view.plot.mapFromScene(view.box.mapViewToScene(QPointF(x, y)))

    # left to right along row 128: the blades lie along +x
    drag(qtbot, view.plot.viewport(), [at(x, 128.0) for x in np.linspace(40.0, 210.0, 12)])
    trample = window.document.maps.layer("trample")
    assert np.allclose(decode(trample[128, 80:180]), [0.6, 0.0], atol=0.01)
    assert np.all(trample[:100] == 0.5) and np.all(trample[160:] == 0.5)  # upright elsewhere
    qtbot.waitUntil(lambda: abs(view.displayed()[128, 120, 0] - 0.5) > 0.2)  # shown red
    laid = grab(window)
    rows = (np.abs(laid.astype(int) - before.astype(int)).max(axis=-1) > 24).mean(axis=1)
    assert rows.max() > 0.1, "the viewport shows the grass as it stood"
    assert (rows > 0.02).mean() < 0.2  # a band across the view: the stroke's

    # the direction box, the stroke's way off: the blades lie towards -z whichever way it goes
    qtbot.mouseClick(panel.along_box, Qt.MouseButton.LeftButton)
    assert panel.direction_box.isEnabled()
    panel.direction_box.selectAll()
    qtbot.keyClicks(panel.direction_box, "270")
    qtbot.keyClick(panel.direction_box, Qt.Key.Key_Return)
    drag(qtbot, view.plot.viewport(), [at(60.0, y) for y in np.linspace(20.0, 90.0, 8)])
    assert np.allclose(decode(trample[40:80, 60]), [0.0, -0.6], atol=0.01)
    assert window.undo_stack.count() == 2

    window.undo_stack.undo()
    window.undo_stack.undo()
    assert np.all(window.document.maps.layer("trample") == 0.5)
    upright = grab(window)
    assert np.abs(upright.astype(int) - before.astype(int)).max(axis=-1).mean() < 1.0
