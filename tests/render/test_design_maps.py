"""The design-map stack reaches every representation: density, colour modulation, aperiodic
tiling (thesis 6.3-6.4), and edits upload only their rectangle."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core.design_maps import LAYER_INDEX, DesignMaps
from core.mipmaps import mip_sizes
from core.params import PatchParams
from render.design_maps import DesignMapTextures
from tests.conftest import covered

SCENE = get_scene("patch-grid")
PARAMS = PatchParams(blade_count=600, seed=5)
SIZE = (200, 150)
REPRESENTATIONS = ("geometry", "volume", "image")


def pixel(camera, world):
    """(column, row) of a world point in a SIZE image, top row first."""
    clip = camera.projection(SIZE[0] / SIZE[1]) @ camera.view() @ np.array([*world, 1.0])
    ndc = clip[:3] / clip[3]
    return int((ndc[0] * 0.5 + 0.5) * SIZE[0]), int((0.5 - ndc[1] * 0.5) * SIZE[1])


def window(image, centre, half=12):
    c, r = centre
    return image[r - half : r + half, c - half : c + half]


def document(**changes):
    """The patch grid with neutral 64 × 64 maps (no colour variation)."""
    doc = dataclasses.replace(SCENE, params=PARAMS, map_size=(64, 64), **changes).document()
    doc.maps.stack[:] = DesignMaps(64).stack
    return doc


def test_an_edit_uploads_its_rectangle_only(ctx):
    maps = DesignMaps(64)
    mirror = DesignMapTextures(ctx, maps)
    maps.write("diffuse", 10, 20, np.full((5, 7, 3), 0.25))
    maps.write("diffuse", 12, 21, np.full((2, 2, 3), 0.25))  # inside: one upload for both
    assert mirror.pending  # nothing uploaded before the frame (no context may be current)
    mirror.flush()
    assert mirror.uploaded_texels == 5 * 7
    w, h = maps.size
    gpu = np.frombuffer(mirror.texture.read(), np.float16).reshape(-1, h, w, 4)
    layer = gpu[LAYER_INDEX["diffuse"]]
    assert np.all(layer[20:25, 10:17, :3] == 0.25)
    assert np.all(layer[:20, :, :3] == 1.0) and np.all(layer[25:, :, :3] == 1.0)
    mirror.release()


def test_the_volumes_height_and_density_texture_follows_edits(ctx):
    maps = DesignMaps(64)
    mirror = DesignMapTextures(ctx, maps)
    mirror.use([1])  # the texture of density channel 1, made from the maps as they are
    maps.write("height", 3, 4, np.full((6, 5, 1), 0.75))
    maps.write("density", 30, 40, np.full((2, 3, 4), (0.1, 0.2, 0.3, 0.4)))
    maps.write("diffuse", 0, 0, np.full((8, 8, 3), 0.5))  # not in it
    mirror.flush()
    w, h = maps.size
    gpu = np.frombuffer(mirror.ground(1).read(), np.float16).reshape(h, w, 2)
    assert np.all(gpu[..., 0] == maps.stack[LAYER_INDEX["height"], ..., 0].astype(np.float16))
    assert np.all(gpu[..., 1] == maps.stack[LAYER_INDEX["density"], ..., 1].astype(np.float16))
    assert np.all(gpu[4:10, 3:8, 0] == np.float16(0.75))
    assert np.all(gpu[40:42, 30:33, 1] == np.float16(0.2))
    mirror.release()


@pytest.mark.parametrize("only", REPRESENTATIONS)
def test_density_map_clears_grass_where_it_is_black(headless, only):
    doc = document()
    camera = doc.camera("top")
    renderer = headless(doc, mode=only)
    doc.maps.fill("density", 0.0)
    bare, _ = renderer.render(camera, SIZE)
    doc.maps.fill("density", 1.0)
    # columns 0-31: u < 0.5, the cells at x < 0
    doc.maps.write("density", 0, 0, np.zeros((64, 32)))
    image, _ = renderer.render(camera, SIZE)
    cleared = pixel(camera, (-2.0, 0.0, 0.0))
    kept = pixel(camera, (2.0, 0.0, 0.0))
    assert covered(window(image, cleared), window(bare, cleared)) < 0.05
    assert covered(window(image, kept), window(bare, kept)) > 0.6


@pytest.mark.parametrize("only", REPRESENTATIONS)
def test_colour_map_with_full_alpha_colours_the_grass(headless, only):
    doc = document()
    camera = doc.camera("top")
    renderer = headless(doc, mode=only)
    doc.maps.fill("color", (0.9, 0.1, 0.1, 1.0))
    image, _ = renderer.render(camera, SIZE)
    r, g, _b = window(image, pixel(camera, (0.0, 0.0, 0.0)), 30).reshape(-1, 3).mean(axis=0)
    assert r > 1.5 * g  # the lawn turned red (eq. 6.8 with A_c = 1)


@pytest.mark.parametrize("only", REPRESENTATIONS)
@pytest.mark.parametrize("layer", ["ambient", "diffuse"])
def test_a_painted_light_map_darkens_the_grass_it_covers(headless, only, layer):
    """Unpainted, the light maps are all ones and no program reads them (LIGHT_MAPS); the
    first stroke makes every program read them from the next frame on."""
    doc = document()
    camera = doc.camera("top")
    renderer = headless(doc, mode=only)
    before, _ = renderer.render(camera, SIZE)
    assert not renderer.pipeline.map_textures.light_maps
    doc.maps.write(layer, 0, 0, np.full((64, 32, 3), 0.3))  # columns 0-31: the cells at x < 0
    after, _ = renderer.render(camera, SIZE)
    dark, lit = pixel(camera, (-2.0, 0.0, 0.0)), pixel(camera, (2.0, 0.0, 0.0))
    assert window(after, dark).mean() < 0.9 * window(before, dark).mean()
    assert abs(window(after, lit).mean() - window(before, lit).mean()) < 2.0


@pytest.mark.parametrize("only", REPRESENTATIONS)
def test_mirror_bits_change_the_pixels_but_not_the_statistics(headless, only):
    doc = document(mirror_seed=None)
    camera = doc.camera("default")
    renderer = headless(doc, mode=only)
    doc.maps.fill("density", 0.0)
    bare, _ = renderer.render(camera, SIZE)
    doc.maps.fill("density", 1.0)
    plain, _ = renderer.render(camera, SIZE)
    tiled, _ = headless(document(mirror_seed=11), mode=only).render(camera, SIZE)
    mask_p = np.abs(plain.astype(int) - bare.astype(int)).max(axis=-1) > 10
    mask_t = np.abs(tiled.astype(int) - bare.astype(int)).max(axis=-1) > 10
    changed = np.abs(plain.astype(int) - tiled.astype(int)).max(axis=-1) > 16
    # a tenth of the grass pixels changed clearly (the volume: 0.19 by more than 16/255, 0.08
    # by more than 24 since its slices' opacity per crossing no longer differs by family)
    assert changed[mask_p].mean() > 0.1
    assert mask_t.mean() == pytest.approx(mask_p.mean(), abs=0.02)  # the same coverage
    mean_p = plain[mask_p].mean(axis=0)
    mean_t = tiled[mask_t].mean(axis=0)
    assert np.abs(mean_p - mean_t).max() < 4  # the same grass colour on average


def test_the_far_copy_follows_colour_edits_weighted_and_mipmapped(ctx):
    """The far representations read the colour map's mipmapped copy, RGB times its weight, so
    that a level's mean is the mean of the colours the blades would be mixed with; an edit
    reaches it at the next flush (its levels: tests/render/test_far_field.py's touchlines)."""
    maps = DesignMaps(64)
    mirror = DesignMapTextures(ctx, maps)
    maps.write("color", 0, 0, np.full((64, 32, 4), (1.0, 0.5, 0.0, 0.5)))  # the left half
    mirror.flush()
    w, h = maps.size
    base = np.frombuffer(mirror.far.read(), np.float16).reshape(h, w, 4)
    np.testing.assert_allclose(base[:, :32], np.tile((0.5, 0.25, 0.0, 0.5), (64, 32, 1)))
    assert np.all(base[:, 32:] == 0.0)  # white of weight 0 mixes in nothing
    mirror.release()


@pytest.mark.parametrize("size", [(64, 64), (100, 70)])
def test_a_brush_dab_redoes_the_far_copys_levels_as_a_whole_rebuild_would(ctx, size):
    """A dab redoes the mipmapped copy only over its rectangle, level by level; every level
    then holds what GL's own mipmap generation makes of the whole edited map (within a unit in
    the last place of half floats), for sizes that halve evenly and for those that do not."""
    rng = np.random.default_rng(3)
    maps = DesignMaps(*size)
    maps.write("color", 0, 0, rng.random((size[1], size[0], 4)).astype(np.float32))
    mirror = DesignMapTextures(ctx, maps)
    before = np.frombuffer(mirror.far.read(level=1), np.float16).copy()
    maps.write("color", 13, 9, rng.random((7, 11, 4)).astype(np.float32))  # a dab
    mirror.flush()
    levels = len(mip_sizes(*size))
    edited = [np.frombuffer(mirror.far.read(level=i), np.float16).astype(np.float32) for i in
              range(levels)]  # fmt: skip
    whole = DesignMapTextures(ctx, maps)  # the same map, its chain made by GL at once
    for level, got in enumerate(edited):
        want = np.frombuffer(whole.far.read(level=level), np.float16).astype(np.float32)
        np.testing.assert_allclose(got, want, rtol=2e-3, atol=1e-3, err_msg=f"level {level}")
    assert not np.array_equal(edited[1], before.astype(np.float32))  # the dab reached it
    mirror.release()
    whole.release()


def _ground(mirror: DesignMapTextures) -> list[np.ndarray]:
    sinks, _levels, chunks = mirror.ground_levels()
    read = [np.frombuffer(t.read(), np.float32) for t in sinks]
    return [*read, chunks.deviation, chunks.low, chunks.high]


def test_the_ground_begun_ahead_is_that_of_the_heights_it_is_drawn_with(ctx):
    """A renderer of uneven ground begins its mesh's sinks and chunks beside the set-up
    (DesignMapTextures.ground_ahead); its first frame draws those of the heights as they are
    then, also after an edit in between."""
    maps = DesignMaps(64)
    ramp = np.linspace(0.0, 1.0, 64, dtype=np.float32)
    maps.write("height", 0, 0, np.sin(6.0 * ramp)[None, :] * np.cos(5.0 * ramp)[:, None])
    mirrors = [DesignMapTextures(ctx, maps) for _ in range(3)]
    try:
        plain, ahead, edited = mirrors
        ahead.ground_ahead()
        edited.ground_ahead()
        for a, b in zip(_ground(ahead), _ground(plain), strict=True):
            np.testing.assert_array_equal(a, b)
        before = _ground(plain)
        maps.write("height", 20, 20, np.full((12, 12), 1.5, np.float32))
        edited.flush()
        after = _ground(edited)
        fresh = DesignMapTextures(ctx, maps)
        mirrors.append(fresh)
        for a, b in zip(after, _ground(fresh), strict=True):
            np.testing.assert_array_equal(a, b)
        assert not np.array_equal(after[-1], before[-1])  # the edit raised the chunks' highest
    finally:
        for mirror in mirrors:
            mirror.release()
