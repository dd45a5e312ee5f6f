"""Standalone-EGL renders of the patch grid, judged by image statistics."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core.params import PatchParams
from tests.conftest import coverage, covered, grass_mask

SIZE = (200, 150)
SCENE = get_scene("patch-grid")
PARAMS = SCENE.params.replace(blade_count=1200)


def document(params=PARAMS, density=1.0):
    return dataclasses.replace(SCENE, params=params, density=density).document()


def render(headless, params=PARAMS, density=1.0, camera="top", mode="geometry"):
    doc = document(params, density)
    return headless(doc, mode=mode).render(doc.camera(camera), SIZE)


def test_grid_is_covered_with_lit_grass(headless):
    image, stats = render(headless)
    assert coverage(image) > 0.5  # from above, the 8 × 8 grid fills most of the frame
    green = image[grass_mask(image)].mean(axis=0)
    assert green[1] > green[0] > green[2]  # green grass, lit (not black)
    assert green[1] > 60
    assert stats.c_g == 64 and stats.t_g_ms > 0 and stats.width == SIZE[0]


def test_halving_density_lowers_coverage(headless):
    bare, _ = render(headless, density=0.0, camera="top")
    full, _ = render(headless, density=1.0, camera="top")
    half, stats = render(headless, density=0.5, camera="top")
    # pixels that differ from the bare ground: thinner grass is also lighter at the roots (AO_blade
    # scales with density, eq. 6.11), so a colour test alone would count it twice
    assert covered(half, bare) < 0.85 * covered(full, bare)
    assert stats.blades == pytest.approx(0.5 * 64 * PARAMS.blade_count, rel=0.05)


def test_zero_density_shows_bare_ground(headless):
    image, _ = render(headless, density=0.0)
    assert coverage(image) < 0.01


def test_seed_changes_pixels_not_statistics(headless):
    a, _ = render(headless, camera="default")
    b, _ = render(headless, PARAMS.replace(seed=PARAMS.seed + 7), camera="default")
    assert np.mean(np.any(a != b, axis=-1)) > 0.1
    assert coverage(b) == pytest.approx(coverage(a), abs=0.03)
    assert np.abs(a.mean(axis=(0, 1)) - b.mean(axis=(0, 1))).max() < 4


def test_taller_grass_covers_more_at_grazing_view(headless):
    short, _ = render(
        headless,
        PatchParams(blade_count=1200, length_min=0.04, length_max=0.06, patch_height=0.1),
        camera="grazing",
    )
    tall, _ = render(headless, camera="grazing")
    assert coverage(tall) > coverage(short) + 0.05


def test_a_half_resolution_frame_shows_the_same_grass_without_msaa(headless):
    doc = document()
    renderer = headless(doc, mode="geometry")
    camera = doc.camera("default")
    full, _ = renderer.render(camera, SIZE)
    half, _ = renderer.render(camera, SIZE, half_resolution=True)
    assert coverage(half) == pytest.approx(coverage(full), abs=0.08)


def test_volume_representation_agrees_with_geometry(headless):
    """The same cells from the same camera, drawn as geometry and as ray-cast slices."""
    geo, _ = render(headless, camera="default")
    vol, stats = render(headless, camera="default", mode="volume")
    assert stats.c_v == 64 and stats.c_g == 0 and stats.t_v_ms > 0
    assert coverage(vol) == pytest.approx(coverage(geo), abs=0.08)
    g_mean = geo[grass_mask(geo)].mean(axis=0)
    v_mean = vol[grass_mask(vol)].mean(axis=0)
    assert np.abs(g_mean - v_mean).max() < 15  # mean grass colour within 15 of 255


def test_volume_density_thins_grass(headless):
    doc = document()
    renderer = headless(doc, mode="volume")
    full, _ = renderer.render(doc.camera("top"), SIZE)
    doc.density = 0.3
    thin, _ = renderer.render(doc.camera("top"), SIZE)
    assert coverage(thin) < 0.8 * coverage(full)


def test_image_representation_agrees_with_geometry_from_above(headless):
    geo, _ = render(headless)
    doc = document()
    renderer = headless(doc, mode="image")
    img, stats = renderer.render(doc.camera("top"), SIZE)
    doc.density = 0.2
    thin, _ = renderer.render(doc.camera("top"), SIZE)
    assert stats.c_i == 64 and stats.c_g == 0 and stats.t_i_ms > 0
    assert coverage(img) == pytest.approx(coverage(geo), abs=0.1)
    assert coverage(thin) < 0.6 * coverage(img)
    g_mean = geo[grass_mask(geo)].mean(axis=0)
    i_mean = img[grass_mask(img)].mean(axis=0)
    assert np.abs(g_mean - i_mean).max() < 20, (g_mean, i_mean)  # within 20 of 255


@pytest.mark.parametrize(
    ("only", "dominant"), [("geometry", "red"), ("volume", "yellow"), ("image", "blue")]
)
def test_technique_view_colours_each_representation(headless, only, dominant):
    doc = document()
    image, _ = headless(doc, mode=only, view="techniques").render(doc.camera("top"), SIZE)
    r, g, b = (image[..., c].astype(int) for c in range(3))
    share = {
        "red": ((r > 120) & (g < 0.5 * r) & (b < 0.5 * r)).mean(),
        "yellow": ((r > 120) & (g > 0.6 * r) & (b < 0.4 * r)).mean(),
        "blue": ((b > 120) & (r < 0.5 * b) & (g < 0.7 * b)).mean(),
    }
    assert share[dominant] > 0.2  # vertical slices seen from straight above cover less
    assert all(v < 0.05 for k, v in share.items() if k != dominant)
    assert coverage(image) < 0.05  # no green grass left in this view
