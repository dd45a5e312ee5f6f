"""Paint dock → Only where: a slope rule set through its controls keeps Fill by rule (and the
brush) off ground steeper than it allows; the rule is one undo step, the fill another, and the
Map dock shades where the rule does not hold."""

import numpy as np
import pytest
from PySide6.QtCore import Qt

pytestmark = pytest.mark.gui


def test_fill_by_rule_keeps_off_the_40_degree_ramp_and_the_map_shows_the_rule(window, qtbot):
    document = window.document
    w, h = document.maps.size
    spacing = document.terrain_spec.columns / w  # world units a texel along x
    rise = np.tan(np.radians(40.0)) * spacing * np.maximum(np.arange(w) - w // 2, 0)
    scale = 4.0
    document.set_heights(np.tile(rise / scale, (h, 1))[..., None].astype(np.float32), scale)
    flat, steep = (slice(8, h - 8), slice(8, w // 2 - 8)), (slice(8, h - 8), slice(w // 2 + 8, -8))
    panel, box = window.paint_panel, window.paint_panel.rule_box
    panel.value_box.setValue(0.0)  # fill the first type's density with none
    assert not box.fill_button.isEnabled() and not window.map_view.mask.isVisible()
    steps = window.undo_stack.count()

    qtbot.mouseClick(box.slope_check, Qt.MouseButton.LeftButton)
    box.slope_max.selectAll()
    qtbot.keyClicks(box.slope_max, "30")
    qtbot.keyClick(box.slope_max, Qt.Key.Key_Return)
    assert document.paint_rule.slope == (0.0, 30.0)
    assert window.undo_stack.count() == steps + 1  # the box sets 0 … 30; typing 30 keeps it
    shade = window.map_view.mask.image[..., 3]
    assert window.map_view.mask.isVisible()
    assert shade[flat].max() == 0 and shade[steep].min() > 150  # the steep half is veiled

    before = document.maps.layer("density")[..., 0].copy()
    qtbot.mouseClick(box.fill_button, Qt.MouseButton.LeftButton)
    density = document.maps.layer("density")[..., 0]
    assert density[flat].max() == 0.0  # filled with none where the rule holds
    assert np.array_equal(density[steep], before[steep])  # 40°: untouched
    assert window.undo_stack.text(window.undo_stack.count() - 1).endswith("by rule")
    window.undo_stack.undo()
    assert np.array_equal(document.maps.layer("density")[..., 0], before)
