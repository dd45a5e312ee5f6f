"""The Light dock's sun dial, driven with the mouse and keys in a real window."""

import numpy as np
import pytest
from PySide6.QtCore import QPointF, Qt
from PySide6.QtTest import QTest

from tests.widgets.conftest import field, grab, type_into

pytestmark = pytest.mark.gui


def test_dragging_the_sun_relights_the_view_while_the_mouse_is_held(window, qtbot):
    """The sun follows the mouse across the dial; the grass relights before the button is let
    go; the drag is one undo step; the dial's right is the picture's right."""
    window.light_dock.raise_()
    dial = window.light_panel.dial
    qtbot.waitExposed(dial)
    before = grab(window).astype(np.float32)
    start = dial.point_of(window.document.light.sun_elevation, window.document.light.sun_azimuth)
    centre, radius = dial._disk()
    end = QPointF(centre.x() + 0.7 * radius, centre.y())  # right of the centre, 27° up
    steps = [start + (end - start) * t for t in (0.25, 0.5, 0.75, 1.0)]
    QTest.mousePress(dial, Qt.MouseButton.LeftButton, pos=start.toPoint())
    for point in steps:
        QTest.mouseMove(dial, point.toPoint())
    light = window.document.light
    assert light.sun_elevation == pytest.approx(90.0 * 0.3, abs=1.0)
    right = window.viewport.camera.view()[0, :3]
    assert float(light.sun_direction @ right) > 0.5  # the sun now stands to the picture's right
    # the view relit by the new sun arrives while the button is still down
    assert window.viewport.renderer_facts(role="draft")["light"] == light
    after = grab(window).astype(np.float32)
    assert np.abs(after - before).mean() > 2.0
    QTest.mouseRelease(dial, Qt.MouseButton.LeftButton, pos=steps[-1].toPoint())
    assert window.light_panel.root.child("sun_elevation").value() == light.sun_elevation
    window.undo_stack.undo()
    assert window.document.light.sun_elevation == 50.0  # the whole drag, undone at once
    assert window.document.light.sun_azimuth == 135.0
    assert dial.elevation == 50.0 and dial.azimuth == 135.0


def test_the_dial_turns_with_the_view_and_steps_with_the_arrow_keys(window, qtbot):
    window.light_dock.raise_()
    dial = window.light_panel.dial
    sun = (window.document.light.sun_elevation, window.document.light.sun_azimuth)
    drawn = dial.point_of(*sun)
    window.viewport.camera.orbit(90.0, 0.0)
    window.viewport.camera_changed.emit()
    assert dial.point_of(*sun) != drawn  # the same sun, seen from another side
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    dial.setFocus()
    qtbot.waitUntil(dial.hasFocus)
    QTest.keyClick(dial, Qt.Key.Key_Up)
    assert window.document.light.sun_elevation == sun[0] + 1.0
    QTest.keyClick(dial, Qt.Key.Key_Left)
    assert window.document.light.sun_azimuth == (sun[1] + 5.0) % 360.0


def test_text_that_is_no_number_in_the_light_dock_gets_a_message(window, qtbot):
    panel = window.light_panel
    window.light_dock.raise_()
    box = field(panel.tree, "sun_azimuth")
    type_into(box, "north")
    assert "Sun azimuth: “north” is not a number" in panel.message.text()
    assert "°" in panel.message.text()  # it may be typed with its unit
    assert window.document.light.sun_azimuth == 135.0
    type_into(box, "90")
    qtbot.waitUntil(lambda: window.document.light.sun_azimuth == pytest.approx(90.0))
    assert panel.message.text() == ""


def test_blade_shadows_are_switched_on_and_weakened_in_the_light_dock(window, qtbot):
    """Light dock → Blade shadows: the ground between the blades darkens; Shadow strength
    weakens it; each is one undo step, and undo brings the unshadowed frame back."""
    panel = window.light_panel
    window.light_dock.raise_()
    window.viewport.set_camera(window.document.camera("top"))
    before = grab(window).astype(int)
    steps = window.undo_stack.count()
    box = field(panel.tree, "blade_shadows")
    box.setFocus()
    qtbot.keyClick(box, Qt.Key.Key_Space)  # as a person tabbing to it
    qtbot.waitUntil(lambda: window.document.light.blade_shadows)
    shadowed = grab(window).astype(int)
    darker = (before - shadowed).sum(axis=-1)
    assert (darker > 30).mean() > 0.01 and (darker < -30).mean() < 0.2 * (darker > 30).mean()
    type_into(field(panel.tree, "shadow_strength"), "0.2")
    qtbot.waitUntil(lambda: window.document.light.shadow_strength == pytest.approx(0.2))
    weaker = grab(window).astype(int)
    assert (before - weaker).sum() < 0.6 * darker.sum()
    assert window.undo_stack.count() == steps + 2
    window.undo_stack.undo()
    window.undo_stack.undo()
    assert not window.document.light.blade_shadows
    assert not field(panel.tree, "blade_shadows").isChecked()
    assert np.abs(grab(window).astype(int) - before).max() <= 2
