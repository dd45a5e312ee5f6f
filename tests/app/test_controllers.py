"""The designer's controllers without Qt: each takes the document and narrow interfaces
(app/dialogs.py), so mocks made from those specs stand in for the window (as ndv tests its
controllers against MagicMock(spec=...) views). `make test` runs these with Qt blocked."""

from unittest.mock import MagicMock

import numpy as np
import pytest

from app.autosave import Autosave
from app.dialogs import CANCEL, DISCARD, SAVE, Dialogs, History
from app.map_files import MapFileActions
from app.painting import BrushPanel, PaintController
from app.project_actions import ProjectActions
from app.scenes import get_scene
from core.brush import Brush
from core.project_file import load_project, save_project


class DictSettings(dict):
    def value(self, key, default=None):
        return self.get(key, default)

    def setValue(self, key, value):
        self[key] = value


def doc():
    return get_scene("patch-grid").document()


def panel(layer="density", channel=0, brush=None):
    p = MagicMock(spec=BrushPanel)
    p.target = (layer, channel)
    p.target_label = f"{layer} map"
    p.brush.return_value = brush or Brush(size=16.0, strength=1.0, value=(0.0,))
    p.follows = False
    return p


# -- painting ---------------------------------------------------------------------------------
def test_a_stroke_paints_the_documents_map_and_becomes_one_step():
    document = doc()
    strokes, heights = [], []
    painter = PaintController(
        document, panel(), lambda s, t: strokes.append((s, t)), heights.append
    )
    painter.press(40.0, 40.0)
    painter.move(80.0, 40.0)
    painter.release()
    density = document.maps.layer("density")[..., 0]
    assert density[40, 40] < 0.1 and density[40, 60] < 0.1 and density[200, 200] == 1.0
    assert len(strokes) == 1 and strokes[0][1] == "paint density map"
    strokes[0][0].undo()
    assert document.maps.layer("density")[..., 0].min() == 1.0
    assert heights == []  # a density stroke leaves the terrain alone


def test_a_trample_stroke_lays_the_grass_the_way_it_goes_on_the_ground():
    """Maps of 256 × 128 texels over 8 × 8 cells: a stroke across as many texels each way
    goes half as far along x as along z on the ground, and the blades lie that way."""
    from core.design_maps import DesignMaps
    from core.project_file import document_data, document_from_data
    from core.trample import brush_value, decode
    from core.wind import MAX_LEAN

    document = document_from_data(document_data(doc()), DesignMaps(256, 128).stack)
    brush = Brush(size=8.0, strength=1.0, value=brush_value(0.5, 90.0), falloff="constant")
    p = panel("trample", None, brush)
    p.follows = True
    strokes = []
    painter = PaintController(document, p, lambda s, t: strokes.append(s), lambda: None)
    painter.press(40.0, 40.0)
    painter.move(80.0, 80.0)
    painter.release()
    x, z = decode(document.maps.layer("trample")[60, 60])
    assert np.isclose(np.hypot(x, z), 0.5, atol=1e-3) and 0.5 <= MAX_LEAN
    assert np.isclose(z / x, 2.0, atol=1e-3)  # not the brush's 90°
    assert len(strokes) == 1


def test_erase_and_smooth_override_the_brush_mode():
    p = panel()
    painter = PaintController(doc(), p, lambda s, t: None, lambda: None)
    painter.press(10.0, 10.0, erase=True)
    p.brush.assert_called_with("erase")
    painter.release()
    painter.press(10.0, 10.0, smooth=True)
    p.brush.assert_called_with("smooth")


def test_a_height_edit_asks_for_the_terrain_to_follow():
    document = doc()
    heights = []
    painter = PaintController(
        document,
        panel("height", None, Brush(size=16.0, strength=1.0, value=(1.0,))),
        lambda s, t: None,
        lambda: heights.append(1),
    )
    painter.press(20.0, 20.0)
    painter.release()
    assert heights == [1]  # after the stroke
    document.maps.fill("height", 0.5)  # an undo or an import
    assert heights == [1, 1]


def test_the_eyedropper_shows_the_value_under_the_cursor():
    document = doc()
    document.maps.write("ambient", 5, 7, np.full((1, 1, 3), 0.25))
    p = panel("ambient", None)
    painter = PaintController(document, p, lambda s, t: None, lambda: None)
    painter.start_eyedropper()
    painter.press(5.0, 7.0)
    p.set_value.assert_called_once_with((0.25, 0.25, 0.25))
    assert not painter.eyedropper


def test_a_refused_brush_shows_its_message_and_paints_nothing():
    document = doc()
    p = panel()
    p.brush.side_effect = ValueError("brush size must be positive")
    strokes = []
    painter = PaintController(document, p, lambda s, t: strokes.append(s), lambda: None)
    painter.press(10.0, 10.0)
    painter.release()
    p.show_message.assert_called_with("brush size must be positive")
    assert strokes == [] and document.maps.layer("density").min() == 1.0


# -- projects ---------------------------------------------------------------------------------
def actions(tmp_path, clean=True, answer=DISCARD):
    state = {"doc": doc()}
    history = MagicMock(spec=History)
    history.isClean.return_value = clean
    dialogs = MagicMock(spec=Dialogs)
    dialogs.ask_unsaved.return_value = answer
    opened = []

    def open_document(d):
        state["doc"] = d
        opened.append(d)

    projects = ProjectActions(lambda: state["doc"], open_document, history, dialogs, DictSettings())
    return projects, history, dialogs, opened, state


def test_save_as_writes_the_document_and_marks_the_history_clean(tmp_path):
    projects, history, dialogs, _, state = actions(tmp_path)
    dialogs.save_path.return_value = str(tmp_path / "mine.sward")
    state["doc"].density = 0.3
    assert projects.save()  # no file yet: asks for one
    assert load_project(tmp_path / "mine.sward").same_as(state["doc"])
    history.setClean.assert_called_once()
    assert projects.recent() == [str((tmp_path / "mine.sward").resolve())]


def test_a_bad_file_warns_and_keeps_the_open_project(tmp_path):
    projects, _, dialogs, opened, state = actions(tmp_path)
    bad = tmp_path / "bad.sward"
    bad.write_text("not a project")
    before = state["doc"]
    assert not projects.open(bad)
    assert "bad.sward" in dialogs.warn.call_args[0][0]
    assert opened == [] and state["doc"] is before


@pytest.mark.parametrize(
    ("answer", "opens", "saves"), [(CANCEL, False, 0), (DISCARD, True, 0), (SAVE, True, 1)]
)
def test_unsaved_changes_are_asked_about_before_opening(tmp_path, answer, opens, saves):
    good = tmp_path / "good.sward"
    save_project(good, doc())
    projects, _, dialogs, opened, _ = actions(tmp_path, clean=False, answer=answer)
    dialogs.save_path.return_value = str(tmp_path / "first.sward")
    assert projects.open(good) is opens
    assert len(opened) == int(opens)
    assert (tmp_path / "first.sward").exists() == bool(saves)


def test_autosave_writes_only_unsaved_work(tmp_path):
    projects, history, dialogs, _, state = actions(tmp_path, clean=True)
    autosave = Autosave(tmp_path / "auto", projects, history, dialogs, name="a")
    assert not autosave.save_now() and not autosave.path.exists()
    history.isClean.return_value = False
    state["doc"].density = 0.45
    assert autosave.save_now() and load_project(autosave.path).density == pytest.approx(0.45)
    autosave.close()
    assert list((tmp_path / "auto").iterdir()) == []  # a normal close leaves nothing


def test_a_running_designers_autosave_is_not_taken_by_another(tmp_path):
    first, history, dialogs, _, _ = actions(tmp_path, clean=False)
    a = Autosave(tmp_path, first, history, dialogs, name="a")
    assert a.save_now()
    second, history2, dialogs2, opened, _ = actions(tmp_path, clean=True)
    b = Autosave(tmp_path, second, history2, dialogs2, name="b")
    assert not b.recover_if_any()  # a still runs: its lock is held
    dialogs2.ask_yes.assert_not_called()
    assert a.path.exists() and opened == []


CRASHING_DESIGNER = """
import sys, time
from unittest.mock import MagicMock
from app.autosave import Autosave
from app.scenes import get_scene
doc = get_scene("patch-grid").document()
doc.density = 0.45
projects = MagicMock()
projects.document.return_value = doc
projects.path = sys.argv[2] if len(sys.argv) > 2 else None
history = MagicMock()
history.isClean.return_value = False
Autosave(sys.argv[1], projects, history, MagicMock(), name="crashed").save_now()
print("saved", flush=True)
time.sleep(120)
"""


def test_work_autosaved_by_a_designer_killed_with_sigkill_is_recovered(tmp_path):
    import signal
    import subprocess
    import sys

    designer = subprocess.Popen(
        [sys.executable, "-c", CRASHING_DESIGNER, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    assert designer.stdout.readline() == "saved\n"
    designer.send_signal(signal.SIGKILL)
    designer.wait()
    designer.stdout.close()
    projects, history, dialogs, opened, _ = actions(tmp_path, clean=True)
    dialogs.ask_yes.return_value = True
    history.isClean.return_value = False  # once recovered, the work is unsaved here
    after = Autosave(tmp_path, projects, history, dialogs, name="next")
    assert after.recover_if_any()
    assert opened[-1].density == pytest.approx(0.45)  # nothing lost
    history.resetClean.assert_called_once()
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["autosave-next.json", "autosave-next.lock", "autosave-next.sward"]


def test_recovery_never_offers_work_older_than_the_saved_file(tmp_path):
    import os
    import signal
    import subprocess
    import sys
    import time

    project = tmp_path / "mine.sward"
    designer = subprocess.Popen(
        [sys.executable, "-c", CRASHING_DESIGNER, str(tmp_path), str(project)],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert designer.stdout.readline() == "saved\n"
    designer.send_signal(signal.SIGKILL)
    designer.wait()
    designer.stdout.close()
    save_project(project, get_scene("patch-grid").document())  # saved after the autosave
    later = time.time() + 5
    os.utime(project, (later, later))
    projects, history, dialogs, opened, _ = actions(tmp_path, clean=True)
    assert not Autosave(tmp_path, projects, history, dialogs, name="b").recover_if_any()
    dialogs.ask_yes.assert_not_called()
    assert opened == [] and not (tmp_path / "autosave-crashed.sward").exists()


def test_a_declined_recovery_removes_the_autosave(tmp_path):
    import subprocess
    import sys

    designer = subprocess.Popen(
        [sys.executable, "-c", CRASHING_DESIGNER, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    assert designer.stdout.readline() == "saved\n"
    designer.kill()
    designer.wait()
    designer.stdout.close()
    projects, history, dialogs, opened, _ = actions(tmp_path, clean=True)
    dialogs.ask_yes.return_value = False
    assert not Autosave(tmp_path, projects, history, dialogs, name="b").recover_if_any()
    assert opened == [] and not (tmp_path / "autosave-crashed.sward").exists()


# -- map files --------------------------------------------------------------------------------
def test_an_imported_map_is_resampled_and_handed_on_as_one_edit(tmp_path):
    from PIL import Image

    document = doc()
    path = tmp_path / "grey.png"
    Image.fromarray(np.full((32, 64), 128, np.uint8), "L").save(path)
    imports = []
    dialogs = MagicMock(spec=Dialogs)
    files = MapFileActions(
        lambda: document, panel("ambient", None), lambda *a: imports.append(a), dialogs, None
    )
    assert files.import_map(path)
    layer, channel, values, text = imports[0]
    assert (layer, channel) == ("ambient", None) and "grey.png" in text
    assert values.shape[:2] == (document.maps.size[1], document.maps.size[0])
    assert np.allclose(values, 128 / 255, atol=1e-3)
    assert "resampled" in dialogs.status.call_args[0][0]


def test_an_unreadable_map_file_warns_and_changes_nothing(tmp_path):
    bad = tmp_path / "broken.png"
    bad.write_bytes(b"\x89PNG not really")
    imports = []
    dialogs = MagicMock(spec=Dialogs)
    files = MapFileActions(doc, panel(), lambda *a: imports.append(a), dialogs, None)
    assert not files.import_map(bad)
    assert imports == [] and "broken.png" in dialogs.warn.call_args[0][0]


def test_a_raw_import_asks_for_its_layout_and_a_cancel_changes_nothing(tmp_path):
    raw = tmp_path / "h.r16"
    raw.write_bytes(np.zeros(16 * 16, "<u2").tobytes())
    dialogs = MagicMock(spec=Dialogs)
    dialogs.raw_height_options.return_value = None
    imports = []
    files = MapFileActions(doc, panel("height", None), lambda *a: imports.append(a), dialogs, None)
    assert not files.import_map(raw)
    dialogs.raw_height_options.assert_called_once_with("h.r16", 512)
    assert imports == []


def test_species_rules_the_person_sets_place_the_grass_and_travel_with_it(tmp_path):
    """Paint → Grass types from colours…: the dialog's rules (here the first type's reference
    set to a blue nobody's blades have) decide where each type grows; a cancel changes
    nothing."""
    import colorsys

    from PIL import Image

    from core.species import Species, SpeciesTuning

    document = doc()
    w, h = document.maps.size
    image = np.zeros((h, w, 3), np.uint8)
    image[:, : w // 2] = (40, 60, 200)  # blue
    image[:, w // 2 :] = np.round(np.asarray(document.light.soil_color) * 255)
    path = tmp_path / "colours.png"
    Image.fromarray(image).save(path)
    placed = []
    dialogs = MagicMock(spec=Dialogs)
    dialogs.open_path.return_value = str(path)
    files = MapFileActions(lambda: document, panel(), None, dialogs, lambda *a: placed.append(a))

    dialogs.species_rules.return_value = None
    assert not files.species_from_image()
    assert placed == [] and not dialogs.open_path.called
    names, derived, given = dialogs.species_rules.call_args[0]
    assert names == [*document.grass_names, "bare soil"] and len(derived) == len(names)
    assert given == document.species

    blue = tuple(colorsys.rgb_to_hsv(40 / 255, 60 / 255, 200 / 255))
    species = Species((SpeciesTuning(reference=blue),))
    dialogs.species_rules.return_value = species
    assert files.species_from_image()
    rules, density, text = placed[0]
    channels = [kind.channel for kind in document.grass_types]
    assert rules == species and text == "grass types from colours.png"
    # blue is the first type's own now (the blades' green would give it 0.84 here)
    assert density[:, 4 : w // 2 - 4, channels[0]].min() > 0.99
    assert density[:, w // 2 + 4 : -4][..., channels].max() < 0.05


def test_a_save_removes_the_autosave_so_recovery_never_offers_older_work(tmp_path):
    projects, history, dialogs, _, state = actions(tmp_path, clean=False)
    autosave = Autosave(tmp_path / "auto", projects, history, dialogs, name="a")
    projects.saved = autosave.discard
    state["doc"].density = 0.3
    assert autosave.save_now() and autosave.path.exists()
    dialogs.save_path.return_value = str(tmp_path / "mine.sward")
    assert projects.save()
    assert not autosave.path.exists()
    assert not autosave.recover_if_any()  # nothing older than the saved file is offered
