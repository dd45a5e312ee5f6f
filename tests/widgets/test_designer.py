"""The designer in a real window under Xvfb: drive the controls, check model and image."""

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt

from app.designer import DesignerWindow
from app.scenes import get_scene
from tests.conftest import coverage

pytestmark = pytest.mark.gui


@pytest.fixture
def window(qtbot):
    scene = get_scene("patch-grid")
    scene = type(scene)(**{**scene.__dict__, "params": scene.params.replace(blade_count=600)})
    win = DesignerWindow(scene)
    qtbot.addWidget(win)
    win.resize(720, 480)
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


def spin_box(win, name):
    for item in win.panel.tree.listAllItems():
        if getattr(item, "param", None) is not None and item.param.name() == name:
            return item.widget
    raise LookupError(name)


def test_blade_count_edit_regenerates_patch_and_changes_image(window, qtbot):
    before = coverage(grab(window))
    box = spin_box(window, "blade_count")
    old_patch = window.patch
    box.setValue(3000)
    qtbot.waitUntil(lambda: window.design.params.blade_count == 3000, timeout=5000)
    qtbot.waitUntil(
        lambda: window.patch is not old_patch and window.patch.blade_count == 3000, timeout=20000
    )
    after = coverage(grab(window))
    assert after > before + 0.05
    assert "blades" in window.status.text()
    # undo restores the old parameters and regenerates
    window.undo_stack.undo()
    qtbot.waitUntil(lambda: window.patch.blade_count == 600, timeout=20000)
    assert window.panel.param("blade_count").value() == 600


def test_out_of_range_edit_is_refused_with_message(window, qtbot):
    window.panel.param("length_min").setValue(0.9)  # above length_max
    assert "length_min" in window.panel.message.text()
    assert window.design.params.length_min == pytest.approx(0.18)


def test_mouse_drag_orbits_camera(window, qtbot):
    vp = window.viewport
    yaw, eye = vp.camera.yaw, vp.camera.eye.copy()
    before = grab(window)
    centre = QPoint(vp.width() // 2, vp.height() // 2)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, pos=centre)
    qtbot.mouseMove(vp, centre + QPoint(80, 10))
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, pos=centre + QPoint(80, 10))
    assert vp.camera.yaw != yaw
    assert not np.allclose(vp.camera.eye, eye)
    after = grab(window)
    assert np.mean(np.any(before != after, axis=-1)) > 0.1


def test_density_slider_thins_grass(window, qtbot):
    before = coverage(grab(window))
    window.panel.param("density").setValue(0.2)
    assert window.design.density == pytest.approx(0.2)
    assert coverage(grab(window)) < 0.8 * before
