"""The undo history's memory cap: the oldest paint strokes are forgotten, the kept ones still
undo and redo exactly, and the saved state stays marked where it still is."""

import numpy as np
import pytest
from PySide6.QtGui import QUndoStack

from app.commands import PaintStroke, history_bytes, push
from core.brush import Brush, Stroke
from core.design_maps import DesignMaps

pytestmark = pytest.mark.gui


def stroke(maps, x):
    s = Stroke(maps, "color", Brush(size=20, strength=1.0, value=(1.0, 0.0, 0.0, 1.0)))
    s.add(x, 40.0)
    s.add(x, 200.0)
    s.finish()
    return PaintStroke(s, f"stroke at {x}")


def test_strokes_past_the_cap_are_forgotten_and_the_rest_undo_exactly(qapp):
    maps = DesignMaps(256)
    stack = QUndoStack()
    states = [maps.stack.copy()]
    first = stroke(maps, 30.0)
    one = first.memory_bytes
    cap = int(2.5 * one)  # room for two strokes of this size
    assert push(stack, first, cap) == 0
    stack.setClean()
    states.append(maps.stack.copy())
    for x in (100.0, 170.0, 230.0):
        dropped = push(stack, stroke(maps, x), cap)
        states.append(maps.stack.copy())
    assert dropped == 1 and stack.count() == 2
    assert history_bytes(stack) <= cap
    assert not stack.isClean()
    stack.undo()
    assert np.array_equal(maps.stack, states[3])
    stack.undo()
    assert np.array_equal(maps.stack, states[2])
    assert not stack.canUndo()  # the older strokes are forgotten
    assert not stack.isClean()  # the saved state (after the first stroke) is not reachable
    stack.redo()
    stack.redo()
    assert np.array_equal(maps.stack, states[4])


def test_a_drag_is_one_undo_step_and_edits_after_a_pause_are_their_own(qapp):
    """Light edits in quick succession (a slider dragged) merge; an edit after a pause (a second
    preset picked) is a step of its own, so one undo takes back only it."""
    import dataclasses

    from app.commands import MERGE_S, set_light
    from app.scenes import get_scene

    doc = get_scene("patch-grid").document()
    stack = QUndoStack()
    start = doc.light.sun_elevation

    def edit(elevation: float, at: float) -> None:
        command = set_light(doc, dataclasses.replace(doc.light, sun_elevation=elevation))
        command.at = at
        stack.push(command)

    edit(start + 1.0, 100.0)
    edit(start + 2.0, 100.1)  # the drag goes on
    edit(start + 3.0, 100.2)
    assert stack.count() == 1
    edit(start + 10.0, 100.2 + 2.0 * MERGE_S)  # later: a new step
    assert stack.count() == 2
    stack.undo()
    assert doc.light.sun_elevation == start + 3.0
    stack.undo()
    assert doc.light.sun_elevation == start


def test_a_slow_drag_of_the_sun_dial_is_still_one_undo_step(qapp):
    """Moves of one sun-dial drag merge however long the person pauses on the way; the next
    drag, even at once, is a step of its own."""
    import dataclasses

    from app.commands import MERGE_S, set_light
    from app.scenes import get_scene

    doc = get_scene("patch-grid").document()
    stack = QUndoStack()
    start = doc.light.sun_azimuth

    def edit(azimuth: float, at: float, drag: int) -> None:
        command = set_light(doc, dataclasses.replace(doc.light, sun_azimuth=azimuth), drag)
        command.at = at
        stack.push(command)

    edit(start + 10.0, 100.0, drag=1)
    edit(start + 20.0, 100.0 + 5.0 * MERGE_S, drag=1)  # a long look, then on
    assert stack.count() == 1
    edit(start + 30.0, 100.0 + 10.0 * MERGE_S, drag=2)  # pressed again, later: a new step
    assert stack.count() == 2
    stack.undo()
    assert doc.light.sun_azimuth == start + 20.0
    stack.undo()
    assert doc.light.sun_azimuth == start
