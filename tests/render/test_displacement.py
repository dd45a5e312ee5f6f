"""Grass on uneven ground (thesis 6.4.4): roots on the terrain surface in all three
representations, and the volume's shifted slice lookup at the blades' heights. A steep ramp
rising 4 units over 8 cells along z, seen from the side and from above the side."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core.camera import Camera
from core.patch import generate_patch
from tests.conftest import pixel_rays

BASE = get_scene("patch-grid")
SCALE = 4.0
SCENE = dataclasses.replace(
    BASE,
    params=BASE.params.replace(blade_count=1200, tilt_max=10.0),
    height_map=lambda w, h: np.tile(((np.arange(h) + 0.5) / h)[:, None], (1, w)),
    height_scale=SCALE,
    map_size=(64, 64),
    mirror_seed=None,
    tint=0.0,
)
SIZE = (240, 200)
# far away and narrow: nearly orthographic, so every cell along the view projects alike
SIDE = Camera.from_eye_target((300.0, 2.0, 0.0), (0.0, 2.0, 0.0), fov_y=2.0, near=250.0, far=350.0)
ABOVE = Camera.from_eye_target((14.0, 9.0, 0.0), (0.0, 1.5, 0.0), fov_y=50.0)


def ground(z):
    return SCALE * np.clip((z + 4.0) / 8.0, 0.0, 1.0)


def render(headless, only, camera, density=1.0):
    doc = dataclasses.replace(SCENE, density=density).document()
    image, _ = headless(doc, mode=only).render(camera, SIZE)
    return image


def grass(image, bare):
    return np.abs(image.astype(int) - bare.astype(int)).max(axis=-1) > 12


def top_heights(mask, camera):
    """Per image column with grass: world z of the column and world height of its topmost grass
    pixel, read through the nearly orthographic side camera."""
    w, h = SIZE
    half = np.tan(np.radians(camera.fov_y) / 2) * np.linalg.norm(
        camera.eye - np.asarray(camera.target)
    )
    cols = np.nonzero(mask.any(axis=0))[0]
    first = mask[:, cols].argmax(axis=0)
    y = camera.target[1] + half * (1 - 2 * (first + 0.5) / h)
    z = half * (w / h) * (1 - 2 * (cols + 0.5) / w)  # looking along -x: +z is to the left
    return z, y


@pytest.mark.parametrize("only", ["geometry", "volume"])
def test_grass_stands_on_the_ramp_seen_from_the_side(headless, only):
    patch_height = generate_patch(SCENE.params).height
    bare = render(headless, only, SIDE, density=0.0)
    image = render(headless, only, SIDE)
    z, top = top_heights(grass(image, bare), SIDE)
    on_ramp = (z > -3.5) & (z < 3.5)
    assert on_ramp.sum() > 100
    above_ground = top[on_ramp] - ground(z[on_ramp])
    # the tallest blade of a column of eight cells stands about the patch height over the ground:
    # not at 0 (sunk into the ramp) nor at the ramp's height plus more (floating or lifted twice)
    assert np.median(above_ground) == pytest.approx(patch_height, abs=0.1)
    assert np.percentile(np.abs(above_ground - patch_height), 90) < 0.2


def test_volume_lookup_matches_the_blades_heights(headless):
    bare = render(headless, "geometry", SIDE, density=0.0)
    geo = render(headless, "geometry", SIDE)
    vol = render(headless, "volume", SIDE)
    zg, tg = top_heights(grass(geo, bare), SIDE)
    zv, tv = top_heights(grass(vol, bare), SIDE)
    both = np.intersect1d(zg.round(3), zv.round(3))
    g = dict(zip(zg.round(3), tg, strict=True))
    v = dict(zip(zv.round(3), tv, strict=True))
    diff = np.array([v[k] - g[k] for k in both if -3.5 < k < 3.5])
    assert len(diff) > 100
    assert abs(np.median(diff)) < 0.05  # the silhouettes agree to about a pixel's worth


def ramp_pixels(camera):
    """Pixels whose ray meets the ramp's surface inside its cells (half a cell in from the
    edges), and pixels whose ray meets the plain ground well away from the ramp."""
    d = pixel_rays(camera, SIZE)
    e = camera.eye
    # y = 0.5 z + 2 over the cells: e.y + t d.y = 0.5 (e.z + t d.z) + 2
    t = (0.5 * e[2] + 2 - e[1]) / (d[..., 1] - 0.5 * d[..., 2])
    p = e + t[..., None] * d
    inside = (t > 0) & (np.abs(p[..., 0]) < 3.5) & (np.abs(p[..., 2]) < 3.5)
    # off the ramp: the ray meets the plain ground (y = 0) and passes nowhere near the ramp's box
    t0 = -e[1] / d[..., 1]
    lo, hi = np.array([-4.5, -0.1, -4.5]), np.array([4.5, SCALE + 0.6, 4.5])
    with np.errstate(divide="ignore", invalid="ignore"):
        a, b = (lo - e) / d, (hi - e) / d
    near = np.nanmax(np.minimum(a, b), axis=-1)
    far_ = np.nanmin(np.maximum(a, b), axis=-1)
    misses = (far_ < near) | (far_ < 0)
    beside = (t0 > 0) & misses
    return inside, beside


@pytest.mark.parametrize("only", ["geometry", "volume", "image"])
def test_grass_covers_the_ramp_and_nothing_beside_it(headless, only):
    bare = render(headless, only, ABOVE, density=0.0)
    image = render(headless, only, ABOVE)
    mask = grass(image, bare)
    on_ramp, beside = ramp_pixels(ABOVE)
    assert on_ramp.sum() > 3000 and beside.sum() > 3000
    assert mask[on_ramp].mean() > 0.8  # grass lies on the ramp, not sunk under it
    assert mask[beside].mean() < 0.02  # nor floating in front of the ground beside it


def test_volume_cells_on_hills_leave_no_cracks_where_the_soil_shows(headless):
    """Where a faint volume fragment of a (macro-)cell nearer the eye lay over the cell behind
    it, the depth it wrote hid the grass behind, and thin lines of soil showed through along the
    hills on the left of the meadow default view. Soil drawn magenta: those pixels counted (30
    at this size before the volume cells were drawn farthest first, 0 after)."""
    doc = get_scene("meadow").document()
    renderer = headless(doc)
    renderer.pipeline.ground.under_grass = (1.0, 0.0, 1.0)
    image = renderer.render(doc.camera("default"), (512, 384), measure=False)[0].astype(int)
    window = image[190:250, 0:200]  # left of the frame, 15-20 m away: volume and image zones
    soil = (window[..., 0] > 180) & (window[..., 2] > 180) & (window[..., 1] < 90)
    assert soil.sum() <= 5


def test_volume_floor_layer_follows_the_ground_under_the_ray(headless):
    """The volume's horizontal slice is a layer at half the grass height: it must follow the
    ground where the ray crosses it, not lie flat at the height of the ground where the ray
    entered the cuboid. Flat, it hovered above the ground downhill and the ray met it too soon:
    looking down this ramp the volume drew the grass 6/255 darker than the blades (1 after);
    on the meadow default view a darker rectangle with straight edges showed where a macro-cell
    stood on a slope."""
    camera = Camera.from_eye_target((8.0, 7.0, 8.0), (0.0, 1.5, 0.0), fov_y=50.0)
    on_ramp, _ = ramp_pixels(camera)
    assert on_ramp.sum() > 1000
    geo, vol = (
        render(headless, only, camera)[on_ramp].mean(axis=0) for only in ("geometry", "volume")
    )
    assert np.abs(vol - geo).max() < 3.0
