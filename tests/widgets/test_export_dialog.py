"""File → Export…: the dialog driven through its controls exports the design as it is now, in
another process, with progress; a folder that cannot be used gets the command's message."""

import json

import pygltflib
import pytest
from PySide6.QtCore import Qt

from core.patch import generate_patch

pytestmark = pytest.mark.gui


def _open(window, qtbot):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.keyClick(
        window,
        Qt.Key.Key_E,
        Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier,
    )
    qtbot.waitUntil(lambda: getattr(window, "export_job", None) is not None)
    dialog = window.export_job.dialog
    qtbot.waitExposed(dialog)
    return dialog


def test_export_writes_the_design_as_it_is_now_with_progress(window, qtbot, tmp_path):
    params = window.document.params(0).replace(blade_count=750)
    window.document.set_params(0, params)  # an edit not saved anywhere
    dialog = _open(window, qtbot)
    out = tmp_path / "export"
    dialog.folder.setText(str(out))
    dialog.parts["maps"].setChecked(False)
    qtbot.mouseClick(dialog.export_button, Qt.MouseButton.LeftButton)
    assert not dialog.export_button.isEnabled()  # running: the window stays live meanwhile
    qtbot.waitUntil(lambda: dialog.export_button.isEnabled(), timeout=120000)
    assert dialog.progress.value() == 100, dialog.message.text()
    assert "grass.gltf" in dialog.message.text()
    assert window.statusBar().currentMessage() == f"exported the design into {out}"
    gltf = pygltflib.GLTF2().load(str(out / "grass.gltf"))
    position = gltf.meshes[0].primitives[0].attributes.POSITION
    assert gltf.accessors[position].count == len(generate_patch(params).vertices)
    assert (
        json.loads((out / "settings.json").read_text())["grass"][0]["params"]["blade_count"] == 750
    )
    assert not (out / "maps" / "density.png").exists()  # not ticked
    dialog.close()
    qtbot.waitUntil(lambda: not dialog.isVisible())


def test_a_folder_that_is_a_file_gets_the_commands_message(window, qtbot, tmp_path):
    taken = tmp_path / "taken"
    taken.write_text("mine")
    dialog = _open(window, qtbot)
    dialog.folder.setText(str(taken))
    qtbot.mouseClick(dialog.export_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: dialog.export_button.isEnabled(), timeout=60000)
    assert "not a folder" in dialog.message.text() and "Traceback" not in dialog.message.text()
    assert taken.read_text() == "mine"
    for box in dialog.parts.values():
        box.setChecked(False)
    qtbot.mouseClick(dialog.export_button, Qt.MouseButton.LeftButton)
    assert "Tick at least one" in dialog.message.text()
    dialog.close()
