"""Painting, the LOD editor and the timing overlay in a real window, driven by mouse and keys."""

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QColor
from PySide6.QtTest import QTest

from tests.conftest import grass_mask
from tests.widgets.conftest import grab, wait_for_slices

pytestmark = pytest.mark.gui


def top_view(window, qtbot):
    """Look straight down on the 8 × 8 cells, geometry everywhere (the brush's footprint is
    then where it was painted), with the paint tool on."""
    window.viewport.set_camera(window.document.camera("top"))
    window.mode_actions["geometry"].trigger()
    window.paint_action.trigger()
    assert window.viewport.tool == "paint"
    wait_for_slices(window, qtbot)
    return grab(window)


def drag(qtbot, widget, points, modifier=Qt.KeyboardModifier.NoModifier):
    QTest.mousePress(widget, Qt.MouseButton.LeftButton, modifier, points[0])
    for p in points[1:]:
        QTest.mouseMove(widget, p)
        qtbot.wait(10)
    QTest.mouseRelease(widget, Qt.MouseButton.LeftButton, modifier, points[-1])
    # while the cursor moves frames are drafts (no MSAA); compare full-quality frames
    if hasattr(widget, "settling"):
        qtbot.waitUntil(lambda: not widget.settling, timeout=60000)


def stroke_line(vp):
    """A horizontal stroke across the middle of the viewport, from 30 % to 70 % of its width."""
    y = vp.height() // 2
    return [QPoint(int(vp.width() * f), y) for f in np.linspace(0.3, 0.7, 12)], y


def test_a_stroke_bares_the_grass_under_it_only_and_undo_redo_are_exact(window, qtbot):
    vp = window.viewport
    before_image = top_view(window, qtbot)
    maps_before = window.document.maps.stack.copy()
    panel = window.paint_panel
    panel.select("density", 0)
    panel.size_box.setValue(16)
    panel.strength_box.setValue(1.0)
    panel.value_box.setValue(0.0)
    points, y = stroke_line(vp)
    drag(qtbot, vp, points)
    assert window.undo_stack.count() == 1 and window.undo_stack.canUndo()
    painted = window.document.maps.stack.copy()
    changed = np.any(painted != maps_before, axis=-1)
    assert changed[0].any() and not changed[1:].any()  # only the density map
    vp.update()
    after_image = grab(window)

    grass_before, grass_after = grass_mask(before_image), grass_mask(after_image)
    x0, x1 = int(vp.width() * 0.36), int(vp.width() * 0.64)
    under = (slice(y - 4, y + 5), slice(x0, x1))
    assert grass_before[under].mean() > 0.3
    assert grass_after[under].mean() < 0.5 * grass_before[under].mean()
    far = np.ones(grass_before.shape, bool)
    far[y - 60 : y + 61, :] = False  # a brush radius (~15 px) plus leaning blades away
    assert abs(grass_after[far].mean() - grass_before[far].mean()) < 0.01

    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.wait(500)  # frames still due from the stroke are drawn
    # Ctrl+Z: the viewport draws the undone map at once, with no mouse move to prompt it
    with qtbot.waitSignal(vp.frame_rendered, timeout=20000):
        QTest.keyClick(vp, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert np.array_equal(window.document.maps.stack, maps_before)
    QTest.keyClick(
        vp, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier
    )
    assert np.array_equal(window.document.maps.stack, painted)


def test_painting_adds_grass_by_default_and_ctrl_erases_it(window, qtbot):
    vp = window.viewport
    top_view(window, qtbot)
    panel = window.paint_panel
    panel.select("density", 0)
    assert panel.mode_box.currentText() == "paint" and panel.value_box.value() == 1.0
    panel.strength_box.setValue(1.0)
    panel.falloff_box.setCurrentText("constant")
    points, _ = stroke_line(vp)
    drag(qtbot, vp, points, Qt.KeyboardModifier.ControlModifier)  # Ctrl: erase the grass
    assert window.document.maps.layer("density")[..., 0].min() == 0.0
    panel.size_box.setValue(40)  # wider than the first stroke, so it paints all of it back
    drag(qtbot, vp, points)  # a plain stroke with the default brush adds grass
    assert window.document.maps.layer("density")[..., 0].min() == 1.0
    assert window.undo_stack.count() == 2


def test_painting_colour_with_high_alpha_shows_that_colour(window, qtbot):
    vp = window.viewport
    before = top_view(window, qtbot)
    panel = window.paint_panel
    panel.select("color")
    panel.color = QColor(230, 40, 220)  # magenta: no grass is that colour
    panel.alpha_box.setValue(1.0)
    panel.strength_box.setValue(1.0)
    panel.size_box.setValue(40)
    points, y = stroke_line(vp)
    drag(qtbot, vp, points)
    vp.update()
    after = grab(window)
    x0, x1 = int(vp.width() * 0.4), int(vp.width() * 0.6)
    region = (slice(y - 5, y + 6), slice(x0, x1))

    def magenta(image):
        r, g, b = (image[..., c].astype(float) for c in range(3))
        return (r > 1.3 * g) & (b > 1.3 * g)

    assert magenta(before)[region].mean() < 0.05
    assert magenta(after)[region].mean() > 0.5
    assert magenta(after)[: y - 80].mean() < 0.05  # nowhere else


def test_eyedropper_takes_the_value_under_the_cursor(window, qtbot):
    vp = window.viewport
    top_view(window, qtbot)
    window.document.maps.fill("ambient", 0.35)
    panel = window.paint_panel
    panel.select("ambient")
    panel.value_box.setValue(1.0)
    window.painter.start_eyedropper()
    QTest.mouseClick(vp, Qt.MouseButton.LeftButton, pos=QPoint(vp.width() // 2, vp.height() // 2))
    assert panel.value_box.value() == pytest.approx(0.35)
    assert window.undo_stack.count() == 0  # picking paints nothing


def test_editing_a_lod_end_changes_the_counts_in_the_overlay(window, qtbot):
    vp = window.viewport
    vp.set_camera(window.document.camera("grazing"))
    window.timings_action.trigger()
    assert window.overlay.isVisible()
    wait_for_slices(window, qtbot)
    before = vp.last_stats
    assert before.c_v > 0 and not before.draft
    panel = window.lod_panel
    panel.end_box(0).setValue(5.5)  # geometry to 5.5 instead of 3.5 + 0.75
    assert window.document.lod(0).levels[0].end == 5.5
    wait_for_slices(window, qtbot)  # the full-quality frame of the new levels
    after = vp.last_stats
    assert after.c_g > before.c_g
    text = window.overlay.text()
    row = next(line for line in text.splitlines() if line.startswith("c_g"))
    assert float(row.split()[3]) == after.c_g  # max over the last frames: the new count
    assert panel.table.item(0, 5).text() == f"{after.c_g:,}"
    window.undo_stack.undo()
    assert window.document.lod(0).levels[0].end == 4.25


def test_distances_set_for_a_smaller_view_draw_more_geometry_and_undo(window, qtbot):
    vp = window.viewport
    vp.set_camera(window.document.camera("grazing"))
    wait_for_slices(window, qtbot)
    before = vp.last_stats
    box = window.lod_panel.view_box
    assert box.text() == "world units" and window.document.lod(0).view_height is None
    box.selectAll()
    QTest.keyClicks(box, "120")  # the distances hold for a view 120 px tall: this one is taller
    QTest.keyClick(box, Qt.Key.Key_Return)
    assert window.document.lod(0).view_height == 120
    wait_for_slices(window, qtbot)
    after = vp.last_stats
    assert after.c_g > before.c_g and not after.draft
    window.undo_stack.undo()
    assert window.document.lod(0).view_height is None
    assert box.text() == "world units"


def test_one_view_height_sets_every_grass_types_distances_in_one_undo_step(qtbot):
    from PySide6.QtGui import QUndoStack

    from app import commands
    from app.scenes import get_scene
    from widgets.lod_panel import LodPanel

    doc = get_scene("meadow").document()  # main grass and tall grass
    panel = LodPanel(doc)
    qtbot.addWidget(panel)
    stack = QUndoStack()
    panel.view_height_edited.connect(
        lambda configs, text: stack.push(commands.set_lods(doc, configs, text))
    )
    levels = [doc.lod(i).levels for i in range(2)]
    panel.view_box.selectAll()
    QTest.keyClicks(panel.view_box, "540")
    QTest.keyClick(panel.view_box, Qt.Key.Key_Return)
    assert [doc.lod(i).view_height for i in range(2)] == [540.0, 540.0]
    assert [doc.lod(i).levels for i in range(2)] == levels  # the distances as they were set
    assert stack.count() == 1 and "540 px" in stack.undoText()
    panel.view_box.selectAll()
    QTest.keyClicks(panel.view_box, "9")  # below 16 pixels: refused with the rule
    QTest.keyClick(panel.view_box, Qt.Key.Key_Return)
    assert "16" in panel.message.text() and stack.count() == 1
    qtbot.waitUntil(lambda: panel.view_box.value() == 540)
    stack.undo()
    assert [doc.lod(i).view_height for i in range(2)] == [None, None]
    assert panel.view_box.text() == "world units"


def test_an_impossible_lod_edit_is_refused_with_the_reason(window, qtbot):
    panel = window.lod_panel
    before = window.document.lod(0)
    panel.end_box(0).setValue(50.0)  # past the volume level's end
    assert window.document.lod(0) == before
    assert "must end after the geometry zone" in panel.message.text()
    qtbot.waitUntil(lambda: panel.end_box(0).value() == before.levels[0].end)


def test_a_broken_map_file_gives_one_message_and_keeps_the_maps(window, tmp_path, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    messages = []
    monkeypatch.setattr(QMessageBox, "warning", lambda parent, title, text: messages.append(text))
    window.paint_panel.select("density", 0)
    before = window.document.maps.stack.copy()
    bad = tmp_path / "paths.png"
    bad.write_bytes(b"\x89PNG\r\n\x1a\n not really")
    assert not window.map_files.import_map(bad)
    raw = tmp_path / "terrain.r16"
    raw.write_bytes(b"\x00" * 1000)
    raw_size = {"width": 64, "height": 64, "big_endian": False, "low": 0.0, "high": 1.0}
    assert not window.map_files.import_map(raw, raw=raw_size)
    assert len(messages) == 2
    assert "paths.png" in messages[0] and "terrain.r16" in messages[1]
    assert np.array_equal(window.document.maps.stack, before)
    assert window.undo_stack.count() == 0


def test_imported_maps_are_resampled_and_undoable_and_export_round_trips(window, qtbot, tmp_path):
    from PIL import Image

    window.paint_panel.select("height")
    ramp = (np.linspace(0, 65535, 512)[None, :].repeat(100, axis=0)).astype(np.uint16)
    Image.fromarray(ramp).save(tmp_path / "ramp.png")  # 16-bit, 512 × 100
    before = window.document.maps.stack.copy()
    assert window.map_files.import_map(tmp_path / "ramp.png")
    assert "resampled" in window.statusBar().currentMessage()
    # shown where a person sees it: in place of the frame's figures, not squeezed beside them
    qtbot.waitUntil(lambda: not window.status.isVisible(), timeout=2000)
    height = window.document.maps.layer("height")[..., 0]
    assert height.shape == (256, 256) and np.all(np.diff(height[128, 8:-8]) > 0)
    assert window.map_files.export_map(tmp_path / "out.png")
    with Image.open(tmp_path / "out.png") as exported:
        assert exported.mode.startswith("I") and exported.size == (256, 256)
    window.undo_stack.undo()
    assert np.array_equal(window.document.maps.stack, before)


def test_painting_in_the_2d_map_view_changes_the_map_and_its_image(window, qtbot):
    from PySide6.QtCore import QPointF

    window.map_dock.show()
    window.map_dock.raise_()
    view = window.map_view
    qtbot.waitUntil(lambda: view.isVisible())
    panel = window.paint_panel
    panel.select("density", 0)
    panel.strength_box.setValue(1.0)
    panel.value_box.setValue(0.0)
    panel.size_box.setValue(20)
    qtbot.wait(50)
    view.box.autoRange(padding=0.0)

    def at(x, y):
        scene = view.box.mapViewToScene(QPointF(x, y))
        return view.plot.mapFromScene(scene)

    points = [at(x, 128.0) for x in np.linspace(60.0, 200.0, 10)]
    drag(qtbot, view.plot.viewport(), points)
    density = window.document.maps.layer("density")[..., 0]
    assert density[128, 80:180].max() < 0.05  # under the stroke
    assert density[:100].min() == 1.0 and density[160:].min() == 1.0  # nowhere else
    qtbot.waitUntil(lambda: view.displayed()[128, 120] < 0.05)
    assert window.undo_stack.count() == 1


def test_recorded_frames_are_saved_as_csv(window, qtbot, tmp_path, monkeypatch):
    from PySide6.QtWidgets import QFileDialog

    out = tmp_path / "session.csv"
    monkeypatch.setattr(QFileDialog, "getSaveFileName", lambda *a, **k: (str(out), "CSV"))
    panel = window.profile_panel
    window.profile_dock.show()
    window.profile_dock.raise_()
    qtbot.mouseClick(panel.record_button, Qt.MouseButton.LeftButton)
    assert panel.recording == []
    qtbot.mouseClick(panel.continuous_box, Qt.MouseButton.LeftButton)  # frame after frame
    qtbot.waitUntil(lambda: len(panel.recording) >= 3, timeout=30000)
    qtbot.mouseClick(panel.continuous_box, Qt.MouseButton.LeftButton)
    qtbot.mouseClick(panel.record_button, Qt.MouseButton.LeftButton)
    rows = out.read_text().splitlines()
    assert rows[0].startswith("frame,t_a_ms") and len(rows) >= 4
    assert all(float(r.split(",")[1]) > 0 for r in rows[1:])  # every frame has its time
    curve_x, _ = panel.curves["t_g_ms"].getData()
    assert curve_x is not None and len(curve_x) >= 3  # the live plot follows the frames


def test_painting_height_raises_the_ground_and_the_terrain_follows(window, qtbot):
    import dataclasses

    from app.scenes import get_scene

    hilly = dataclasses.replace(
        get_scene("patch-grid"), height_scale=1.0, height_map=lambda w, h: np.zeros((h, w))
    )
    window.open_document(hilly.document())
    vp = window.viewport
    top_view(window, qtbot)
    assert vp.renderer_facts()["terrain_top"] < 0.01
    panel = window.paint_panel
    panel.select("height")
    assert "flat" not in panel.message.text()
    panel.value_box.setValue(1.0)
    panel.strength_box.setValue(1.0)
    panel.size_box.setValue(40)
    points, _ = stroke_line(vp)
    drag(qtbot, vp, points)
    assert window.document.maps.layer("height").max() > 0.9
    # the quadtree's bounds follow the painted ground (after the stroke, debounced)
    qtbot.waitUntil(lambda: vp.renderer_facts()["terrain_top"] > 0.9, timeout=10000)
    window.undo_stack.undo()
    qtbot.waitUntil(lambda: vp.renderer_facts()["terrain_top"] < 0.01, timeout=10000)


def test_each_map_keeps_its_own_brush(window, qtbot):
    """A height target of 0.3 and a small brush stay the height map's: the density map keeps
    what it was painted with, and each comes back when its map is chosen again."""
    panel = window.paint_panel
    panel.select("density", 0)
    density = (panel.value_box.value(), panel.size_box.value(), panel.strength_box.value())
    panel.select("height")
    panel.value_box.setValue(0.3)
    panel.size_box.setValue(7)
    panel.strength_box.setValue(0.2)
    panel.select("density", 0)
    assert (panel.value_box.value(), panel.size_box.value(), panel.strength_box.value()) == density
    assert panel.brush().value == (density[0],)
    panel.select("height")
    assert (panel.value_box.value(), panel.size_box.value()) == (pytest.approx(0.3), 7)
    assert panel.brush().strength == pytest.approx(0.2)
    assert window.viewport.brush_size == 7  # the outline follows the map's brush


def test_the_painting_shortcuts_people_know(window, qtbot):
    vp = window.viewport
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    vp.setFocus()
    panel = window.paint_panel
    size, strength = panel.size_box.value(), panel.strength_box.value()
    QTest.keyClick(vp, Qt.Key.Key_B)
    assert vp.tool == "paint" and window.paint_action.isChecked()
    QTest.keyClick(vp, Qt.Key.Key_BracketRight)
    assert panel.size_box.value() > size and vp.brush_size == panel.size_box.value()
    QTest.keyClick(vp, Qt.Key.Key_BracketLeft)
    QTest.keyClick(vp, Qt.Key.Key_BracketLeft)
    assert panel.size_box.value() < size
    QTest.keyClick(vp, Qt.Key.Key_Minus)
    assert panel.strength_box.value() == pytest.approx(strength - 0.1)
    QTest.keyClick(vp, Qt.Key.Key_Equal)
    assert panel.strength_box.value() == pytest.approx(strength)
    QTest.keyClick(vp, Qt.Key.Key_I)
    assert window.painter.eyedropper
    QTest.keyClick(vp, Qt.Key.Key_Escape)  # drops the pick first, the tool stays
    assert not window.painter.eyedropper and vp.tool == "paint"
    QTest.keyClick(vp, Qt.Key.Key_P)
    assert window.overlay.isVisible()
    QTest.keyClick(vp, Qt.Key.Key_Escape)
    assert vp.tool == "camera" and not window.paint_action.isChecked()


def test_the_timings_plot_shows_frames_drawn_while_its_dock_was_closed(window, qtbot):
    """Frames drawn while the Timings dock is closed are plotted as soon as it is opened
    again (View menu), not from the next frame on; the frame axis spans the frames the plot
    holds, not pyqtgraph's -0.5 … 0.5."""
    from widgets.profile_view import PLOT_FRAMES

    panel = window.profile_panel
    window.profile_dock.toggleViewAction().trigger()  # View → Timings: closed
    qtbot.waitUntil(lambda: not panel.isVisible())
    seen = len(panel.history)
    panel.total.setData([], [])  # the plot as if nothing had been drawn yet
    window.viewport.request_frame(draft=False)  # as any edit does
    qtbot.waitUntil(lambda: len(panel.history) > seen, timeout=60_000)
    hidden_x, _ = panel.total.getData()
    assert hidden_x is None or len(hidden_x) == 0  # closed: not drawn
    window.profile_dock.toggleViewAction().trigger()  # opened again
    qtbot.waitUntil(panel.isVisible)
    x, y = panel.total.getData()
    assert x is not None and len(x) == len(panel.history)
    assert list(y) == [s.t_a_ms for s in panel.history]
    low, high = panel.plot.getViewBox().viewRange()[0]
    assert low <= x[0] and high >= x[-1] and high - low >= PLOT_FRAMES * 0.9
