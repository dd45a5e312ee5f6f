"""LOD dock → Fewer blade segments within: the tolerance in pixels, per grass type, one undo
step; at 0 every blade is drawn with all its segments (core/segments.py)."""

import pytest
from PySide6.QtCore import Qt

from tests.widgets.conftest import wait_full

pytestmark = pytest.mark.gui


def _triangles(window) -> int:
    wait_full(window)
    return window.viewport.last_stats.triangles


def test_the_segment_tolerance_draws_fewer_triangles_and_undo_takes_it_back(window, qtbot):
    document, box = window.document, window.lod_panel.segments_box
    window.resize(480, 360)  # a small view: most blades are few pixels tall
    assert document.lod(0).segment_tolerance == 0.125 and box.value() == 0.125
    steps = window.undo_stack.count()
    box.selectAll()
    qtbot.keyClicks(box, "4")
    qtbot.keyClick(box, Qt.Key.Key_Return)
    assert document.lod(0).segment_tolerance == 4.0
    assert window.undo_stack.count() == steps + 1
    coarse = _triangles(window)
    box.selectAll()
    qtbot.keyClicks(box, "0")
    qtbot.keyClick(box, Qt.Key.Key_Return)
    assert document.lod(0).segment_tolerance == 0.0 and box.text() == "all segments"
    whole = _triangles(window)
    assert coarse < 0.8 * whole
    window.undo_stack.undo()
    assert document.lod(0).segment_tolerance == 4.0 and box.value() == 4.0
