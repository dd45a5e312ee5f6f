"""Painting by rule (core/paint_rule.py): the brush takes only where the ground's slope and
height lie in the rule's ranges, fading over its soft edge."""

import numpy as np
import pytest

from core.brush import Brush, Stroke
from core.design_maps import DesignMaps
from core.paint_rule import PaintRule, ground_slope, rule_mask

SIZE = 64  # texels a side over 64 × 64 cells: one world unit a texel


def _ramps() -> np.ndarray:
    """The left half flat at 0.5, the right half rising at 40° along x (tan 40° a texel)."""
    h = np.full((SIZE, SIZE), 0.5)
    x = np.arange(SIZE // 2, dtype=np.float64)
    h[:, SIZE // 2 :] = 0.5 + np.tan(np.radians(40.0)) * (x + 1)
    return h


def test_the_slope_of_a_ramp_is_its_angle():
    h = _ramps()
    slope = ground_slope(h, (1.0, 1.0))
    assert slope[:, 4:28] == pytest.approx(0.0)
    assert slope[:, 36:60] == pytest.approx(40.0, abs=1e-6)
    assert ground_slope(h, (2.0, 2.0))[:, 36:60] == pytest.approx(
        np.degrees(np.arctan(np.tan(np.radians(40)) / 2)), abs=1e-6
    )


def test_a_stroke_over_40_degrees_with_a_rule_of_at_most_30_changes_nothing_there():
    scale = 100.0
    heights = _ramps() / scale  # the height map holds 0 … 1 of the scale
    maps = DesignMaps(SIZE)
    maps.write("density", 0, 0, np.zeros((SIZE, SIZE)), channel=0)
    mask = rule_mask(PaintRule(slope=(0.0, 30.0)), heights, scale, (SIZE, SIZE))
    stroke = Stroke(maps, "density", Brush(size=12, strength=1.0), 0, mask)
    for x in range(4, SIZE - 4, 2):  # across the flat half and the steep one
        stroke.add(float(x), SIZE / 2)
    density = maps.layer("density")[..., 0]
    assert density[:, 10:28].max() > 0.9  # painted on the flat
    assert density[:, 36:].max() == 0.0  # nothing on the 40° ramp
    unruled = Stroke(maps, "density", Brush(size=12, strength=1.0), 0)
    unruled.add(48.0, SIZE / 2)
    assert maps.layer("density")[..., 0][:, 36:].max() > 0.9  # without the rule it would


def test_fill_by_rule_paints_where_the_height_holds_and_fades_over_the_soft_edge():
    heights = np.tile(np.linspace(0.0, 1.0, SIZE), (SIZE, 1))  # rising along x, 0 … 10 units
    maps = DesignMaps(SIZE)
    maps.write("density", 0, 0, np.zeros((SIZE, SIZE)), channel=0)
    rule = PaintRule(height=(5.0, 20.0), soft_height=1.0)
    mask = rule_mask(rule, heights, 10.0, (SIZE, SIZE))
    Stroke(maps, "density", Brush(value=(0.8,), mode="fill"), 0, mask)
    row = maps.layer("density")[0, :, 0]
    x = np.linspace(0.0, 10.0, SIZE)
    assert row[x >= 5.0] == pytest.approx(0.8)
    assert (row[x < 4.0] == 0.0).all()
    edge = row[(x > 4.0) & (x < 5.0)]
    assert edge.size and (np.diff(edge) >= 0).all() and 0.0 < edge.mean() < 0.8


def test_rules_are_checked_and_travel_as_plain_data():
    with pytest.raises(ValueError, match="least first"):
        PaintRule(slope=(30.0, 10.0))
    with pytest.raises(ValueError, match="0 to 90"):
        PaintRule(slope=(0.0, 95.0))
    rule = PaintRule(slope=(5.0, 25.0), height=(-1.0, 3.0), soft_slope=4.0)
    assert PaintRule.from_dict(rule.to_dict()) == rule and rule.active
    assert not PaintRule().active
