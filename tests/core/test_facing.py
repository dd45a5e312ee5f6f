"""The blades' mean diffuse factor by view direction (core/facing.py)."""

import numpy as np
import pytest

from core.facing import directions, facing_lambert


def test_one_blade_lights_from_the_front_and_through_from_behind():
    light = np.array([1.0, 0.0, 0.0])
    table = facing_lambert(np.array([[1.0, 0.0, 0.0]]), light, translucency=0.35)
    e = directions()
    front, behind = e[..., 0] > 0.2, e[..., 0] < -0.2
    np.testing.assert_allclose(table[front], 1.0, atol=1e-6)  # the face turned to the viewer
    np.testing.assert_allclose(table[behind], 0.35, atol=1e-6)  # light passed through


def test_two_sided_a_normal_and_its_negation_light_alike():
    rng = np.random.default_rng(3)
    n = rng.normal(size=(500, 3))
    light = np.array([0.3, 0.8, -0.5]) / np.linalg.norm([0.3, 0.8, -0.5])
    np.testing.assert_allclose(
        facing_lambert(n, light, 0.2), facing_lambert(-n, light, 0.2), atol=1e-6
    )


def test_upright_blades_seen_level_match_the_closed_form():
    """Horizontal normals of every azimuth, seen level from azimuth ψ with the sun level at
    azimuth β: the visible faces turn to the viewer and cover in proportion to cos(φ − ψ), so
    L = ½ [P + t (P − π/2 cos δ)] with P = ½ sin δ + ½ (π − δ) cos δ and δ = |β − ψ|."""
    phi = np.linspace(0, 2 * np.pi, 20000, endpoint=False)
    normals = np.stack([np.sin(phi), np.zeros_like(phi), np.cos(phi)], -1)
    t, beta = 0.35, np.radians(135.0)
    light = np.array([np.sin(beta), 0.0, np.cos(beta)])
    table = facing_lambert(normals, light, t, azimuths=16, elevations=64)
    psi = 2 * np.pi * (np.arange(16) + 0.5) / 16
    delta = np.abs((beta - psi + np.pi) % (2 * np.pi) - np.pi)
    p = 0.5 * np.sin(delta) + 0.5 * (np.pi - delta) * np.cos(delta)
    expected = 0.5 * (p + t * (p - 0.5 * np.pi * np.cos(delta)))
    np.testing.assert_allclose(table[0], expected, atol=0.01)  # the lowest row: ~0.7 degrees up


def test_no_normals_no_light():
    assert not facing_lambert(np.zeros((4, 3)), np.array([0.0, 1.0, 0.0]), 0.3).any()


def test_blades_hidden_below_the_canopy_count_less_the_flatter_the_view():
    """Lower parts facing the sky, tips facing sideways, a sun overhead: seen through the
    blades above them, a level view meets the tips alone, a steep one the lower parts too."""
    from core.canopy import Canopy

    light = np.array([0.0, 1.0, 0.0])
    up, side = [0.0, 1.0, 0.0], [0.8, 0.0, 0.6]
    normals = np.array([up] * 50 + [side] * 50)
    heights = np.array([0.1] * 50 + [0.95] * 50)
    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = 0.3
    canopy = Canopy.of([stack], 1.0)
    plain = facing_lambert(normals, light, 0.0)
    seen = facing_lambert(normals, light, 0.0, seen=(heights, canopy))
    tips = facing_lambert(normals[50:], light, 0.0)  # 0: lit edge-on
    assert plain[0].mean() > 0.05  # unoccluded, the lit lower parts count even seen level
    assert seen[0].mean() < 0.2 * plain[0].mean()
    np.testing.assert_allclose(seen[0], tips[0], atol=0.02)
    assert seen[-1].mean() > 2.0 * seen[0].mean()


def _uniform_canopy(height: float = 1.0):
    from core.canopy import Canopy

    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = 0.3
    return Canopy.of([stack], height)


def test_slope_ratios_are_one_on_flat_ground():
    from core.slopes import ACROSS, SLOPES, slope_tables

    rng = np.random.default_rng(5)
    normals = rng.normal(size=(400, 3))
    roots = rng.uniform(0, 1, size=(400, 2))
    positions = np.column_stack([roots[:, 0], rng.uniform(0, 1, 400), roots[:, 1]])
    positions[:, [0, 2]] += rng.normal(scale=0.1, size=(400, 2))
    light = np.array([0.3, 0.8, -0.5]) / np.linalg.norm([0.3, 0.8, -0.5])
    table = slope_tables(normals, positions, roots, _uniform_canopy(), light, 0.3)
    assert table.shape == (ACROSS, SLOPES, 8, 32, 2)
    np.testing.assert_allclose(table[ACROSS // 2, SLOPES // 2], 1.0, atol=1e-5)  # both layers
    assert (np.abs(table - 1.0).max(axis=(0, 1, 2, 3)) > 0.02).all()  # and both move off flat


def test_upright_blades_on_a_slope_show_the_parts_that_lean_down_it():
    """Seen from -z, tips leaning away from the eye face the sky (lit by a sun overhead), tips
    leaning towards it face sideways (lit edge-on: dark). Where the ground rises away from the
    eye, the tips leaning up the slope come close to it and hide: upright blades are darker than
    blades sheared with the ground (ratio < 1; the volume's layer) and than upright blades on
    flat ground (the image-based grass's layer); where it falls away, brighter (> 1)."""
    from core.slopes import ACROSS, SLOPES, slope_tables

    k = 200
    roots = np.zeros((2 * k, 2))
    up, side = [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]
    normals = np.array([up] * k + [side] * k)
    positions = np.array([[0.0, 0.5, 0.3]] * k + [[0.0, 0.5, -0.3]] * k)  # away, towards
    table = slope_tables(normals, positions, roots, _uniform_canopy(), np.array([0, 1.0, 0]), 0.0)
    towards_minus_z = 15  # a column beside azimuth 180 degrees (174.4): the eye at -z
    for layer in (0, 1):
        # the second row: ~17 degrees over the horizon; no rise across the view
        low = table[ACROSS // 2, :, 1, towards_minus_z, layer]
        assert low[SLOPES // 2] == 1.0
        assert (low[SLOPES // 2 + 1 :] < 0.97).all(), (layer, low)  # rising away: darker
        assert (low[: SLOPES // 2] > 1.03).all(), (layer, low)  # falling away: brighter


def test_upright_blades_on_ground_rising_across_the_view_show_the_parts_that_lean_down_it():
    """Seen from -z (looking towards +z, the viewer's right is -x), tips leaning to the right
    face the sky (lit by a sun overhead), tips leaning to the left face sideways (dark). Where
    the ground rises to the right, the tips leaning up it come close to it and hide: darker
    than flat ground; where it falls to the right, brighter. A hillside seen obliquely has
    both rises: with the rise along the view alone the model was 4.5 % too dark there
    (core/facing.py)."""
    from core.slopes import ACROSS, SLOPES, slope_tables

    k = 200
    roots = np.zeros((2 * k, 2))
    up, side = [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]
    normals = np.array([up] * k + [side] * k)
    positions = np.array([[-0.3, 0.5, 0.0]] * k + [[0.3, 0.5, 0.0]] * k)  # right, left
    table = slope_tables(normals, positions, roots, _uniform_canopy(), np.array([0, 1.0, 0]), 0.0)
    towards_minus_z = 15  # a column beside azimuth 180 degrees (174.4): the eye at -z
    for layer in (0, 1):
        across = table[:, SLOPES // 2, 1, towards_minus_z, layer]  # no rise along the view
        assert across[ACROSS // 2] == 1.0
        assert (across[ACROSS // 2 + 1 :] < 0.97).all(), (layer, across)  # rising to the right
        assert (across[: ACROSS // 2] > 1.03).all(), (layer, across)  # falling to the right


@pytest.mark.parametrize("preset", [None, "short-cut turf", "long thin meadow grass"])
def test_the_bend_coefficients_light_the_blades_as_the_wind_bends_them(preset):
    """L + G · λ + ½ λᵀ H λ against the table of the patch bent by λ (core/wind.py, as the
    blades' shader bends it), within the leans the coefficients span; the lean changes the
    light several times more than the coefficients miss."""
    from core.facing import bend_coefficients
    from core.params import PRESETS, PatchParams
    from core.patch import generate_patch
    from core.wind import bend_vertices

    params = PatchParams(seed=4) if preset is None else PRESETS[preset].replace(seed=4)
    v = generate_patch(params).vertices
    light = np.array([0.5, 0.64, -0.58]) / np.linalg.norm([0.5, 0.64, -0.58])
    rest = facing_lambert(v["normal"], light, 0.35)
    c = bend_coefficients(v, light, 0.35)
    for lean in ([0.2, 0.0], [0.0, -0.25], [0.3, 0.17], [-0.2, 0.25]):
        x, z = lean
        predicted = rest + x * c[..., 0] + z * c[..., 1]
        predicted += 0.5 * (c[..., 2] * x * x + 2.0 * c[..., 3] * x * z + c[..., 4] * z * z)
        bent = facing_lambert(bend_vertices(v, np.array(lean))[1], light, 0.35)
        rows = slice(0, 6)  # the views of far grass: up to 62° (the top rows see blades end-on)
        change = np.abs(bent - rest)[rows].max()
        assert change > 0.02, f"{lean}: the bend changes the light by {change:.3f} only"
        assert np.abs(predicted - bent)[rows].max() < 0.35 * change, lean
