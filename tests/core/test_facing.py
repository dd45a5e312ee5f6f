"""The blades' mean diffuse factor by view direction (core/facing.py)."""

import numpy as np

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
