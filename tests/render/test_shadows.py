"""Blade shadows (core/shadows.py): the blades darken the ground on the side away from the sun;
the ground beyond the blades loses what their shadows would take, so the shadow does not end
where the geometry does."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core.camera import Camera

SIZE = (480, 270)
MODES = ("geometry", "volume")


def _lit(doc, on: bool, strength: float = 0.6):
    doc.light = dataclasses.replace(doc.light, blade_shadows=on, shadow_strength=strength)


def _darkening(renderer, doc, camera) -> np.ndarray:
    """(h, w): how much darker each pixel is with the blades' shadows than without."""
    _lit(doc, False)
    before = renderer.render(camera, SIZE, measure=False)[0].astype(float)
    _lit(doc, True)
    after = renderer.render(camera, SIZE, measure=False)[0].astype(float)
    return (before - after).mean(axis=-1)


def _pixel(camera, size, point) -> tuple[int, int]:
    w, h = size
    clip = camera.projection(w / h) @ camera.view() @ np.append(point, 1.0)
    x, y = clip[:2] / clip[3]
    return int((x * 0.5 + 0.5) * w), int((0.5 - y * 0.5) * h)


def test_a_tuft_darkens_the_ground_away_from_the_sun_and_not_the_sky(headless):
    doc = get_scene("patch-grid").document()
    w, h = doc.maps.size
    v, u = np.mgrid[0:h, 0:w]
    centre = np.array([w / 2, h / 2])
    tuft = ((u - centre[0]) ** 2 + (v - centre[1]) ** 2) < (w / 24) ** 2
    doc.maps.write("density", 0, 0, np.repeat(tuft[..., None], 4, axis=2).astype(np.float32))
    terrain = doc.terrain_spec
    x0, z0, x1, z1 = doc.terrain.rect
    middle = np.array([(x0 + x1) / 2, 0.0, (z0 + z1) / 2])  # the tuft's centre
    camera = Camera(target=tuple(middle), yaw=0.0, pitch=89.0, distance=3.0)  # from above
    renderer = headless(doc)
    _lit(doc, False)
    before = renderer.render(camera, SIZE, measure=False)[0].astype(float)
    _lit(doc, True)
    after, stats = renderer.render(camera, SIZE, measure=True)
    darker = (before - after.astype(float)).mean(axis=-1)
    sun = doc.light.sun_direction
    way = sun[[0, 2]] / np.linalg.norm(sun[[0, 2]])
    reach = terrain.columns / 24 + 0.12  # just past the tuft's edge
    for side, sign in (("away from the sun", -1.0), ("towards the sun", 1.0)):
        x, y = _pixel(camera, SIZE, middle + sign * reach * np.array([way[0], 0.0, way[1]]))
        window = darker[y - 4 : y + 5, x - 4 : x + 5]
        if sign < 0:
            assert window.mean() > 6.0, f"{side}: {window.mean():.2f}"
        else:
            assert abs(window.mean()) < 1.0, f"{side}: {window.mean():.2f}"
    # seen along the ground, the sky stays as it was
    grazing = doc.camera("grazing")
    sky_frames = []
    for on in (False, True):
        _lit(doc, on)
        sky_frames.append(renderer.render(grazing, SIZE, measure=False)[0].astype(float))
    sky = (sky_frames[0][..., 2] > sky_frames[0][..., 1]) & (sky_frames[0][..., 2] > 150)
    assert sky.sum() > 5000 and np.array_equal(sky_frames[0][sky], sky_frames[1][sky])
    assert stats.t_s_ms > 0.0


@pytest.mark.parametrize("scene,camera", [("bench", "zones"), ("meadow", "path")])
def test_the_shadows_mean_darkening_goes_on_past_the_blades(headless, scene, camera):
    """Sparse grass, the ground showing between the blades: on either side of the hand-over
    from the blades to the volume, the rows of the LOD frame darken by what they darken in the
    all-geometry frame, where every blade casts its shadow (within a fifth); the ground beyond
    the blades keeping its sun would leave the volume's rows undarkened."""
    from core.quality import technique_regions
    from render.grass_type import technique_colors

    def darkening(doc, mode, cam):
        renderer = headless(doc, mode=mode)
        return _darkening(renderer, doc, cam).mean(axis=1), renderer

    doc = get_scene(scene).document()
    doc.density = 0.3
    cam = doc.camera(camera)
    lod, renderer = darkening(doc, "lod", cam)
    renderer.pipeline.view = "techniques"
    techniques = renderer.render(cam, SIZE, measure=False)[0]
    renderer.pipeline.view = "shaded"
    shaded = renderer.render(cam, SIZE, measure=False)[0]
    regions = technique_regions(shaded, techniques, technique_colors())
    blade_rows = regions["geometry"].mean(axis=1)
    volume_rows = regions["volume"].mean(axis=1)
    # the hand-over: from the rows of volume nearest the blades to the rows the blades hold
    first = int(np.flatnonzero(blade_rows > 0.2)[0])
    band = np.arange(max(first - 30, 0), min(first + 30, SIZE[1]))
    geometry, _ = darkening(doc, "geometry", cam)
    for side, rows in (
        ("volume", band[volume_rows[band] > 0.5]),
        ("blades", band[blade_rows[band] > 0.2]),
    ):
        assert rows.size > 10, side
        want, got = geometry[rows].mean(), lod[rows].mean()
        assert want > 1.0, f"{scene} {side}: the shadows darken the rows by {want:.2f} only"
        assert abs(got - want) < 0.2 * want, f"{scene} {side}: {got:.2f} against {want:.2f}"


def _ramp(sign: float) -> tuple:
    """A patch grid at density 0.3 on a 31° slope, rising towards the sun (sign +1: it faces
    the sun) or away from it (−1), or level (0), and a camera above its middle."""
    doc = get_scene("patch-grid").document()
    doc.density = 0.3
    sun = doc.light.sun_direction
    way = sun[[0, 2]] / np.linalg.norm(sun[[0, 2]])
    w, h = doc.maps.size
    v, u = np.mgrid[0:h, 0:w]
    along = ((u + 0.5) / w - 0.5) * way[0] + ((v + 0.5) / h - 0.5) * way[1]
    columns = doc.terrain_spec.columns
    if sign:
        doc.maps.write("height", 0, 0, np.clip(0.5 + sign * along, 0.0, 1.0).astype(np.float32))
        doc.terrain_spec = dataclasses.replace(doc.terrain_spec, height_scale=0.6 * columns)
    x0, z0, x1, z1 = doc.terrain.rect
    middle = ((x0 + x1) / 2, 0.3 * columns if sign else 0.0, (z0 + z1) / 2)  # half way up
    return doc, Camera(target=middle, yaw=0.0, pitch=89.0, distance=3.0)


def test_the_far_ground_darkens_a_slope_as_the_blades_shadows_do(headless):
    """The blades stand upright on a slope and their shadows fall along the sun onto it: on a
    slope turned away from the sun they reach farther across the ground than on one turned
    towards it. The volume's ground, where no blade casts a shadow, loses as much of its sun
    as the blades' shadows take on either slope (within a third); taken as on level ground it
    would lose the same on both."""
    out = {}
    for sign in (1.0, -1.0):
        doc, camera = _ramp(sign)
        for mode in MODES:
            out[sign, mode] = _darkening(headless(doc, mode=mode), doc, camera).mean()
    steep, gentle = sorted((1.0, -1.0), key=lambda s: -out[s, "geometry"])
    assert out[steep, "geometry"] > 1.5 * out[gentle, "geometry"]
    for sign in (steep, gentle):
        want, got = out[sign, "geometry"], out[sign, "volume"]
        assert abs(got - want) < want / 3, f"slope {sign:+.0f}: {got:.2f} against {want:.2f}"


@pytest.mark.parametrize("sign", [0.0, 1.0, -1.0])
def test_on_bare_ground_the_far_ground_loses_what_the_blades_shadows_take(
    headless, monkeypatch, sign
):
    """The grass itself not drawn, only the shadows on the ground: the blades' shadows (as
    much of a pixel as their blades cover, the blade texture's alpha) and the volume's ground
    (the patch's field, its shadows stretched along the sun on a slope) darken it alike, on
    level ground and on slopes turned towards the sun and away from it (within a tenth)."""
    import render.geometry
    import render.volume

    monkeypatch.setattr(render.geometry.GeometryRenderer, "draw", lambda self: None)
    monkeypatch.setattr(render.volume.VolumeRenderer, "draw", lambda self: None)
    doc, camera = _ramp(sign)
    got = {mode: _darkening(headless(doc, mode=mode), doc, camera).mean() for mode in MODES}
    assert got["geometry"] > 3.0
    assert got["volume"] == pytest.approx(got["geometry"], rel=0.1), got


def test_the_far_grounds_shadows_fall_where_the_blades_shadows_fall(headless):
    """Sparse clustered grass (density 0.3) seen from above: the volume's ground darkens where
    the blades' shadows fall in the all-geometry frame (its field per mirror state of the
    tiling), not evenly over the cells: their darkening's 8 × 8 pixel blocks correlate."""
    doc = get_scene("bench").document()
    doc.density = 0.3
    camera = Camera.from_eye_target((10.5, 3.0, 12.0), (12.5, 0.0, 14.0), fov_y=40.0)
    dark = {mode: _darkening(headless(doc, mode=mode), doc, camera) for mode in MODES}
    h, w = dark["geometry"].shape
    blocks = [d[: h // 8 * 8, : w // 8 * 8].reshape(h // 8, 8, w // 8, 8).mean(axis=(1, 3))
              for d in dark.values()]  # fmt: skip
    assert np.corrcoef(blocks[0].ravel(), blocks[1].ravel())[0, 1] > 0.7


def test_beyond_the_blades_the_bare_ground_beside_grass_gets_its_shadows(headless):
    """A tuft drawn by the volume casts no shadows of its own; the bare ground beside it on the
    side away from the sun still darkens as where the tuft's blades cast them (the ground takes
    the density where the shadows falling there come from), and not towards the sun."""
    doc = get_scene("patch-grid").document()
    w, h = doc.maps.size
    v, u = np.mgrid[0:h, 0:w]
    tuft = ((u - w / 2) ** 2 + (v - h / 2) ** 2) < (w / 12) ** 2
    doc.maps.write("density", 0, 0, np.repeat(tuft[..., None], 4, axis=2).astype(np.float32))
    x0, z0, x1, z1 = doc.terrain.rect
    middle = np.array([(x0 + x1) / 2, 0.0, (z0 + z1) / 2])
    camera = Camera(target=tuple(middle), yaw=0.0, pitch=89.0, distance=3.0)
    sun = doc.light.sun_direction
    way = np.array([sun[0], 0.0, sun[2]]) / np.linalg.norm(sun[[0, 2]])
    edge = doc.terrain_spec.columns / 12  # the tuft's radius in world units
    darker = {mode: _darkening(headless(doc, mode=mode), doc, camera) for mode in MODES}

    def beside(mode: str, sign: float) -> float:
        x, y = _pixel(camera, SIZE, middle + sign * (edge + 0.06) * way)
        return float(darker[mode][y - 3 : y + 4, x - 3 : x + 4].mean())

    cast = beside("geometry", -1.0)
    assert cast > 6.0, f"the blades' own shadows beside the tuft: {cast:.2f}"
    assert 0.4 * cast < beside("volume", -1.0) < 2.0 * cast, (
        f"{beside('volume', -1.0):.2f} against {cast:.2f}"
    )
    assert abs(beside("volume", 1.0)) < 1.0


def test_no_pixel_of_hilly_ground_goes_black_under_the_shadows(headless):
    """The far ground's shadows on a hilly meadow take away at most the shadow strength's share
    of the sun: no pixel comes out black (a vertical skirt's normal once made the shadows'
    length NaN along a crest)."""
    doc = get_scene("meadow").document()
    camera = doc.camera("path")
    renderer = headless(doc)
    _lit(doc, False)
    before = renderer.render(camera, (960, 540), measure=False)[0].astype(float).sum(axis=-1)
    _lit(doc, True)
    after = renderer.render(camera, (960, 540), measure=False)[0].astype(float).sum(axis=-1)
    lit = before > 60.0
    assert (after[lit] / before[lit]).min() > 0.3


def test_a_draft_answers_a_new_sun_with_the_level_field_alone(headless):
    """On uneven terrain the full frame's ground reads the shadows drawn at three lengths (a
    slope stretches them); a draft, which answers an edit first, draws only level ground's."""
    doc = get_scene("meadow").document()
    _lit(doc, True)
    renderer = headless(doc)
    camera = doc.camera("default")
    stretches = {}
    for draft in (True, False):
        renderer.render(camera, (160, 90), measure=False, half_resolution=draft)
        stretches[draft] = {f.shape[1] for f in renderer.pipeline.ground.shadows.fields}
    assert stretches == {True: {1}, False: {3}}
