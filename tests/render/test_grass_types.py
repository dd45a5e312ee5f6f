"""Several grass types on one terrain (thesis 6.4.5): each with its own patch and LOD levels,
placed by its own channel of the density map, sharing terrain and light maps."""

import dataclasses

import numpy as np
import pytest

from app.scenes import GrassRecipe, get_scene
from core.lod import LodConfig
from core.params import PRESETS

BASE = get_scene("patch-grid")
SIZE = (200, 150)


def left_half(width, height):
    out = np.zeros((height, width), np.float32)
    out[:, : width // 2] = 1.0  # u < 0.5: the cells at x < 0
    return out


TALL = GrassRecipe(
    "tall",
    PRESETS["long thin meadow grass"].replace(blade_count=600, tip_color=(0.9, 0.8, 0.3)),
    LodConfig.zones(geometry_end=None, volume_end=None),  # geometry everywhere
    channel=1,
    density_map=left_half,
)


def test_a_second_grass_type_grows_only_where_its_density_channel_says(headless, ctx):
    one = dataclasses.replace(BASE, params=BASE.params.replace(blade_count=500), mirror_seed=None)
    two = dataclasses.replace(one, grass=(TALL,)).document()
    camera = two.camera("top")
    a, sa = headless(one.document()).render(camera, SIZE)
    b, sb = headless(two).render(camera, SIZE)
    changed = np.abs(a.astype(int) - b.astype(int)).max(axis=-1) > 20
    # the top camera looks down -y with +x to the right of the image
    left, right = changed[:, 20:90], changed[:, 110:180]
    assert left.mean() > 0.2  # the tall grass stands among the first where its channel is 1
    assert right.mean() < 0.02  # and nowhere else
    assert sb.c_g > sa.c_g  # its cells are drawn too
    assert sb.blades > sa.blades


MEADOW_TALL = dataclasses.replace(get_scene("meadow").grass[0], density_map=left_half)


@pytest.mark.parametrize("only", ["geometry", "volume", "image"])
def test_the_meadows_second_grass_type_shows_in_every_representation(headless, only):
    """Drawn by one representation throughout, the meadow's tall grass shows where its channel
    says, beside and above the first type (an image-based slice at the first type's height
    would hide it wherever both grow)."""
    one = dataclasses.replace(BASE, params=BASE.params.replace(blade_count=500), mirror_seed=None)
    two = dataclasses.replace(one, grass=(MEADOW_TALL,))
    camera = one.document().camera("default")
    a, _ = headless(one.document(), mode=only).render(camera, SIZE)
    b, _ = headless(two.document(), mode=only).render(camera, SIZE)
    changed = np.abs(a.astype(int) - b.astype(int)).max(axis=-1) > 20
    left, right = changed[:, : SIZE[0] // 2], changed[:, SIZE[0] // 2 :]
    assert left.mean() > 0.1
    assert left.mean() > 4 * right.mean()
    # its yellow tips: the tall grass's half is yellower than the same half without it
    yellow = (b[:, : SIZE[0] // 2, 0].astype(int) - b[:, : SIZE[0] // 2, 2]).mean()
    assert yellow > (a[:, : SIZE[0] // 2, 0].astype(int) - a[:, : SIZE[0] // 2, 2]).mean() + 3


def test_far_away_a_taller_type_lets_the_grass_among_it_show_as_its_blades_do(headless):
    """Over another type's grass the image-based slice of the tall grass stops a ray by its
    share of the blades above and among the shorter ones (core/canopy.py: Canopy.over), not by
    its top view's coverage: the tall grass's half gains about as much yellow over the same
    half without it as the blades give it."""
    one = dataclasses.replace(BASE, params=BASE.params.replace(blade_count=500), mirror_seed=None)
    two = dataclasses.replace(one, grass=(MEADOW_TALL,))
    camera = one.document().camera("default")
    gain = {}
    for only in ("geometry", "image"):
        a, _ = headless(one.document(), mode=only).render(camera, SIZE)
        b, _ = headless(two.document(), mode=only).render(camera, SIZE)
        half = slice(0, SIZE[0] // 2)
        yellow = [(f[:, half, 0].astype(int) - f[:, half, 2]).mean() for f in (a, b)]
        gain[only] = yellow[1] - yellow[0]
    assert gain["geometry"] > 3.0
    assert 0.65 * gain["geometry"] < gain["image"] < 1.35 * gain["geometry"]


def test_a_taller_types_volume_lets_the_shorter_grass_beneath_show(headless):
    """The meadow's tall grass alone drawn white (the short grass, soil and light black but for
    a white ambient light): at the default camera a clump on the left, 8-12 m away in the
    volume zone, is the share of its pixels that the tall grass covers. The tall grass's volume
    held a horizontal layer with its top view, which covered the short grass beneath: 0.81 of
    the clump in the LOD frame against the blades' 0.61 (0.69 without the layer)."""
    scene = get_scene("meadow")
    white, black = (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)

    def ramp(params, colour):
        return params.replace(root_color=colour, tip_color=colour, blade_color_variation=0.0)

    scene = dataclasses.replace(
        scene,
        params=ramp(scene.params, black),
        grass=tuple(dataclasses.replace(g, params=ramp(g.params, white)) for g in scene.grass),
    )
    doc = scene.document()
    doc.light = dataclasses.replace(
        doc.light, sun_color=black, ambient_color=white, blade_ao_impact=0.0,
        soil_color=black, fog_distance=1e6,
    )  # fmt: skip
    camera = doc.camera("default")
    # the grass beyond 25 m shows nowhere in the clump, and drawn as blades it is most of
    # the all-geometry frame's work
    camera.far = 25.0
    cover = {}
    for mode in ("geometry", "lod"):
        renderer = headless(doc, mode=mode)
        renderer.pipeline.ground.under_grass = black
        image = renderer.render(camera, (512, 384), measure=False)[0]
        cover[mode] = image[270:310, 10:125].mean() / 255.0
    assert cover["geometry"] > 0.4  # the clump is there
    assert cover["lod"] < cover["geometry"] + 0.12


def test_a_taller_types_volume_covers_where_no_grass_grows_beneath(headless):
    """The meadow's first type given the long-thin preset stands over the tall grass's type,
    but where that grass does not grow (its density 0 everywhere here) its volume must cover
    the soil as its blades do. Its horizontal layer, which holds the blades its vertical
    slices miss, had been dropped wherever another type's slices lay lower: the soil showed
    between the slices and the volume zone was darker than the blades."""
    doc = get_scene("meadow").document()
    doc.set_params(0, PRESETS["long thin meadow grass"])
    width, height = doc.maps.size
    doc.maps.write("density", 0, 0, np.zeros((height, width)), channel=1)
    white, black = (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)
    doc.light = dataclasses.replace(
        doc.light, sun_color=black, ambient_color=white, blade_ao_impact=0.0, fog_distance=1e6
    )
    camera = doc.camera("default")
    mean = {}
    for mode in ("geometry", "lod"):
        renderer = headless(doc, mode=mode)
        image = renderer.render(camera, (480, 270), measure=False)[0][150:190, :, :3]
        mean[mode] = image.astype(float).mean()
    assert abs(mean["lod"] / mean["geometry"] - 1.0) < 0.03
