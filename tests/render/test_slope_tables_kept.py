"""The slope-ratio tables' sums over the blades (core/slopes.py slope_moments_table) take a
quarter of a second to build, and each renderer of a grass type has its own texture of them: render/facing.py
keeps the last few by the patch and canopy they are of, and a light change is a small product
of the same sums. Kept sums must never stand in for another patch or canopy, and the tables of
another light must differ."""

from __future__ import annotations

import dataclasses

import numpy as np

from core.canopy import Canopy
from core.lighting import Lighting
from core.params import PatchParams
from core.patch import generate_patch
from core.slopes import slope_ratios
from render.facing import kept_slope_moments


def kept_slope_tables(patch, canopy: Canopy, light: Lighting) -> np.ndarray:
    """The tables a SlopeTable writes for this patch, canopy and light."""
    sums = kept_slope_moments(patch, canopy)
    assert sums is not None
    return slope_ratios(sums, light.sun_direction, light.translucency)


def _canopy(alpha: float) -> Canopy:
    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = alpha
    return Canopy.of([stack], 0.3)


def test_sums_are_built_once_for_a_patch_and_canopy_and_every_light_uses_them():
    patch = generate_patch(PatchParams(blade_count=300))
    light = Lighting(sun_azimuth=315.0)
    canopy = _canopy(0.3)
    first = kept_slope_tables(patch, canopy, light)
    sums = kept_slope_moments(patch, canopy)
    assert kept_slope_moments(patch, canopy) is sums  # kept, not built again
    same_patch = dataclasses.replace(patch, vertices=patch.vertices.copy())
    assert kept_slope_moments(same_patch, _canopy(0.3)) is sums  # the same content
    turned_sun = dataclasses.replace(light, sun_azimuth=45.0)
    kept_slope_tables(patch, canopy, turned_sun)
    assert kept_slope_moments(patch, canopy) is sums  # a light change builds nothing
    np.testing.assert_array_equal(kept_slope_tables(same_patch, _canopy(0.3), light), first)

    turned = kept_slope_tables(patch, canopy, dataclasses.replace(light, sun_azimuth=45.0))
    denser = kept_slope_tables(patch, _canopy(0.6), light)
    other = generate_patch(PatchParams(blade_count=300, seed=7))
    regrown = kept_slope_tables(other, canopy, light)
    for table in (turned, denser, regrown):
        assert np.abs(table - first).max() > 1e-3  # a table of its own, not the kept one


def test_the_designers_render_processes_hand_each_other_the_sums(tmp_path, monkeypatch):
    """What one render process built, the other reads from the folder they share (render/
    derived_cache.py) rather than building it again; without that folder nothing is written."""
    from render import derived_cache, facing

    patch = generate_patch(PatchParams(blade_count=200, seed=3))
    canopy = _canopy(0.4)
    light = Lighting(sun_azimuth=200.0)
    monkeypatch.setattr(facing, "_kept", facing.OrderedDict())  # this process keeps nothing
    built = kept_slope_tables(patch, canopy, light)
    assert not list(tmp_path.iterdir())  # no folder named: nothing shared

    monkeypatch.setenv(derived_cache.SHARED_DIR_ENV, str(tmp_path))
    monkeypatch.setattr(facing, "_kept", facing.OrderedDict())
    kept_slope_tables(patch, canopy, light)  # built, and handed over
    assert len(list(tmp_path.glob("slope-*.npz"))) == 1
    monkeypatch.setattr(facing, "_kept", facing.OrderedDict())  # the other process
    handed = kept_slope_moments(patch, canopy, build=False)  # a draft: read, never built
    assert handed is not None
    tables = slope_ratios(handed, light.sun_direction, light.translucency)
    np.testing.assert_allclose(tables, built, atol=1e-5)
    # another patch is not handed the first one's sums
    other = generate_patch(PatchParams(blade_count=200, seed=4))
    assert kept_slope_moments(other, canopy, build=False) is None


def test_facing_sums_come_back_with_a_patch_of_the_same_content():
    """An undo of a blade edit regenerates the patch before it: its facing sums are kept."""
    from render.facing import kept_facing_moments

    patch = generate_patch(PatchParams(blade_count=250, seed=5))
    canopy = _canopy(0.3)
    sums = kept_facing_moments(patch, canopy)
    again = generate_patch(PatchParams(blade_count=250, seed=5))  # regenerated: a new object
    assert again is not patch and kept_facing_moments(again, canopy) is sums
    assert kept_facing_moments(patch, None) is not sums  # seen through no canopy: its own
    other = kept_facing_moments(generate_patch(PatchParams(blade_count=250, seed=6)), canopy)
    light = Lighting().sun_direction
    assert np.abs(other.lit(light, 0.3) - sums.lit(light, 0.3)).max() > 1e-3
