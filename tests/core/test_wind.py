"""The wind field and the blade bend (core/wind.py): roots stay, blades keep their length, gusts
travel with the wind, the field is off when the wind is."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core.params import PRESETS
from core.patch import generate_patch
from core.wind import (
    MAX_LEAN,
    Wind,
    bend,
    bend_vertices,
    curve_length,
    curve_point,
    curve_tangent,
    lean,
    noise_map,
    preset_of,
    sample_noise,
)
from core.wind import PRESETS as WIND_PRESETS

POINTS = np.random.default_rng(3).uniform(-40.0, 40.0, (4000, 2))


def _polyline_length(points: np.ndarray) -> np.ndarray:
    return np.linalg.norm(np.diff(points, axis=-2), axis=-1).sum(axis=-1)


def test_no_wind_no_lean():
    assert not np.any(lean(Wind(enabled=False, gust_strength=0.9), POINTS, 3.0))


def test_gusts_travel_with_the_wind():
    """With turbulence off, the gust pattern at t is the pattern at 0 moved downwind by
    speed · t: what a blade feels now, one downwind of it feels t seconds later."""
    wind = Wind(enabled=True, turbulence_strength=0.0, direction=70.0, speed=3.0)
    t = 1.7
    later = lean(wind, POINTS + wind.heading * wind.speed * t, t)
    assert np.allclose(later, lean(wind, POINTS, 0.0), atol=1e-9)
    # and it does change in place over time
    assert np.abs(lean(wind, POINTS, t) - lean(wind, POINTS, 0.0)).max() > 0.05


def test_gusts_lean_downwind_and_vary():
    wind = Wind(enabled=True, turbulence_strength=0.0, direction=120.0, gust_strength=0.5)
    w = lean(wind, POINTS, 0.0)
    along = w @ wind.heading
    across = w @ np.array([-wind.heading[1], wind.heading[0]])
    assert np.all(along >= -1e-12) and np.allclose(across, 0.0, atol=1e-12)
    # calm between gusts, strong in one
    assert along.min() < 0.15 and along.max() > 0.35


def test_lean_is_bounded():
    wind = Wind(enabled=True, gust_strength=0.9, turbulence_strength=0.5)
    size = np.linalg.norm(lean(wind, POINTS, 2.0), axis=-1)
    assert size.max() <= MAX_LEAN + 1e-9


def test_noise_map_tiles_and_samples_like_gl():
    tex = noise_map()
    n = tex.shape[0]
    # at a texel centre the sample is that texel
    i, j = 5, 17
    assert np.allclose(sample_noise(np.array([(i + 0.5) / n, (j + 0.5) / n])), tex[j, i])
    # one repeat further: the same
    uv = np.random.default_rng(0).uniform(-3, 3, (100, 2))
    assert np.allclose(sample_noise(uv), sample_noise(uv + np.array([2.0, -1.0])))
    assert tex.min() >= -1.0 and tex.max() <= 1.0 and tex.std() > 0.2


@pytest.mark.parametrize("scale", [4.0, 10.0])
def test_a_gust_is_about_gust_scale_across(scale):
    """Blades a tenth of gust_scale apart lean alike; half a gust_scale apart, much less so."""
    wind = Wind(enabled=True, turbulence_strength=0.0, gust_scale=scale)
    here = lean(wind, POINTS, 0.0)[:, 0]
    near = lean(wind, POINTS + np.array([0.1 * scale, 0.0]), 0.0)[:, 0] - here
    far = lean(wind, POINTS + np.array([0.5 * scale, 0.0]), 0.0)[:, 0] - here
    assert np.abs(near).mean() < 0.4 * np.abs(far).mean()


@pytest.mark.parametrize("preset", sorted(PRESETS))
@pytest.mark.parametrize("strength", [0.2, 0.5, 0.9])
def test_bent_blades_keep_root_and_length(preset, strength):
    patch = generate_patch(PRESETS[preset].replace(blade_count=300))
    s = patch.params.subdivisions
    per_blade = patch.vertices.reshape(patch.blade_count, s + 1, 2)[:, 0, 0]
    c1, c2 = per_blade["ctrl1"].astype(float), per_blade["ctrl2"].astype(float)
    direction = np.random.default_rng(1).normal(size=(patch.blade_count, 2))
    w = strength * direction / np.linalg.norm(direction, axis=1, keepdims=True)
    b1, b2 = bend(c1, c2, w)
    t = np.linspace(0.0, 1.0, 33)[None, :]
    rest = curve_point(c1[:, None], c2[:, None], t)
    bent = curve_point(b1[:, None], b2[:, None], t)
    assert np.allclose(bent[:, 0], 0.0)  # the root stays where it was
    ratio = _polyline_length(bent) / _polyline_length(rest)
    assert np.all(np.abs(ratio - 1.0) < 0.01)  # a bent blade does not stretch
    # and it does bend: the tip moves with the wind
    moved = (b2 - c2)[:, [0, 2]]
    assert np.all(np.einsum("ij,ij->i", moved, w) > 0.0)


def test_patch_control_points_trace_the_blades():
    """The vertices lie on their blade's curve (plus half the width across it)."""
    patch = generate_patch(PRESETS["long thin meadow grass"].replace(blade_count=200))
    s = patch.params.subdivisions
    v = patch.vertices.reshape(patch.blade_count, s + 1, 2)
    centre = 0.5 * (v["position"][:, :, 0] + v["position"][:, :, 1]).astype(float)
    root = np.stack([v["root"][:, 0, 0, 0], np.zeros(patch.blade_count), v["root"][:, 0, 0, 1]], 1)
    t = v["uv"][:, :, 0, 1].astype(float)
    curve = curve_point(v["ctrl1"][:, :, 0].astype(float), v["ctrl2"][:, :, 0].astype(float), t)
    above = curve[..., 1] > 0.0  # the trajectory is clamped at the ground
    assert np.allclose((root[:, None, :] + curve)[above], centre[above], atol=1e-5)


def test_bent_vertices_turn_with_their_blade():
    """What the geometry shader draws, in numpy: the roots stay, the tips move with the wind,
    each normal turns with its blade's tangent (still at right angles to it), and no wind
    leaves the patch as it is."""
    patch = generate_patch(PRESETS["long thin meadow grass"].replace(blade_count=200))
    v = patch.vertices
    still_positions, still_normals = bend_vertices(v, np.zeros(2))
    assert np.allclose(still_positions, v["position"], atol=1e-6)
    assert np.allclose(still_normals, v["normal"], atol=1e-6)
    positions, normals = bend_vertices(v, np.array([0.0, 0.5]))
    t = v["uv"][:, 1]
    assert np.allclose(positions[t == 0.0], v["position"][t == 0.0], atol=1e-6)
    assert (positions[t == 1.0, 2] - v["position"][t == 1.0, 2]).min() > 0.0
    b1, b2 = bend(v["ctrl1"].astype(float), v["ctrl2"].astype(float), np.array([[0.0, 0.5]]))
    tangent = curve_tangent(b1, b2, t.astype(float))
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    rest = curve_tangent(v["ctrl1"].astype(float), v["ctrl2"].astype(float), t.astype(float))
    rest /= np.linalg.norm(rest, axis=1, keepdims=True)
    before = np.einsum("ij,ij->i", v["normal"].astype(float), rest)
    after = np.einsum("ij,ij->i", normals, tangent)
    assert np.allclose(after, before, atol=1e-5)  # the angle to the blade is kept
    assert np.abs(normals - v["normal"]).max() > 0.1  # and the normals did turn


def test_curve_length_of_a_straight_blade():
    c2 = np.array([0.3, 0.4, 0.0])
    assert np.isclose(curve_length(0.5 * c2, c2), 0.5)


@settings(max_examples=60, deadline=None)
@given(
    direction=st.floats(-360, 360),
    speed=st.floats(0, 30),
    gust=st.floats(0, 0.9),
    turbulence=st.floats(0, 0.5),
)
def test_any_valid_wind_round_trips(direction, speed, gust, turbulence):
    wind = Wind(True, direction, speed, gust, 8.0, turbulence, 1.5)
    assert Wind.from_dict(wind.to_dict()) == wind


@pytest.mark.parametrize(
    "changes, message",
    [
        ({"gust_strength": 1.5}, "gust_strength"),
        ({"speed": -1.0}, "speed"),
        ({"gust_scale": float("nan")}, "gust_scale"),
        ({"enabled": 1}, "enabled"),
        ({"turbulence_scale": "big"}, "turbulence_scale"),
        ({"blade_reach": 0.5}, "blade_reach"),
    ],
)
def test_impossible_winds_are_refused(changes, message):
    with pytest.raises(ValueError, match=message):
        Wind(**changes)
    with pytest.raises(ValueError, match="unknown field"):
        Wind.from_dict({"gale": 3})


def test_wind_presets_rise_from_breeze_to_storm_and_are_recognised():
    """The Wind dock's presets: the light breeze bends the blades least and the storm most, and
    a wind with a preset's values is named by it (the default wind is "gusty")."""
    means = []
    for name, values in WIND_PRESETS.items():
        wind = Wind(enabled=True, direction=45.0, **values)  # a valid wind
        assert preset_of(wind) == name
        means.append(np.linalg.norm(lean(wind, POINTS, 1.0), axis=-1).mean())
    assert list(WIND_PRESETS) == ["light breeze", "gusty", "storm"]
    assert means[0] < means[1] < means[2]
    assert preset_of(Wind()) == "gusty"
    assert preset_of(Wind(gust_strength=0.36)) is None
