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
