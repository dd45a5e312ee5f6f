"""A volume ray counts the blades of each slab its path runs through inside the grass, not only
the slices whose plane it happens to cross there (shaders/volume.glsl). On ground that faces
the eye a ray runs through the grass in less than a slab: counted by plane crossings alone, the
soil showed in rings that follow the slice spacing (landscape `valley`)."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core.camera import Camera
from core.image_diff import downsample, to_float
from core.lod import LodConfig, LodLevel

BASE = get_scene("patch-grid")
SCALE = 6.0
# a ramp rising 6 units over 32 cells along -z, towards the far side: it faces the eye
SCENE = dataclasses.replace(
    BASE,
    grid=(32, 32),
    params=BASE.params.replace(blade_count=800),
    height_map=lambda w, h: np.tile(((np.arange(h)[::-1] + 0.5) / h)[:, None], (1, w)),
    height_scale=SCALE,
    map_size=(64, 64),
    mirror_seed=None,
    lod=LodConfig((LodLevel("volume", 0.0, None, slices=2, macro=1),)),
)
CAMERA = Camera.from_eye_target((0.0, 5.0, 30.0), (0.0, 3.0, 0.0), fov_y=24.0)


def soil_shares(headless, mode: str) -> np.ndarray:
    """Per 8 × 8 block of the ramp, how far it turned magenta with the soil drawn so."""
    renderer = headless(SCENE.document(), mode=mode)
    renderer.pipeline.segment_lod = False  # the blades whole: what the volume is made from
    frames = []
    for soil in (renderer.pipeline.ground.under_grass, (1.0, 0.0, 1.0)):
        renderer.pipeline.ground.under_grass = soil
        frames.append(to_float(renderer.render(CAMERA, (256, 192))[0]))
    moved = (frames[1][..., 2] - frames[1][..., 1]) - (frames[0][..., 2] - frames[0][..., 1])
    blocks = downsample(np.repeat(np.clip(moved, 0, 1)[..., None], 3, axis=-1), 8)[..., 0]
    return blocks[8:24, 4:28]  # the ramp, below the sky, away from its edges


def test_volume_on_ground_facing_the_eye_lets_the_soil_show_as_the_blades_do(headless):
    volume = soil_shares(headless, "lod")  # the scene draws one volume level of 2 slices
    blades = soil_shares(headless, "geometry")
    # counted by plane crossings alone the volume showed soil in bands along the slices (rows
    # of blocks 0.20, 0.17, 0.20 against the blades' 0.06 then); by the slabs its rays run
    # through, as the blades do; in the nearest rows, seen steepest, the blades show more
    assert abs(volume.mean() - blades.mean()) < 0.015
    assert np.abs(volume.mean(axis=1) - blades.mean(axis=1)).max() < 0.06


def test_rays_up_the_landscapes_hill_count_all_the_grass_they_cross(headless):
    """The landscape's hill seen from its valley: rays rise up the slope and meet the grass
    near where they enter their cuboids. Counted a slab's length about each crossing, the
    rays' ends went uncounted and the soil showed in rings: 5.8 % of the blocks below the sky
    more than half soil. Then 2.4 %: the far levels' reduced texels averaged alpha over heights
    whose depths differ, and a ray crossing the slices at all those heights meets the mean of
    their depths; scaled to their rows' depth at the base level, none (density is 1
    everywhere: the issue's limit is 1 %)."""
    from app.sweep import MAGENTA
    from core.quality import bare_blocks

    doc = get_scene("landscape").document()
    camera = doc.camera("valley")
    renderer = headless(doc)
    size = (480, 270)
    shaded = renderer.render(camera, size, measure=False)[0]
    renderer.pipeline.view = "techniques"
    techniques = renderer.render(camera, size, measure=False)[0]
    renderer.pipeline.view = "shaded"
    renderer.pipeline.ground.under_grass = MAGENTA
    soil = renderer.render(camera, size, measure=False)[0]
    figures = bare_blocks(shaded, soil, techniques)
    assert figures["terrain_blocks"] > 1000
    assert figures["bare_blocks"] <= 0.01
    # Rays rising up the hill fall into its grass as the hill rises faster: counted by their
    # direction alone they never met the horizontal layer, nor were runs too short for a
    # crossing counted, and single pixels along the cuboids' walls showed the soil whole
    moved = to_float(soil) - to_float(shaded)
    share = np.clip(moved[..., 2] - moved[..., 1], 0.0, 1.0)
    assert int((share[50:150] > 0.8).sum()) <= 5


@pytest.mark.parametrize(
    ("eye", "mean_limit", "block_limit"),
    [((0.0, 4.0, 30.0), 0.002, 0.01), ((0.0, 16.0, 24.0), 0.007, 0.02)],
    ids=["low", "steep"],
)
def test_band_passes_of_one_type_show_what_its_single_pass_shows(
    headless, monkeypatch, eye, mean_limit, block_limit
):
    """A type that grows among another is drawn in passes of a band of heights each (render/
    volume_order.py), each pass's cuboids only as tall as its band's top over the highest
    ground (shaders/volume.glsl): its rays count nothing above it. Split so, a type's grass on
    hills, where its macro-cells' cuboids are tall, shows what its one pass does. Seen from
    high up the horizontal slice shows: only the band that holds it crosses it (a mean
    difference of 0.0045 in 0 … 1 there; with the slice dropped from its band too, 0.015)."""
    import render.frame_draw
    from core.heights import hills
    from render.volume_order import INF

    scene = dataclasses.replace(
        SCENE,
        height_map=lambda w, h: hills(w, seed=4)[:h, :w],
        height_scale=0.5,  # gentle: the grass is as tall as a macro-cell's ground varies
        lod=LodConfig((LodLevel("volume", 0.0, None, slices=4, macro=4),)),
    )
    camera = Camera.from_eye_target(eye, (0.0, 0.0, 0.0), fov_y=30.0)
    renderer = headless(scene.document(), mode="lod")
    whole = to_float(renderer.render(camera, (256, 192))[0])
    height = float(renderer.pipeline.grass_types[0].image.textures.height)
    low = height / 3.0
    split = [[((0, 0), (0.0, low)), ((0, 1), (low, INF))]]
    monkeypatch.setattr(render.frame_draw, "stacked_parts", lambda beneath, bands=2: split)
    parts = to_float(renderer.render(camera, (256, 192))[0])
    blocks = np.abs(downsample(parts, 8) - downsample(whole, 8)).max(axis=-1)
    assert np.abs(parts - whole).mean() < mean_limit
    assert np.percentile(blocks, 99) < block_limit
