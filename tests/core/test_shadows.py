"""Blade shadows in core: the share of a cell's ground the blades' shadows cover, measured
from the patch (core/shadows.py), and the light's shadow settings."""

import dataclasses
import math

import numpy as np
import pytest

from core.lighting import Lighting
from core.params import PRESETS
from core.patch import generate_patch
from core.shadows import MIRRORS, STRETCHES, _outlines, cover, field, reach


def _sun(elevation: float, azimuth: float = 135.0) -> np.ndarray:
    return Lighting(sun_elevation=elevation, sun_azimuth=azimuth).sun_direction


def _shoelace(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


@pytest.mark.parametrize("elevation", [25.0, 50.0, 75.0])
def test_one_blades_shadow_covers_the_area_of_its_outline_along_the_sun(elevation):
    """A patch of one blade: what its shadow covers is the area of its outline moved along the
    sun onto the ground (the shoelace formula), within the raster's resolution."""
    params = PRESETS[sorted(PRESETS)[0]].replace(blade_count=1, tilt_min=0.0, tilt_max=0.0)
    patch = generate_patch(params)
    sun = _sun(elevation)
    outline, _ = _outlines(patch)
    ground = outline[0][:, [0, 2]] - outline[0][:, 1:2] * sun[[0, 2]] / sun[1]
    area = _shoelace(ground)
    got = cover(patch, sun, mirrored=False, raster=1024)
    assert got[0] == 0.0 and got[-1] == pytest.approx(area, rel=0.08)


@pytest.mark.parametrize("stretch", [0.5, 2.0])
def test_a_slope_stretches_a_blades_whole_shadow_along_the_sun(stretch):
    """On a slope the ground's plane maps a blade's shadow by a map of determinant k along the
    sun, its footprint too: a lone blade's shadow in the field drawn k times as long covers k
    times the ground (a tilted blade, so its footprint counts)."""
    params = PRESETS[sorted(PRESETS)[0]].replace(blade_count=1, tilt_min=30.0, tilt_max=30.0)
    patch = generate_patch(params)
    f = field(patch, _sun(50.0), mirrored=False, stretches=(1.0, stretch), raster=1024)
    level, slope = f[0, 0, -1].mean(), f[0, 1, -1].mean()
    assert level > 0.0 and slope == pytest.approx(stretch * level, rel=0.05)


def test_the_field_says_where_the_shadows_fall_and_its_mean_is_the_cover():
    """Per mirror state and density the field's mean over the cell is `cover`'s share; each
    mirror state's field is the first one's mirrored (the blades mirrored, the sun not: the
    sun along a diagonal, so that the mirrored shadows fall elsewhere)."""
    patch = generate_patch(PRESETS[sorted(PRESETS)[0]].replace(blade_count=300))
    sun = _sun(40.0, azimuth=135.0)
    f = field(patch, sun, stretches=STRETCHES)
    assert f.shape[:3] == (len(MIRRORS), len(STRETCHES), 17)
    assert np.allclose(f[:, 1].mean(axis=(0, 2, 3)), cover(patch, sun), atol=1e-6)
    assert np.all(np.diff(f, axis=2) >= 0)  # more blades, more shadow, everywhere
    # the field is not one value spread over the cell: the shadows fall in places
    assert f[0, 1, -1].std() > 0.1
    # two mirror states put them in different places
    assert np.abs(f[0, 1, -1] - f[1, 1, -1]).mean() > 0.1


def test_a_blades_outline_follows_its_masks_curve_between_the_strips_rows():
    """The blade texture's mask narrows the blade along a curve, not straight from row to row:
    the outline, sampled between the rows, covers more than its rows alone say (the mask
    bulges), and about as much as sampled twice as finely."""
    patch = generate_patch(PRESETS[sorted(PRESETS)[0]].replace(blade_count=50, subdivisions=3))

    def area(steps: int) -> float:
        outline, _ = _outlines(patch, steps)
        n = outline.shape[1] // 2
        left, right = outline[:, :n], outline[:, n:][:, ::-1]
        width = np.linalg.norm(right - left, axis=-1)
        run = np.linalg.norm(np.diff(0.5 * (left + right), axis=1), axis=-1)
        return float((0.5 * (width[:, 1:] + width[:, :-1]) * run).sum())

    assert area(4) > 1.02 * area(1)
    assert area(8) == pytest.approx(area(4), rel=0.01)


def test_the_lower_the_sun_the_more_ground_lies_in_shadow_and_density_adds_to_it():
    patch = generate_patch(PRESETS[sorted(PRESETS)[0]].replace(blade_count=400))
    low, high = cover(patch, _sun(20.0)), cover(patch, _sun(70.0))
    assert np.all(np.diff(low) >= 0) and np.all(np.diff(high) >= 0)  # more blades, more shadow
    assert low[0] == 0.0 and 0.0 < high[-1] < low[-1] <= 1.0
    # a sun that has set casts shadows as long as one 5° above the horizon
    assert np.allclose(cover(patch, _sun(-5.0)), cover(patch, _sun(5.0)), atol=0.02)


def test_the_shadows_union_is_no_more_than_the_sum_of_the_blades():
    """Overlapping shadows count once: the share for all blades is below the sum of each
    half's share."""
    patch = generate_patch(PRESETS[sorted(PRESETS)[0]].replace(blade_count=800))
    c = cover(patch, _sun(30.0))
    half = c[len(c) // 2]  # the blades below threshold ½: about half of them
    assert c[-1] < 2.0 * half


def test_the_light_keeps_its_shadow_settings_and_refuses_bad_ones(tmp_path):
    from app.scenes import get_scene
    from core.project_file import load_project, save_project

    doc = get_scene("patch-grid").document()
    assert not doc.light.blade_shadows  # off unless asked for
    doc.light = dataclasses.replace(doc.light, blade_shadows=True, shadow_strength=0.35)
    save_project(tmp_path / "lit.sward", doc)
    light = load_project(tmp_path / "lit.sward").light
    assert light.blade_shadows is True and math.isclose(light.shadow_strength, 0.35)
    with pytest.raises(ValueError, match="shadow_strength"):
        Lighting(shadow_strength=1.5)
    with pytest.raises(ValueError, match="blade_shadows"):
        Lighting(blade_shadows=1.0)


def test_shadows_come_from_a_third_of_the_way_up_tapering_upright_blades():
    """reach: the height of the blades' outlines' centroid. Upright blades narrowing to their
    tips have it below half their length and above a third of it less the tip's narrowing;
    blades twice as long reach twice as far."""
    upright = PRESETS["short-cut turf"].replace(tilt_min=0.0, tilt_max=0.0, bending=0.0)
    patch = generate_patch(upright)
    length = 0.5 * (upright.length_min + upright.length_max)
    assert 0.25 * length < reach(patch) < 0.5 * length
    longer = upright.replace(
        length_min=2 * upright.length_min,
        length_max=2 * upright.length_max,
        patch_height=2 * upright.patch_height,
    )
    assert reach(generate_patch(longer)) == pytest.approx(2 * reach(patch), rel=0.05)
