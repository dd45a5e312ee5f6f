"""What a view at a low elevation meets of the grass (core/canopy.py)."""

import numpy as np
import pytest

from core.canopy import Canopy, elevations


def slices(rows_rgba):
    """(2, rows, 4, 4) vertical slices whose rows (bottom first) have the given colours."""
    stack = np.zeros((2, len(rows_rgba), 4, 4), np.float32)
    stack[:] = np.asarray(rows_rgba, np.float32)[None, :, None, :]
    return stack


def test_an_opaque_top_row_is_all_a_low_view_meets():
    stack = slices([(0.0, 0.0, 1.0, 1.0)] * 3 + [(1.0, 0.0, 0.0, 1.0)])
    colours = Canopy.of([stack], 1.0).level_colors()
    low = elevations() < np.radians(20.0)
    np.testing.assert_allclose(colours[low], np.tile([1.0, 0.0, 0.0], (low.sum(), 1)), atol=1e-3)


def test_empty_rows_are_seen_through():
    stack = slices([(0.0, 1.0, 0.0, 1.0)] * 2 + [(1.0, 0.0, 0.0, 0.0)] * 2)
    colours = Canopy.of([stack], 1.0).level_colors()
    np.testing.assert_allclose(colours[:, 1], 1.0, atol=1e-3)


def test_the_flatter_the_view_the_more_of_the_upper_rows_it_meets():
    """Sparse rows: a steep view reaches the lower rows, a level one stops near the top."""
    stack = slices([(0.0, 0.0, 1.0, 0.1)] * 4 + [(1.0, 0.0, 0.0, 0.1)] * 4)
    colours = Canopy.of([stack], 1.0).level_colors()
    red = colours[:, 0]
    assert np.all(np.diff(red) < 0)  # elevations rise: less and less of the top
    assert red[0] > 0.9 and red[-1] < 0.7


def test_in_another_grass_a_type_stops_a_ray_by_its_share_of_the_blades():
    """Red rows over the whole height in a dense blue grass reaching half of it: a level ray
    is stopped by the red rows above the blue grass, a steep one reaches the blue grass more
    often; and with no grass beneath, the red stops every ray that anything stops."""
    red = Canopy.of([slices([(1.0, 0.0, 0.0, 0.05)] * 8)], 1.0)
    dense = Canopy.of([slices([(0.0, 0.0, 1.0, 0.9)] * 8)], 0.5)
    share, colours = red.over(dense)
    assert np.all(np.diff(share) < 0)  # elevations rise: shorter paths through the red rows
    assert share[0] > 0.5 and share[-1] < 0.3
    np.testing.assert_allclose(colours[:, 0], 1.0, atol=1e-3)  # only the red blades
    empty = Canopy.of([slices([(0.0, 0.0, 1.0, 0.0)] * 8)], 0.5)
    alone, _ = red.over(empty)
    assert np.all(alone > share)


def test_a_view_reaches_the_lower_rows_less_the_flatter_it_is():
    canopy = Canopy.of([slices([(0.0, 1.0, 0.0, 0.2)] * 8)], 1.0)
    theta = elevations()
    seen = canopy.transmittance(np.array([0.1, 0.5, 0.9, 1.5]), theta)
    assert np.all(np.diff(seen, axis=0) > 0)  # higher rows are reached more
    assert np.all(np.diff(seen[:3], axis=1) > 0)  # steeper views reach deeper
    np.testing.assert_allclose(seen[3], 1.0)  # above the grass
    assert seen[0, 0] < 0.01 and seen[0, -1] > 0.2


def test_the_ao_a_view_meets_darkens_as_it_reaches_down():
    """1 − smoothstep(0, B_height, y) over the heights met: near 0 for a level view into a
    canopy whose top lies above B_height, more the steeper the view; another type's dense
    grass standing among the blades takes the deep rays."""
    canopy = Canopy.of([slices([(0.0, 1.0, 0.0, 0.2)] * 8)], 1.0)
    shade = canopy.shade_met(0.5)
    assert np.all(np.diff(shade) > 0)
    assert shade[0] < 0.05 and shade[-1] > 0.2
    dense = Canopy.of([slices([(0.0, 0.0, 1.0, 0.9)] * 8)], 0.5)
    assert np.all(canopy.shade_met(0.5, dense)[2:] < shade[2:])


def test_a_level_rays_column_depth_sums_the_rows_above_a_height():
    """Two slices of rows with mean alpha 0.2 and 0.5: a level ray through one patch length of
    a row meets 1 − 0.8 · 0.5 of it, depth −ln 0.4 per patch length; four rows of a grass 1 tall
    sum to that, and the rows above 0.25 (three of them) or 0.375 (two and a half) to their
    share (core/canopy.py side_column, the image-based grass's depth from the side)."""
    stack = np.zeros((2, 4, 4, 4), np.float32)
    stack[0, ..., 3], stack[1, ..., 3] = 0.2, 0.5
    canopy = Canopy.of([stack], 1.0)
    depth = -np.log(0.8 * 0.5)
    assert np.isclose(canopy.side_column(), depth)
    assert np.isclose(canopy.side_column(0.25), 0.75 * depth)
    assert np.isclose(canopy.side_column(0.375), 0.625 * depth)
    assert canopy.side_column(1.0) == 0.0


def test_the_blades_depths_are_their_area_seen_from_the_side_and_from_above():
    """core/canopy.py BladeDepths: an upright square 0.1 on a side facing x, its texture whole
    (v = 0), gives a level ray its area times 2/π (|cos| averaged over the directions around
    it) and a vertical ray nothing; a flat one lying on the ground gives a vertical ray its
    area and a level one nothing; the rows above half the upright one's height, half."""
    from core.canopy import BladeDepths

    upright = np.array([(0, 0, 0), (0, 0, 0.1), (0, 0.1, 0), (0, 0.1, 0.1)], np.float64)
    flat = np.array([(0, 0, 0), (0.1, 0, 0), (0, 0, 0.1), (0.1, 0, 0.1)], np.float64)
    quads = np.array([[0, 1, 2], [2, 1, 3], [4, 5, 6], [6, 5, 7]])
    blades = BladeDepths.of(np.concatenate([upright, flat]), np.zeros((8, 2)), quads)
    assert np.isclose(blades.column(), 0.01 * 2 / np.pi)
    assert np.isclose(blades.column(0.05), 0.5 * 0.01 * 2 / np.pi)  # one of its two triangles
    assert blades.column(0.2) == 0.0
    side, top = blades.rows(0.1, 2)  # the lower row holds the flat square and half the other
    np.testing.assert_allclose(side, [0.005 * 2 / np.pi, 0.005 * 2 / np.pi])
    np.testing.assert_allclose(top, [0.01, 0.0])


def test_a_steep_view_meets_the_blades_area_from_above():
    """Campbell's ellipse: blades lying flat stop a vertical ray by their area from above and
    a level one not at all; upright ones the other way round (core/canopy.py row_depths)."""
    from core.canopy import BladeDepths

    flat = np.array([(0, 0.05, 0), (1, 0.05, 0), (0, 0.05, 1), (1, 0.05, 1)], np.float64)
    upright = np.array([(0, 0, 0.5), (0, 0.1, 0.5), (1, 0, 0.5), (1, 0.1, 0.5)], np.float64)
    quads = np.array([[0, 1, 2], [2, 1, 3]])
    stack = [slices([(0.0, 1.0, 0.0, 0.5)] * 4)]
    lying = Canopy.of(stack, 0.1, BladeDepths.of(flat, np.zeros((4, 2)), quads))
    standing = Canopy.of(stack, 0.1, BladeDepths.of(upright, np.zeros((4, 2)), quads))
    steep, level = np.radians(89.9), np.radians(0.5)
    assert lying.row_depths(steep).sum() == pytest.approx(1.0, rel=1e-3)
    assert lying.row_depths(level).sum() == pytest.approx(1.0, rel=1e-3)  # still the area
    assert standing.row_depths(steep).sum() < 0.01
    assert standing.row_depths(level).sum() == pytest.approx(0.1 * 2 / np.pi / np.tan(level))
