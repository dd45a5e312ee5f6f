"""The blades' mean diffuse factor with the light kept apart (core/light_moments.py): for every
light, the small product of a patch's sums gives the tables the exact sums over its blades do."""

import numpy as np
import pytest

from core.facing import facing_lambert, facing_moments
from core.light_moments import LightMoments
from core.lighting import Lighting
from core.params import PRESETS, PatchParams
from core.patch import generate_patch

PATCHES = {
    "default": PatchParams(seed=4),
    "upright": PatchParams(seed=4, tilt_min=0.0, tilt_max=0.0),
    **{name: params.replace(seed=4) for name, params in PRESETS.items()},
}


@pytest.mark.parametrize("name", sorted(PATCHES))
def test_every_light_lights_a_patch_as_its_blades_do(name):
    v = generate_patch(PATCHES[name]).vertices
    sums = facing_moments(v["normal"])
    # upright blades under a high sun are lit edge-on, where the polynomial's kink shows (below)
    high = (75.0,) if name != "upright" else ()
    for elevation in (-5.0, 20.0, 60.0, *high):
        for azimuth in (0.0, 200.0):
            light = Lighting(sun_elevation=elevation, sun_azimuth=azimuth)
            for translucency in (0.0, 1.0):  # the factor is linear in it
                exact = facing_lambert(v["normal"], light.sun_direction, translucency)
                kept = sums.lit(light.sun_direction, translucency)
                assert np.abs(kept - exact).max() < 2e-3, (elevation, azimuth, translucency)


def test_upright_blades_under_the_zenith_are_lit_edge_on_within_the_stated_error():
    v = generate_patch(PATCHES["upright"]).vertices
    sun = Lighting(sun_elevation=90.0).sun_direction
    exact = facing_lambert(v["normal"], sun, 0.35)
    kept = facing_moments(v["normal"]).lit(sun, 0.35)
    assert exact.max() < 0.01  # edge-on
    assert np.abs(kept - exact).max() < 0.035  # the polynomial's kink error (module docstring)


def test_the_linear_part_is_exact_and_both_faces_of_a_normal_share_the_sums():
    rng = np.random.default_rng(2)
    n = rng.normal(size=(300, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    e = np.array([[0.0, 1.0, 0.0], [0.6, 0.0, 0.8]])
    w = np.abs(n @ e.T)
    sums = LightMoments.of(n, w, np.sign(n @ e.T))
    flipped = LightMoments.of(-n, w, np.sign(-n @ e.T))
    light = np.array([0.36, 0.48, 0.8])
    np.testing.assert_allclose(sums.lit(light, 0.2), flipped.lit(light, 0.2), atol=1e-12)
    # with translucency 1 the factor is |n · L| alone; with 0 a face lit from behind is dark
    lit_both = (w * np.abs(n @ light)[:, None]).sum(0) / w.sum(0)
    assert np.abs(sums.lit(light, 1.0) - lit_both).max() < 2e-3


def test_no_normals_light_nothing_and_change_no_slope():
    from core.canopy import Canopy
    from core.slopes import slope_tables

    sun = Lighting().sun_direction
    assert not facing_moments(np.zeros((4, 3))).lit(sun, 0.3).any()
    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = 0.3
    table = slope_tables(
        np.zeros((5, 3)), np.zeros((5, 3)), np.zeros((5, 2)), Canopy.of([stack], 1.0), sun, 0.3
    )
    np.testing.assert_array_equal(table, 1.0)


@pytest.mark.parametrize("name", sorted(PATCHES))
def test_sums_kept_in_single_precision_light_as_the_double_ones(name):
    """The sums kept on disk and in memory are single precision (render/derived_cache.py);
    their product with the light's coefficients stays in it, and every entry of the table
    agrees with double precision's to a millionth."""
    v = generate_patch(PATCHES[name]).vertices
    double = facing_moments(v["normal"])
    single = LightMoments(*(a.astype(np.float32) for a in (double.powers, double.signed,
                                                           double.total)))  # fmt: skip
    for elevation in (-5.0, 20.0, 60.0, 89.0):
        light = Lighting(sun_elevation=elevation, sun_azimuth=130.0)
        for translucency in (0.0, 0.6):
            a = single.lit(light.sun_direction, translucency)
            b = double.lit(light.sun_direction, translucency)
            assert np.abs(a - b).max() < 1e-6, (elevation, translucency)


@pytest.mark.parametrize("name", sorted(PATCHES))
def test_sums_seen_through_the_canopy_light_as_the_blades_do(name):
    """facing_moments with `seen` (the image-based grass's table: each vertex as far as a view
    reaches it through the blades above) against facing_lambert's sum over the same normals."""
    from core.canopy import Canopy

    patch = generate_patch(PATCHES[name])
    v = patch.vertices
    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = 0.35
    seen = (v["position"][:, 1], Canopy.of([stack], patch.height))
    sums = facing_moments(v["normal"], seen=seen)
    for elevation in (-5.0, 20.0, 60.0):
        for translucency in (0.0, 0.7):
            light = Lighting(sun_elevation=elevation, sun_azimuth=200.0)
            exact = facing_lambert(v["normal"], light.sun_direction, translucency, seen=seen)
            kept = sums.lit(light.sun_direction, translucency)
            assert np.abs(kept - exact).max() < 2e-3, (elevation, translucency)
