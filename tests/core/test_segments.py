"""Blade segments fewer with distance (core/segments.py): each level's chords stay within the
error bound the level is chosen by, a leaving vertex's colour is its chord's, and the level
rises with distance within the tolerance on screen."""

import numpy as np
import pytest

from core import segments
from core.params import PRESETS, PatchParams
from core.patch import generate_patch
from core.wind import curve_point


@pytest.mark.parametrize("preset", sorted(PRESETS))
@pytest.mark.parametrize("subdivisions", [2, 3, 5, 8])
def test_a_levels_chords_stay_within_its_error_bound(preset, subdivisions):
    """Sampling each blade's curve at level k's rows strays at most e₀ 4^k from it, e₀ from
    the patch's largest |g| (the bound the level is chosen by)."""
    patch = generate_patch(PRESETS[preset].replace(blade_count=60, subdivisions=subdivisions))
    c1 = patch.vertices["ctrl1"][::2].reshape(60, -1, 3)[:, 0].astype(np.float64)
    c2 = patch.vertices["ctrl2"][::2].reshape(60, -1, 3)[:, 0].astype(np.float64)
    g = segments.curvature(c1, c2)
    e0 = g / (4.0 * subdivisions**2)
    fine = np.linspace(0.0, 1.0, 257)
    curve = curve_point(c1[:, None], c2[:, None], fine[None, :])
    for level in range(segments.level_count(subdivisions)):
        t = segments.level_rows(subdivisions, level) / subdivisions
        knots = curve_point(c1[:, None], c2[:, None], t[None, :])
        chord = np.stack(
            [
                np.stack([np.interp(fine, t, knots[b, :, a]) for a in range(3)], -1)
                for b in range(60)
            ]
        )
        worst = np.linalg.norm(chord - curve, axis=-1).max()
        assert worst <= e0 * 4**level * 1.0001 + 1e-9
        if level == 1:
            assert worst > 0.2 * e0 * 4**level  # the bound is not loose by orders


def test_a_leaving_vertex_takes_its_chords_colour_root_and_tip_keep_theirs():
    colors = np.random.default_rng(2).random((3, 6, 3))  # 5 segments: rows 0 … 5
    chord = segments.chord_colors(colors)
    lo, hi, share = segments.leaving(5)
    assert (lo[[0, 5]] == [0, 5]).all() and np.allclose(chord[:, [0, 5]], colors[:, [0, 5]])
    assert (lo[1], hi[1], share[1]) == (0, 2, 0.5)  # leaves at level 0 → 1: rows 0, 2
    assert np.allclose(chord[:, 1], 0.5 * (colors[:, 0] + colors[:, 2]))
    assert (lo[2], hi[2], share[2]) == (0, 4, 0.5)  # leaves at level 1 → 2: rows 0, 4
    assert (lo[4], hi[4]) == (0, 5)  # leaves at level 2 → 3: the root and the tip alone
    patch = generate_patch(PatchParams(blade_count=4, subdivisions=5))
    assert np.allclose(
        patch.vertices["chord_color"].reshape(4, 6, 2, 3)[:, :, 0],
        segments.chord_colors(patch.vertices["color"].reshape(4, 6, 2, 3)[:, :, 0]),
    )


def test_the_level_rises_with_distance_and_keeps_the_chord_within_the_tolerance():
    s, g, pixel = 4, 0.1, np.radians(50) / 540
    scale = segments.error_scale(g, s, 1.0, pixel)
    count = segments.level_count(s)
    d = np.geomspace(0.1, 500.0, 400)
    f = segments.segment_level(d, scale, count)
    assert (np.diff(f) >= 0).all() and f[0] == 0 and f[-1] == count - 1
    e0 = g / (4 * s**2)
    on_screen = e0 * 4 ** np.floor(f) / (d * pixel)  # pixels
    coarser = f >= 1  # (near the eye the finest level is all there is)
    assert coarser.any() and on_screen[coarser].max() <= segments.TOLERANCE_PX * 1.0001
    assert on_screen[~coarser].max() > segments.TOLERANCE_PX  # the bound is what decides
    assert (segments.segment_level(d, scale, count, bias=1) >= np.minimum(f + 1, count - 1)).all()
    assert segments.error_scale(0.0, s, 1.0, pixel) == float("inf")  # straight: coarsest


def test_the_wind_bends_the_curve_further_so_segments_stay_finer():
    patch = generate_patch(PRESETS[sorted(PRESETS)[0]].replace(blade_count=50))
    v = patch.vertices
    rest, breeze, storm = (segments.curvature(v["ctrl1"], v["ctrl2"], x) for x in (0, 0.3, 0.9))
    assert rest < breeze < storm == segments.curvature(v["ctrl1"], v["ctrl2"], 5.0)


@pytest.mark.parametrize("lean", [0.2, 0.5, 0.9])
def test_a_bent_blades_curvature_stays_within_the_bound_for_its_lean(lean):
    """Every blade bent by `lean` in any direction (core/wind.py bend) keeps |g| within the
    curvature the segment levels are chosen by for that lean."""
    from core.wind import bend

    patch = generate_patch(PRESETS[sorted(PRESETS)[-1]].replace(blade_count=40))
    c1 = patch.vertices["ctrl1"].astype(np.float64)
    c2 = patch.vertices["ctrl2"].astype(np.float64)
    bound = segments.curvature(c1, c2, lean)
    for a in np.linspace(0.0, 2.0 * np.pi, 12, endpoint=False):
        b1, b2 = bend(c1, c2, np.tile([lean * np.cos(a), lean * np.sin(a)], (len(c1), 1)))
        assert np.linalg.norm(b2 - 2.0 * b1, axis=-1).max() <= bound + 1e-9


def test_an_instances_distance_is_to_its_nearest_point():
    from core.grid import INSTANCE_DTYPE

    cells = np.zeros(3, INSTANCE_DTYPE)
    cells["origin"] = [(0, 0), (10, 0), (0, 0)]
    cells["size"] = [(1, 1), (2, 2), (1, 1)]
    cells["ground"] = [(0, 0), (0, 0), (5, 1)]
    d = segments.cell_distance(np.array([0.5, 3.0, 0.5]), cells, 1.0, 0.5)
    assert d == pytest.approx([2.5, np.hypot(9.5, 2.5), 2.0])
