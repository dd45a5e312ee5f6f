"""The slope-ratio tables (core/facing.py slope_tables) take about a second to build, and each
renderer of a grass type has its own texture of them: render/facing.py keeps the last few by
what they are of. A kept table must never stand in for another patch, canopy or light."""

from __future__ import annotations

import dataclasses

import numpy as np

from core.canopy import Canopy
from core.lighting import Lighting
from core.params import PatchParams
from core.patch import generate_patch
from render.facing import kept_slope_tables


def _canopy(alpha: float) -> Canopy:
    stack = np.zeros((2, 8, 4, 4), np.float32)
    stack[..., 3] = alpha
    return Canopy.of([stack], 0.3)


def test_a_table_is_built_once_for_its_patch_canopy_and_light_and_again_when_one_changes():
    patch = generate_patch(PatchParams(blade_count=300))
    light = Lighting(sun_azimuth=315.0)
    canopy = _canopy(0.3)
    first = kept_slope_tables(patch, canopy, light)
    assert kept_slope_tables(patch, canopy, light) is first  # kept, not built again
    same_patch = dataclasses.replace(patch, vertices=patch.vertices.copy())
    assert kept_slope_tables(same_patch, _canopy(0.3), light) is first  # the same content

    turned = kept_slope_tables(patch, canopy, dataclasses.replace(light, sun_azimuth=45.0))
    denser = kept_slope_tables(patch, _canopy(0.6), light)
    other = generate_patch(PatchParams(blade_count=300, seed=7))
    regrown = kept_slope_tables(other, canopy, light)
    for table in (turned, denser, regrown):
        assert table is not first
        assert np.abs(table - first).max() > 1e-3  # a table of its own, not the kept one
