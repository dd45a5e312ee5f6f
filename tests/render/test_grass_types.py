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
    half without it as the blades give it (geometry 6.3, the image-based 3.5 before, 4.6 now)."""
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
