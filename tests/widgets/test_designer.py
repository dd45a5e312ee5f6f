"""The designer in a real window under Xvfb: drive the controls, check model and image."""

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt

from render.protocol import SetOverlay
from tests.conftest import coverage
from tests.widgets.conftest import field, grab, keep, type_into, wait_for_slices

pytestmark = pytest.mark.gui


def spin_box(win, name):
    return field(win.panel.tree, name)


def test_blade_count_edit_regenerates_patch_and_changes_image(window, qtbot):
    before = coverage(grab(window))
    box = spin_box(window, "blade_count")
    box.setValue(3000)
    qtbot.waitUntil(lambda: window.document.params(0).blade_count == 3000, timeout=5000)
    after = coverage(grab(window))  # the full-quality frame made from the new patch
    assert after > before + 0.05
    assert "blades" in window.status.text()
    assert window.viewport.renderer_facts()["patch_params"][0].blade_count == 3000
    # undo restores the old parameters and regenerates
    window.undo_stack.undo()
    assert window.panel.param("blade_count").value() == 600
    assert coverage(grab(window)) == pytest.approx(before, abs=0.02)


def test_out_of_range_edit_is_refused_with_message(window, qtbot):
    window.panel.param("length_min").setValue(0.9)  # above length_max
    text = window.panel.message.text()
    assert "Length min" in text and "Length max" in text  # named as the panel names them
    assert "length_min" not in text and "length_max" not in text
    assert window.document.params(0).length_min == pytest.approx(0.18)


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
    assert window.document.density == pytest.approx(0.2)
    assert coverage(grab(window)) < 0.8 * before


def technique_shares(image):
    r, g, b = (image[..., c].astype(int) for c in range(3))
    return {
        "red": (r > 120) & (g < 0.5 * r) & (b < 0.5 * r),
        "yellow": (r > 120) & (g > 0.6 * r) & (b < 0.4 * r),
        "blue": (b > 120) & (r < 0.5 * b) & (g < 0.7 * b),
    }


def test_compare_mode_with_technique_colours_shows_three_columns(window, qtbot):
    wait_for_slices(window, qtbot)
    window.mode_actions["compare"].trigger()
    window.techniques_action.trigger()
    assert window.viewport.mode == "compare" and window.techniques_action.isChecked()
    wait_for_slices(window, qtbot)
    masks = technique_shares(grab(window))
    w = masks["red"].shape[1]
    for k, colour in enumerate(("red", "yellow", "blue")):
        column = masks[colour][:, k * w // 3 : (k + 1) * w // 3]
        assert column.mean() > 0.1, colour
    window.techniques_action.trigger()  # T again: back to shaded grass
    assert not any(m.mean() > 0.01 for m in technique_shares(grab(window)).values())


def test_slice_count_edit_reconverts_in_the_render_processes_and_undoes(window, qtbot):
    """The window's process only changes the document; the render processes convert (how
    long the window's thread is busy meanwhile: `sward bench --suite latency`)."""
    window.mode_actions["volume"].trigger()
    wait_for_slices(window, qtbot)
    assert window.viewport.renderer_facts()["volume_slices"] == 8
    window.panel.param("slices").setValue(2)
    assert window.document.slices.slices == 2
    wait_for_slices(window, qtbot)
    assert window.viewport.renderer_facts()["volume_slices"] == 2
    window.undo_stack.undo()
    assert window.panel.param("slices").value() == 8
    wait_for_slices(window, qtbot)
    assert window.viewport.renderer_facts()["volume_slices"] == 8


def test_opening_a_built_in_scene_replaces_terrain_cameras_and_patch(window, qtbot):
    from app.scenes import get_scene

    meadow = get_scene("meadow")
    window.open_document(meadow.document())
    assert window.windowTitle().startswith("Sward — meadow")
    assert [a.text() for a in window.camera_menu.actions()] == list(meadow.cameras)
    wait_for_slices(window, qtbot)
    stats = window.viewport.last_stats
    assert stats.c_g > 0 and stats.c_v > 0 and stats.c_i > 0  # the meadow's three LOD levels
    facts = window.viewport.renderer_facts()
    assert facts["height_scale"] == meadow.height_scale
    assert facts["patch_params"][0] == meadow.params
    assert not window.undo_stack.canUndo()


def test_project_saved_and_reopened_restores_the_parameters(window, qtbot, tmp_path, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    from core.lod_edit import set_field

    path = tmp_path / "mine.sward"
    window.panel.param("density").setValue(0.6)
    window.document.maps.write(
        "color", 0, 0, np.tile([0.9, 0.8, 0.1, 0.8], (128, 256, 1))
    )  # painted
    lod = set_field(window.document.lod(0), 0, "end", 4.5)
    window.lod_panel.lod_edited.emit(0, lod)
    assert window.isWindowModified()
    wait_for_slices(window, qtbot)
    saved_image = grab(window)
    assert window.projects.save_as(path)
    assert not window.isWindowModified()
    saved_params = window.document.params(0)
    window.panel.param("density").setValue(0.3)
    monkeypatch.setattr(QMessageBox, "question", lambda *a, **k: QMessageBox.StandardButton.Discard)
    camera = window.viewport.camera
    assert window.projects.open(path)
    assert window.document.density == pytest.approx(0.6)
    assert window.document.params(0) == saved_params
    assert window.document.lod(0) == lod
    assert str(path.resolve()) in window.projects.recent()
    assert [a.text() for a in window.recent_menu.actions()] == [str(path.resolve())]
    window.viewport.set_camera(camera)
    wait_for_slices(window, qtbot)
    image = grab(window)
    assert abs(coverage(image) - coverage(saved_image)) < 0.01
    assert np.abs(image.mean(axis=(0, 1)) - saved_image.mean(axis=(0, 1))).max() < 1.0


def test_a_corrupt_project_gives_a_message_and_keeps_the_open_one(window, tmp_path, monkeypatch):
    import os

    from PySide6.QtWidgets import QMessageBox

    from core.project_file import save_project
    from tests.project_files import project_parts, variant

    good = tmp_path / "good.sward"
    save_project(good, window.document)
    data, maps = project_parts(good)

    bad = [tmp_path / "broken.sward"]
    bad[0].write_bytes(b"PK\x03\x04 broken")
    change = {
        "nocolumns": lambda d: d["terrain"].update(columns=0),
        "cameras": lambda d: d.update(cameras=7),
    }
    bad += [variant(tmp_path / f"{name}.sward", data, maps, fn) for name, fn in change.items()]
    os.mkfifo(tmp_path / "pipe.sward")
    bad.append(tmp_path / "pipe.sward")
    messages = []
    monkeypatch.setattr(QMessageBox, "warning", lambda parent, title, text: messages.append(text))
    window.panel.param("density").setValue(0.35)  # unsaved work in the open project
    before = window.document
    saved = tmp_path / "before.sward"
    save_project(saved, before)
    for path in bad:
        assert not window.projects.open(path)
        assert path.name in messages[-1] and "\n" not in messages[-1]
        assert window.document is before and window.windowTitle().startswith("Sward — patch")
    assert len(messages) == len(bad)
    from core.project_file import load_project

    assert load_project(saved).same_as(window.document)  # nothing of it changed


def test_closing_with_unsaved_changes_asks_and_cancel_keeps_the_window(window, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    window.panel.param("density").setValue(0.4)
    asked = []

    def cancel(*args, **kwargs):
        asked.append(True)
        return QMessageBox.StandardButton.Cancel

    monkeypatch.setattr(QMessageBox, "question", cancel)
    window.close()
    assert asked and window.isVisible()
    window.undo_stack.setClean()


def test_each_designer_has_its_own_autosave_and_a_save_removes_it(
    window, qtbot, tmp_path, monkeypatch
):
    """Recovery after a real crash (kill -9) is tested without Qt in tests/app."""
    from PySide6.QtWidgets import QMessageBox

    from app.designer import DesignerWindow
    from app.scenes import get_scene

    assert not window.autosave.save_now()  # nothing unsaved: nothing written
    window.panel.param("density").setValue(0.45)
    assert window.autosave.save_now() and window.autosave.path.exists()
    other = keep(DesignerWindow(get_scene("patch-grid").document()))  # a second designer
    other.autosave.directory = window.autosave.directory
    other.autosave.name = "other"
    asked = []
    monkeypatch.setattr(
        QMessageBox,
        "question",
        lambda *a, **k: asked.append(a[2]) or QMessageBox.StandardButton.Yes,
    )
    assert not other.autosave.recover_if_any()  # the first designer still runs: not offered
    assert asked == [] and window.autosave.path.exists()
    other.close()
    assert window.autosave.path.exists()  # the other's close leaves the first's autosave
    assert window.projects.save_as(tmp_path / "saved.sward")
    assert not window.autosave.path.exists()  # saved: no older work left to recover


def test_an_image_larger_than_the_window_is_drawn_at_that_size(window, qtbot, tmp_path):
    from PIL import Image

    from app.image_output import save_image

    wait_for_slices(window, qtbot)
    path = tmp_path / "big.png"
    assert save_image(window, str(path), scale=2)
    vp = window.viewport
    with Image.open(path) as image:
        assert image.size == (2 * vp.width(), 2 * vp.height())
        big = np.asarray(image.convert("RGB"))
    small = grab(window)
    assert abs(coverage(big) - coverage(small)) < 0.05  # the same view, not a blank image
    assert coverage(big) > 0.2


def test_an_image_saved_as_the_window_opens_waits_for_its_renderer(window, tmp_path):
    """File → Save image before the render processes have said how large they draw (just
    after the window opened): the image is drawn once they have, not refused as larger than
    a GPU that draws 0 pixels."""
    from PIL import Image

    from app.designer import DesignerWindow
    from app.image_output import save_image
    from app.scenes import get_scene

    other = keep(DesignerWindow(get_scene("patch-grid").document()))
    other.autosave.directory = tmp_path / "other"
    other.resize(800, 480)
    other.show()
    assert other.viewport.renderer.max_image_size == 0  # not said yet
    path = tmp_path / "at_once.png"
    assert save_image(other, str(path))
    with Image.open(path) as image:
        assert image.size == (other.viewport.width(), other.viewport.height())
        assert coverage(np.asarray(image.convert("RGB"))) > 0.2
    other.close()


def test_the_light_panel_relights_the_grass_undoably_and_is_saved(window, qtbot, tmp_path):
    from core.project_file import load_project

    before = grab(window).astype(float).mean()
    window.light_panel.root.child("sun_elevation").setValue(5.0)  # the sun near the horizon
    assert window.document.light.sun_elevation == 5.0
    assert window.viewport.renderer_facts()["light"].sun_elevation == 5.0
    after = grab(window).astype(float).mean()
    assert after < before - 3  # low sun: darker grass
    assert window.projects.save_as(tmp_path / "dusk.sward")
    assert load_project(tmp_path / "dusk.sward").light.sun_elevation == 5.0
    window.undo_stack.undo()
    assert window.document.light.sun_elevation == 50.0
    assert window.light_panel.root.child("sun_elevation").value() == 50.0
    # undo and redo from the keyboard, with the platform's keys (Ctrl+Shift+Z redoes on X11)
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    window.viewport.setFocus()
    ctrl = Qt.KeyboardModifier.ControlModifier
    qtbot.keyClick(window.viewport, Qt.Key.Key_Z, ctrl | Qt.KeyboardModifier.ShiftModifier)
    assert window.document.light.sun_elevation == 5.0
    qtbot.keyClick(window.viewport, Qt.Key.Key_Z, ctrl)
    assert window.document.light.sun_elevation == 50.0


def test_a_bookmarked_view_is_in_the_camera_menu_and_the_saved_project(window, tmp_path):
    from core.project_file import load_project

    vp = window.viewport
    vp.camera.orbit(40.0, 10.0)
    assert window.bookmark_view("over the hill")
    assert "over the hill" in [a.text() for a in window.camera_menu.actions()]
    assert window.projects.save_as(tmp_path / "b.sward")
    spec = load_project(tmp_path / "b.sward").cameras["over the hill"]
    assert np.allclose(spec.eye, vp.camera.eye, atol=1e-5)
    window.undo_stack.undo()
    assert "over the hill" not in window.document.cameras


def test_each_grass_type_has_its_own_blades(window, qtbot, tmp_path):
    import dataclasses

    from app.scenes import GrassRecipe, get_scene
    from core.lod import LodConfig
    from core.project_file import load_project

    first = window.document.params(0)
    clumps = GrassRecipe("clumps", first.replace(blade_count=300, seed=9), LodConfig.zones(), 1)
    scene = dataclasses.replace(get_scene("patch-grid"), params=first, grass=(clumps,))
    window.open_document(scene.document())
    panel = window.panel
    panel.param("grass_type").setValue(1)
    assert panel.grass_type == 1
    assert panel.param("blade_count").value() == 300
    panel.param("blade_count").setValue(700)
    assert window.document.params(1).blade_count == 700
    assert window.document.params(0) == first  # the first type keeps its blades
    assert window.viewport.renderer_facts()["patch_params"][1].blade_count == 700
    assert window.projects.save_as(tmp_path / "two.sward")
    assert load_project(tmp_path / "two.sward").params(1).blade_count == 700
    window.undo_stack.undo()
    assert window.document.params(1).blade_count == 300
    assert panel.param("blade_count").value() == 300
    panel.param("grass_type").setValue(0)
    assert panel.param("blade_count").value() == first.blade_count


def test_a_number_typed_without_its_unit_is_taken_in_that_unit(window, qtbot):
    box = spin_box(window, "length_max")
    assert box.lineEdit().text().endswith("patch units")
    type_into(box, "0.36")
    qtbot.waitUntil(lambda: window.document.params(0).length_max == pytest.approx(0.36))
    type_into(box, "0.32 patch units")  # with the unit as well
    qtbot.waitUntil(lambda: window.document.params(0).length_max == pytest.approx(0.32))
    assert window.panel.message.text() == ""


def test_text_that_is_no_number_gets_a_message_naming_the_field(window, qtbot):
    """ "abc" in a number field: a message names the field (not only a red border), nothing
    changes, and the message goes once a number is typed."""
    before = window.document.params(0)
    for name, title in (("length_max", "Length max"), ("density", "Global density")):
        box = spin_box(window, name)
        type_into(box, "abc")
        message = window.panel.message.text()
        assert title in message and "“abc” is not a number" in message
        assert window.document.params(0) == before and not window.undo_stack.canUndo()
    box = spin_box(window, "density")
    type_into(box, "0.5")
    qtbot.waitUntil(lambda: window.document.density == pytest.approx(0.5))
    assert window.panel.message.text() == ""


def test_an_out_of_range_value_is_refused_with_the_field_and_its_range(window, qtbot):
    box = spin_box(window, "length_max")
    before = window.document.params(0)
    type_into(box, "5")
    qtbot.waitUntil(lambda: window.panel.message.text() != "")
    message = window.panel.message.text()
    assert "Length max" in message and "0.005" in message and "… 2" in message
    assert window.document.params(0) == before  # refused, not clamped to 2
    assert box.value() == pytest.approx(before.length_max)
    assert not window.undo_stack.canUndo()


def test_the_readme_names_the_menus_as_they_are(window):
    """Every `Menu → Item` the README mentions is an item of that menu."""
    import re
    from pathlib import Path

    readme = (Path(__file__).parents[2] / "README.md").read_text()
    menus = {
        action.text().replace("&", ""): [a.text().replace("&", "") for a in action.menu().actions()]
        for action in window.menuBar().actions()
    }
    mentioned = re.findall(r"\*\*(\w+) → ([^*]+)\*\*", readme)
    assert ("File", "New from built-in scene") in mentioned
    for menu, item in mentioned:
        assert item in menus[menu], (menu, item, menus[menu])


def test_the_quality_view_shows_the_difference_against_all_geometry(window, qtbot):
    """Ctrl+6: at rest, an all-geometry frame is drawn in the background; the difference lies
    over the frame as a heat map and its figures are in the status line; a camera move gives
    them up until the view rests again; a blowing wind waits while the view is on."""
    vp = window.viewport
    wait_for_slices(window, qtbot)
    plain = vp.grab().toImage()
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    vp.setFocus()
    qtbot.keyClick(vp, Qt.Key.Key_6, Qt.KeyboardModifier.ControlModifier)
    assert window.quality_action.isChecked() and vp.quality
    qtbot.wait(100)
    vp.renderer.set_view_state(SetOverlay("brush", []))  # interrupts it: drawn again after
    qtbot.waitUntil(lambda: vp.quality_figures is not None, timeout=120000)
    figures = vp.quality_figures
    assert 0 < figures["lod"]["flip_quarter"] < 1
    assert figures["geometry_ms"] > 0 and figures["speedup"] > 0
    assert "quality against all-geometry" in window.status.text()
    assert f"{figures['lod']['flip_quarter']:.3f}" in window.status.text()

    def image(qimage):
        qimage = qimage.convertToFormat(qimage.Format.Format_RGB888)
        w, h = qimage.width(), qimage.height()
        data = np.frombuffer(qimage.constBits(), np.uint8, count=qimage.sizeInBytes())
        return data.reshape(h, qimage.bytesPerLine())[:, : w * 3].reshape(h, w, 3).astype(int)

    shown, before = image(vp.grab().toImage()), image(plain)
    assert np.abs(shown - before).mean() > 10  # the heat map lies over the frame
    assert [legend.kind for legend in vp.legends()] == ["heat"]  # and its scale says what counts
    # the wind starts blowing: the Quality view holds it at its moment, so the reference of the
    # new view is drawn (each next moment would give it up)
    window.wind_action.trigger()
    assert window.document.wind.enabled and not vp.animating
    held = vp.wind_time
    with qtbot.waitSignal(vp.frame_rendered, timeout=20000):
        vp.camera.orbit(15.0, 0.0)
        vp.request_frame()
    assert vp.quality_figures is None  # the new view's difference is not drawn yet
    qtbot.waitUntil(lambda: vp.quality_figures is not None, timeout=120000)
    assert vp.wind_time == held
    qtbot.keyClick(vp, Qt.Key.Key_6, Qt.KeyboardModifier.ControlModifier)  # off again
    assert not vp.quality and not window.quality_action.isChecked()
    assert "quality" not in window.status.text()  # its figures leave with it
    assert vp.legends() == []
    assert vp.animating  # the wind blows on from where it was held
    qtbot.waitUntil(lambda: vp.wind_time > held, timeout=20000)


def test_the_wind_dock_animates_the_grass_undoably_and_is_saved(window, qtbot, tmp_path):
    from PySide6.QtWidgets import QApplication

    from core.project_file import load_project

    vp = window.viewport
    still = grab(window)
    assert not vp.animating and not window.wind_action.isChecked()
    box = window.wind_panel.enabled_box
    qtbot.mouseClick(box, Qt.MouseButton.LeftButton, pos=QPoint(8, box.height() // 2))
    assert window.document.wind.enabled and vp.animating and window.wind_action.isChecked()
    assert window.viewport.renderer_facts()["wind"].enabled
    # frames keep coming at later moments of the wind, and the grass moves between them (two
    # frames of one kind compared: drafts, or full frames where the renderer keeps up)
    seen: dict[bool, list[tuple[float, np.ndarray]]] = {True: [], False: []}

    def record(stats):
        seen[stats.draft].append((vp.wind_time, vp.frame_image()))

    def two_moments():
        return any(len({t for t, _ in frames}) >= 2 for frames in seen.values())

    vp.frame_rendered.connect(record)
    qtbot.waitUntil(two_moments, timeout=60_000)
    vp.frame_rendered.disconnect(record)
    frames = next(f for f in seen.values() if len({t for t, _ in f}) >= 2)
    first, last = frames[0], frames[-1]
    assert last[0] > first[0]
    assert first[1].shape == last[1].shape and np.any(first[1] != last[1])
    # the dial turns the wind (one more undo step), the project keeps it
    window.wind_panel.dial.setValue((window.wind_panel.dial.value() + 90) % 360)
    assert window.document.wind.direction == pytest.approx(120.0)
    assert window.projects.save_as(tmp_path / "windy.sward")
    saved = load_project(tmp_path / "windy.sward").wind
    assert saved.enabled and saved.direction == pytest.approx(120.0)
    # undo: the direction, then the wind itself; the view holds still again
    assert window.undo_stack.undoText() == "change wind"
    window.undo_stack.undo()
    assert window.document.wind.direction == pytest.approx(30.0)
    assert window.document.wind.enabled and window.undo_stack.undoText() == "wind on"
    window.undo_stack.undo()
    assert not window.document.wind.enabled and not vp.animating and not box.isChecked()
    QApplication.processEvents()
    calm = grab(window)
    assert np.abs(calm.astype(int) - still.astype(int)).mean() < 1.0  # as before the wind


def test_sharp_wind_frames_draw_each_moment_at_full_quality(window, qtbot):
    """View → Sharp wind frames (Ctrl+Shift+H): while the wind blows, each new moment waits for
    the full frame of the last and comes without a draft, so a slow renderer shows sharp
    frames instead of a stream of drafts."""
    vp = window.viewport
    qtbot.waitUntil(lambda: not vp.settling, timeout=60_000)
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    vp.setFocus()
    shift_ctrl = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier
    qtbot.keyClick(vp, Qt.Key.Key_H, shift_ctrl)
    assert window.sharp_wind_action.isChecked() and vp.sharp_wind
    shown: list[tuple[bool, float]] = []
    vp.frame_rendered.connect(lambda stats: shown.append((stats.draft, vp.wind_time)))
    window.set_wind_blowing(True)
    # the switch itself is a change of the document: a draft may come first; after that the
    # moments are full frames only
    qtbot.waitUntil(lambda: len({t for p, t in shown if not p}) >= 3, timeout=120_000)
    first_full = next(i for i, (p, _) in enumerate(shown) if not p)
    assert not any(p for p, _ in shown[first_full:])
    moments = [t for _, t in shown[first_full:]]
    assert moments == sorted(moments) and moments[-1] > moments[0]
    window.set_wind_blowing(False)


def test_while_the_wind_moves_on_drafts_the_status_line_says_so(window, qtbot):
    """On a scene whose full frames are slower than the wind's step the wind moves on with
    drafts: the status line says so (and where sharp frames are), not "full quality follows"
    frame after frame; the wind stopped, the full frame follows again."""
    from app.scenes import get_scene
    from tests.widgets.conftest import wait_full

    window.resize(1300, 640)  # the meadow's full frames at a size where they are slow
    window.open_document(get_scene("meadow").document())
    wait_full(window)
    vp = window.viewport
    if vp.last_stats.t_a_ms < 500:
        pytest.skip("full frames here keep up with the wind: no drafts to speak of")
    window.wind_action.trigger()
    qtbot.waitUntil(lambda: vp.schedule.wind_on_drafts, timeout=30000)
    for _ in range(3):  # the drafts that follow each other as the wind blows
        with qtbot.waitSignal(vp.frame_rendered, timeout=30000) as drawn:
            pass
        if drawn.args[0].draft:
            assert "Sharp wind frames" in window.status.text()
            assert "full quality follows" not in window.status.text()
    window.wind_action.trigger()
    wait_full(window)
    assert "draft" not in window.status.text()


def test_the_window_layout_and_view_preferences_are_kept_for_the_next_start(window, qtbot):
    """Closed and opened again, the designer has the size, the docks and the View menu's
    display preferences it was left with (QSettings); the project's own state is not among
    them."""
    from app.designer import DesignerWindow
    from app.scenes import get_scene

    vp = window.viewport
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    vp.setFocus()
    shift_ctrl = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier
    qtbot.keyClick(vp, Qt.Key.Key_T)  # technique colours
    qtbot.keyClick(vp, Qt.Key.Key_P)  # timings overlay
    qtbot.keyClick(vp, Qt.Key.Key_H, shift_ctrl)  # sharp wind frames
    assert window.techniques_action.isChecked() and window.overlay.isVisible()
    window.history_dock.close()  # a dock the user closed
    window.resize(760, 520)  # inside pytest-xvfb's 800 × 600 screen
    qtbot.waitUntil(lambda: window.width() == 760)
    window.close()

    again = keep(DesignerWindow(get_scene("patch-grid").document()))
    try:
        assert again.techniques_action.isChecked()
        assert again.timings_action.isChecked()
        assert again.sharp_wind_action.isChecked() and again.viewport.sharp_wind
        assert not again.zones_action.isChecked()
        assert not again.wind_action.isChecked()  # the project's wind is still off
        again.show()
        qtbot.waitExposed(again)
        assert again.width() == 760  # as built: 1200 (the height is held by the docks' least)
        assert again.overlay.isVisible()
        assert not again.history_dock.isVisible() and again.patch_dock.isVisible()
        again.reset_layout_action.trigger()  # View → Reset layout
        qtbot.waitUntil(again.history_dock.isVisible)
        assert again.width() == 1200  # as built
        assert again.techniques_action.isChecked()  # the preferences stay
    finally:
        again.close()


def test_settings_that_are_not_what_the_designer_saved_leave_the_window_as_built(window):
    """A settings file edited by hand (or another version's): the designer opens as built
    instead of failing."""
    from PySide6.QtCore import QSettings

    from app.designer import DesignerWindow
    from app.scenes import get_scene

    settings = QSettings("Sward", "Sward")
    settings.setValue("window/geometry", "hello")
    settings.setValue("window/dock_state", b"not a dock state")
    settings.setValue("view/technique_colours", "banana")
    settings.setValue("view/timings_overlay", "true")
    settings.sync()
    again = keep(DesignerWindow(get_scene("patch-grid").document()))
    try:
        assert (again.width(), again.height()) == (1200, 760)
        assert not again.techniques_action.isChecked()
        assert again.timings_action.isChecked()  # the one value that is a check mark
    finally:
        again.close()


def test_a_wind_preset_sets_the_gusts_in_one_undo_step(window, qtbot):
    """Wind dock → Preset: picking "storm" sets the gusts' and the turbulence's values at
    once (the direction stays), the numbers show them, one undo puts the wind back; a value
    edited by hand shows the preset box as "(custom)"."""
    from core.wind import PRESETS

    panel = window.wind_panel
    box = panel.preset_box
    assert box.currentText() == "gusty"  # the default wind
    before = window.document.wind
    window.wind_dock.raise_()
    qtbot.waitUntil(box.isVisible)
    box.setFocus()
    qtbot.keyClick(box, Qt.Key.Key_Down)  # gusty -> storm, as a user steps through the list
    wind = window.document.wind
    assert box.currentText() == "storm"
    assert wind.gust_strength == PRESETS["storm"]["gust_strength"]
    assert wind.speed == PRESETS["storm"]["speed"] and wind.direction == before.direction
    assert panel.root.child("gust_strength").value() == PRESETS["storm"]["gust_strength"]
    assert window.undo_stack.count() == 1
    window.undo_stack.undo()
    assert window.document.wind == before and box.currentText() == "gusty"
    panel.root.child("gust_scale").setValue(9.5)  # by hand
    assert window.document.wind.gust_scale == 9.5 and box.currentText() == "(custom)"


def test_ctrl_z_in_a_field_with_nothing_to_undo_undoes_the_document(window, qtbot):
    """Ctrl+Z pressed while a field has the focus reaches the document's history unless the
    field holds an edit of its own: then that edit is undone first, as a person expects."""
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QLineEdit

    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    window.panel.param("density").setValue(0.5)
    assert window.undo_stack.canUndo() and window.document.density == 0.5
    field = window.paint_panel.size_box  # a spin box that has nothing to undo
    window.paint_dock.raise_()
    field.setFocus()
    qtbot.waitUntil(field.hasFocus)
    QTest.keyClick(field, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert window.document.density == 1.0  # the document's edit, undone
    QTest.keyClick(
        field, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier
    )
    assert window.document.density == 0.5  # and redone
    edit = field.findChild(QLineEdit)
    edit.selectAll()
    QTest.keyClicks(edit, "30")  # the field's own edit
    QTest.keyClick(field, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert window.document.density == 0.5  # the field undid its typing, not the document


def test_fly_speed_follows_the_scene_and_the_wheel_and_is_shown(window, qtbot):
    """Half a second of E in fly mode lifts the camera by what the scene's size allows (its
    longer side crossed in 30 s), not by a share of the distance to the orbit's target; the
    wheel makes flying faster and the status line says how fast."""
    from PySide6.QtTest import QTest

    from widgets.fly import CROSSING_S

    vp = window.viewport
    spec = window.document.terrain_spec
    speed = max(spec.columns, spec.rows) / CROSSING_S
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    vp.setFocus()
    QTest.keyClick(vp, Qt.Key.Key_F)
    assert vp.fly.on and "units/s" in window.status.text()
    y = vp.camera.eye[1]
    QTest.keyPress(vp, Qt.Key.Key_E)
    qtbot.wait(500)
    QTest.keyRelease(vp, Qt.Key.Key_E)
    rise = vp.camera.eye[1] - y
    assert 0.0 < rise <= speed * 0.5 * 1.5
    from PySide6.QtCore import QPoint, QPointF
    from PySide6.QtGui import QWheelEvent
    from PySide6.QtWidgets import QApplication

    centre = QPointF(vp.width() / 2, vp.height() / 2)
    event = QWheelEvent(centre, vp.mapToGlobal(centre), QPoint(), QPoint(0, 120),
                        Qt.MouseButton.NoButton, Qt.KeyboardModifier.NoModifier,
                        Qt.ScrollPhase.NoScrollPhase, False)  # fmt: skip
    distance = vp.camera.distance
    QApplication.sendEvent(vp, event)
    assert vp.fly.speed == pytest.approx(speed * 1.25)
    assert vp.camera.distance == distance  # flying, the wheel does not zoom
    assert f"{speed * 1.25:.3g} units/s" in window.status.text()
    QTest.keyClick(vp, Qt.Key.Key_F)
    assert not vp.fly.on


def test_the_light_dock_takes_numbers_with_or_without_their_unit(window, qtbot):
    """ "45" is 45 degrees of sun elevation, as "45 °" is; a value out of range gets a message
    naming the field and its range and changes nothing."""
    panel = window.light_panel
    window.light_dock.raise_()
    box = field(panel.tree, "sun_elevation")
    type_into(box, "45")
    qtbot.waitUntil(lambda: window.document.light.sun_elevation == pytest.approx(45.0))
    type_into(box, "30 °")
    qtbot.waitUntil(lambda: window.document.light.sun_elevation == pytest.approx(30.0))
    type_into(box, "95")
    qtbot.waitUntil(lambda: "Sun elevation" in panel.message.text())
    assert "0 … 90" in panel.message.text()
    assert window.document.light.sun_elevation == pytest.approx(30.0)


def test_the_patch_panels_slice_count_says_which_views_it_sets(window):
    """Two controls of slices: the LOD zones dock's per volume zone, and the Patch panel's,
    which only the Volume only and Compare views draw with; the panel says so."""
    param = window.panel.param("slices")
    assert "Volume" in param.title() and "Compare" in param.title()
    assert "LOD zones dock" in param.opts["tip"]


def test_file_dialogs_open_where_the_last_file_went(window, tmp_path, monkeypatch):
    """The first file dialog opens in the documents folder, not where the designer was
    started; each next one, in this window or a later one, where the last file was saved or
    opened."""
    import os

    from PySide6.QtWidgets import QFileDialog

    asked = []
    folder = tmp_path / "renders"
    folder.mkdir()

    def save(parent, title, start, filters):
        asked.append(start)
        return str(folder / "grass.png"), filters

    def open_(parent, title, start, filters):
        asked.append(start)
        return "", filters

    monkeypatch.setattr(QFileDialog, "getSaveFileName", save)
    monkeypatch.setattr(QFileDialog, "getOpenFileName", open_)
    window.dialogs.save_path("Save image", "grass.png", "PNG (*.png)")
    # in a folder of its own (documents), not relative to where the designer was started
    assert os.path.isabs(asked[0]) and os.path.dirname(asked[0]) != os.getcwd()
    window.dialogs.open_path("Open project", "Sward projects (*.sward)")
    assert asked[1] == str(folder)
    window.dialogs.save_path("Save recorded frames", "timings.csv", "CSV (*.csv)")
    assert asked[2] == str(folder / "timings.csv")


def test_the_title_names_the_project_file(window, tmp_path):
    """Saved or opened, the window's title is the project file's name, not the scene's."""
    assert window.projects.save_as(tmp_path / "my meadow.sward")
    assert "my meadow.sward" in window.windowTitle()
    window.projects.new(window.document)  # a built-in scene again: its name
    assert window.document.name in window.windowTitle()
    assert window.projects.open(tmp_path / "my meadow.sward")
    assert "my meadow.sward" in window.windowTitle()


def test_the_fog_distance_reads_as_a_plain_number(window):
    """1500 units of fog distance read "1500 units", not "1.5e+03 units"."""
    panel = window.light_panel
    panel.root.child("fog_distance").setValue(1500.0)
    box = field(panel.tree, "fog_distance")
    assert box.lineEdit().text().startswith("1500") and "e+" not in box.lineEdit().text()


def test_an_impossible_lod_edit_names_the_zones_by_representation(window, qtbot):
    """The geometry zone ended before the volume zone begins: the refusal names both zones
    as the dock shows them, not "level 2" and "level 1"."""
    panel = window.lod_panel
    window.lod_dock.raise_()
    before = window.document.lod(0)
    panel.end_box(0).setValue(0.1)
    qtbot.waitUntil(lambda: "zone" in panel.message.text())
    text = panel.message.text()
    assert "volume zone" in text and "geometry zone" in text
    assert window.document.lod(0) == before
