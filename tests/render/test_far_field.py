"""Far away, the image-based grass shows what the blades show: level with the grass a ray meets
the tips and covers the ground (shaders/image.glsl), so its colour agrees with the blades' band
by band down the frame."""

import numpy as np
import pytest

from app.scenes import get_scene

SIZE = (320, 180)


def test_image_based_grass_has_the_blades_colour_at_a_grazing_view(headless):
    doc = get_scene("bench").document()
    camera = doc.camera("grazing")
    frames = {}
    for mode in ("geometry", "image"):
        renderer = headless(doc, mode=mode)
        frames[mode] = renderer.render(camera, SIZE, measure=False)[0].astype(np.float64)
    geometry, image = frames["geometry"], frames["image"]
    grass = np.abs(geometry - geometry[0, 0]).sum(axis=-1) > 4  # not the sky
    assert grass.mean() > 0.3
    assert np.abs(image[grass].mean(axis=0) - geometry[grass].mean(axis=0)).max() < 3.0
    for rows in np.array_split(np.flatnonzero(grass.any(axis=1)), 4):
        band = grass[rows]
        diff = image[rows][band].mean(axis=0) - geometry[rows][band].mean(axis=0)
        assert np.abs(diff).max() < 7.0, (rows[0], diff)


def test_a_taller_types_image_slice_knows_the_grass_beneath_it(headless):
    """The meadow's tall grass lies above the short grass's image-based slice: level rays that
    pass between its blades meet the short grass there, so only the short grass covers the
    ground at a grazing view (shaders/image.glsl: u_under)."""
    doc = get_scene("meadow").document()
    renderer = headless(doc, mode="image")
    renderer.render(doc.camera("default"), (160, 90), measure=False)
    short, tall = renderer.pipeline.grass_types
    assert short.image.layer_height() < tall.image.layer_height()
    assert short.image.under_channels == ()
    assert tall.image.under_channels == (short.density_channel,)


def test_volume_rays_meet_the_blades_at_the_heights_the_geometry_shows(headless):
    """Blades black at the root and white at the tip, white ambient light alone: a pixel's grey
    is how high along the blades it meets them. Near the camera the volume's rays, which cross
    its slices obliquely, meet them as high as the geometry's (opacity per slice crossed,
    shaders/volume.glsl; without it the volume met them 10/255 lower here)."""
    import dataclasses

    scene = get_scene("bench")
    params = scene.params.replace(
        root_color=(0.0, 0.0, 0.0), tip_color=(1.0, 1.0, 1.0), blade_color_variation=0.0
    )
    doc = dataclasses.replace(scene, params=params).document()
    doc.light = dataclasses.replace(
        doc.light, sun_color=(0.0, 0.0, 0.0), ambient_color=(1.0, 1.0, 1.0), blade_ao_impact=0.0
    )
    camera = doc.camera("zones")
    frames = {
        mode: headless(doc, mode=mode).render(camera, SIZE, measure=False)[0].astype(np.float64)
        for mode in ("geometry", "volume")
    }
    near = slice(SIZE[1] * 3 // 4, SIZE[1])  # the bottom quarter: the grass nearest the eye
    diff = frames["volume"][near].mean() - frames["geometry"][near].mean()
    # the volume stays somewhat darker near the eye: 1.5 / (|d.x| + |d.z|) per crossing
    # approximates the blades a ray passes between two slices
    assert abs(diff) < 7.5, diff


def _sun_view(doc_scene):
    """White blades lit by a white sun alone, over black ground: a pixel's grey is the diffuse
    factor the grass shows there."""
    import dataclasses

    doc = doc_scene.recoloured((1.0, 1.0, 1.0), (1.0, 1.0, 1.0)).document()
    doc.light = dataclasses.replace(
        doc.light, sun_color=(1.0, 1.0, 1.0), ambient_color=(0.0, 0.0, 0.0),
        blade_ao_impact=0.0, soil_color=(0.0, 0.0, 0.0), fog_distance=1e6,
    )  # fmt: skip
    return doc


def test_volume_lights_its_grass_like_the_blades_near_and_far(headless):
    """The volume's slices hold the mean normal of the blades under a texel: far away one short
    vector for many blades facing every way, near the eye the horizontal slice's averaged
    normal turned to the sky. Lit as they stand, the far volume was darker than the blades
    and the near one brighter; lit with the blades' mean diffuse factor as far as averaging
    shortened them (shaders/volume.glsl), the near volume is closer to the blades."""
    doc = _sun_view(get_scene("meadow"))
    camera = doc.camera("path")
    frames = {}
    for mode in ("geometry", "volume"):
        renderer = headless(doc, mode=mode)
        renderer.pipeline.ground.under_grass = (0.0, 0.0, 0.0)
        frames[mode] = renderer.render(camera, SIZE, measure=False)[0][..., 1].astype(np.float64)
    geometry, volume = frames["geometry"], frames["volume"]
    sky = geometry[0, 0]
    rows = np.flatnonzero((np.abs(geometry - sky) > 4).mean(axis=1) > 0.5)
    far, near = rows[: len(rows) // 3], rows[-len(rows) // 3 :]
    diff = {
        name: volume[band].mean() - geometry[band].mean()
        for name, band in (("far", far), ("near", near))
    }
    # What stays near is the samples' own normals made unit length where filtering averaged
    # two blades' into a shorter one.
    assert abs(diff["near"]) < 11.0, diff
    assert abs(diff["far"]) < 6.0, diff


@pytest.mark.parametrize("density", [0.5, 0.25])
def test_thinned_volume_covers_the_ground_as_its_thinned_blades_do(headless, density):
    """White blades over black soil in white ambient light without AO: a pixel's grey is how
    much of it the grass covers. Thinned by the density (the density map, the hand-over from the
    blades), the volume keeps the share of its texels' blades as a layer of random blades
    keeps it: at 0.25 it covered 0.39 where the blades cover 0.49 when the share scaled the
    alpha, 0.45 now."""
    import dataclasses

    scene = dataclasses.replace(get_scene("patch-grid"), density=density)
    grey, ground = _cover(headless, scene, "volume", "grazing")
    diff = grey["volume"][ground].mean() - grey["geometry"][ground].mean()
    assert abs(diff) < 0.05, diff


def test_image_based_grass_shows_the_blades_ambient_occlusion_on_a_slope(headless):
    """White blades over black soil in white ambient light: a pixel's grey over its grey
    without AO is the AO_blade the grass shows there. The image-based grass takes it from the
    heights a view meets of the blades (core/canopy.py Canopy.shade_met): taken at fixed heights
    near the tips it would show much less AO than the blades on this slope."""
    import dataclasses

    frames = {}
    for ao in (True, False):
        doc = get_scene("bench").recoloured((1.0, 1.0, 1.0), (1.0, 1.0, 1.0)).document()
        columns, rows = doc.maps.size
        ramp = np.repeat(np.linspace(1.0, 0.0, rows)[:, None], columns, axis=1)
        doc.set_heights(ramp[..., None].astype(np.float32), 8.0)  # rising away from the eye
        doc.light = dataclasses.replace(
            doc.light, sun_color=(0.0, 0.0, 0.0), ambient_color=(1.0, 1.0, 1.0),
            soil_color=(0.0, 0.0, 0.0), fog_distance=1e6,
            **({} if ao else {"blade_ao_impact": 0.0}),
        )  # fmt: skip
        for mode in ("geometry", "image"):
            renderer = headless(doc, mode=mode)
            renderer.pipeline.ground.under_grass = (0.0, 0.0, 0.0)
            image, _ = renderer.render(doc.camera("grazing"), SIZE, measure=False)
            frames[ao, mode] = image[..., 1].astype(np.float64) / 255.0
    plain = frames[False, "geometry"]
    grass = np.abs(plain - plain[0, 0]) > 2 / 255  # not the sky
    assert grass.mean() > 0.5
    shown = {
        mode: frames[True, mode][grass].mean() / frames[False, mode][grass].mean()
        for mode in ("geometry", "image")
    }
    assert shown["geometry"] < 0.8  # the blades are darker than without AO
    assert abs(shown["image"] - shown["geometry"]) < 0.04, shown


@pytest.mark.parametrize(
    "mode, grass, within, azimuth, sun_azimuth",
    [
        ("volume", None, 0.05, 0.0, None),
        ("image", "tall", 0.08, 0.0, None),
        ("volume", None, 0.03, 321.0, 315.0),
    ],
)
def test_far_grass_lights_upright_blades_on_a_slope_like_the_blades(
    headless, mode, grass, within, azimuth, sun_azimuth
):
    """The bench on a ramp rising 14 degrees away from a camera 5 degrees over the horizon,
    white blades on black soil: sun alone over ambient alone is the blades' diffuse factor. The
    slices are sheared with the ground, the blades stand upright (their parts that lean down
    the slope stand out): the volume's light takes the slope-ratio table (core/facing.py). The
    image-based grass is lit as on flat ground (its facing table) and takes the table's
    upright-on-the-slope over upright-on-flat layer. Seen 39 degrees off the ramp's fall line
    (`azimuth`), with the sun 84 degrees to the side of the view, the ground also rises across
    the view: the table's blocks by that rise keep the volume's light with the blades'."""
    import dataclasses
    import math

    from app.scenes import CameraSpec

    scene = get_scene("bench")
    meadow = get_scene("meadow")  # its grasses: fewer blades than the presets
    base = meadow.params if grass is None else meadow.grass[0].params
    params = base.replace(
        root_color=(1.0, 1.0, 1.0), tip_color=(1.0, 1.0, 1.0), blade_color_variation=0.0
    )

    def ramp(width, height):
        return np.repeat(np.linspace(0.0, 1.0, height, dtype=np.float32)[:, None], width, axis=1)

    el, az = math.radians(5.0), math.radians(azimuth)
    level = 20.0 * math.cos(el)
    eye = (level * math.sin(az), 20.0 * math.sin(el) + 4.0, -level * math.cos(az))
    scene = dataclasses.replace(
        scene, params=params, height_map=ramp, height_scale=8.0,
        cameras={"default": CameraSpec(eye, (0.0, 4.0, 0.0), 300.0)},
    )  # fmt: skip
    window = (slice(70, 110), slice(100, 220))
    diffuse = {}
    for drawn in ("geometry", mode):
        doc = scene.document()
        light = doc.light
        if sun_azimuth is not None:
            light = dataclasses.replace(light, sun_azimuth=sun_azimuth)
        # the light is linear in each channel and the blades white: a red sun and a green
        # ambient light draw the sun alone in red and the ambient light alone in green
        doc.light = dataclasses.replace(
            light, sun_color=(1, 0, 0), ambient_color=(0, 1, 0), soil_color=(0, 0, 0),
            sky_color=(0, 0, 0), fog_distance=1e6, blade_ao_impact=0.0,
        )  # fmt: skip
        renderer = headless(doc, mode=drawn)
        renderer.pipeline.ground.under_grass = (0.0, 0.0, 0.0)
        renderer.pipeline.segment_lod = False  # the blades whole: what it is made from
        frame = renderer.render(doc.camera("default"), SIZE, measure=False)[0]
        seen = {"sun": float(frame[..., 0][window].mean())}
        seen["ambient"] = float(frame[..., 1][window].mean())
        assert seen["ambient"] > 0.8 * 255, (drawn, seen)  # the window is grass
        diffuse[drawn] = seen["sun"] / seen["ambient"]
    assert abs(diffuse[mode] / diffuse["geometry"] - 1.0) < within, diffuse


@pytest.mark.parametrize("camera", ["grazing", "default"])
def test_upright_blades_cover_the_ground_far_away_as_their_geometry_does(headless, camera):
    """Blades standing upright (tilt 0, a patch the panel allows) have no area seen from
    straight above: their top view is empty. The image-based grass takes what a ray meets from
    the side from the vertical slices (shaders/image.glsl, core/canopy.py side_column); with the
    top view alone it drew nothing and the soil showed wherever it stood. White blades over
    black soil in white ambient light: a pixel's grey is how much of it the grass covers."""
    import dataclasses

    scene = get_scene("patch-grid")
    scene = dataclasses.replace(scene, params=scene.params.replace(tilt_min=0.0, tilt_max=0.0))
    grey, ground = _cover(headless, scene, "image", camera)
    assert ground.mean() > 0.2
    diff = grey["image"][ground].mean() - grey["geometry"][ground].mean()
    assert abs(diff) < 0.1, diff


def _cover(headless, scene, mode: str, camera: str):
    """White blades over black soil in white ambient light without AO, drawn as geometry and
    as `mode` (320 × 240): per mode a pixel's grey, how much of it the grass covers; and the
    pixels that are not the sky."""
    import dataclasses

    doc = scene.recoloured((1.0, 1.0, 1.0), (1.0, 1.0, 1.0)).document()
    doc.light = dataclasses.replace(
        doc.light, sun_color=(0.0, 0.0, 0.0), ambient_color=(1.0, 1.0, 1.0),
        blade_ao_impact=0.0, soil_color=(0.0, 0.0, 0.0), fog_distance=1e6,
    )  # fmt: skip
    grey = {}
    for name in ("geometry", mode):
        renderer = headless(doc, mode=name)
        renderer.pipeline.ground.under_grass = (0.0, 0.0, 0.0)
        image, _ = renderer.render(doc.camera(camera), (320, 240), measure=False)
        grey[name] = image.astype(np.float64).mean(axis=-1) / 255.0
    return grey, np.abs(grey["geometry"] - grey["geometry"][0, 0]) > 2 / 255


def test_the_footballs_touchlines_run_unbroken_to_the_far_end(headless):
    """A touchline is a texel or so of the colour map wide. Read at the map's base level, far
    away it broke into dashes (camera high, 1024 × 768: 0.52 of the far line's points in gaps);
    the far representations read the map's mipmapped copy over the pixel's footprint
    (shaders/_design.glsl), and the line fades but does not break."""
    from core.markings import touchlines
    from core.quality import line_gaps, screen_path

    scene = get_scene("football")
    doc = scene.document()
    camera = doc.camera("high")
    size = (1024, 768)
    image, _ = headless(doc).render(camera, size, measure=False)
    view_proj = camera.projection(size[0] / size[1]) @ camera.view()
    judged = []
    for line in touchlines(*scene.grid):
        points, across = screen_path(line, view_proj, size)
        gaps = line_gaps(image, points, across)["gaps"]
        if gaps is not None:
            judged.append(gaps)
    assert len(judged) == 2  # both lines show along most of their length
    assert max(judged) < 0.1, judged


@pytest.mark.parametrize("camera", ["default", "grazing"])
def test_short_dense_turf_covers_the_ground_in_the_volume_as_its_blades_do(headless, camera):
    """The football's turf (5000 blades 0.05-0.08 tall) on the patch grid, drawn as one volume
    level of one slice a direction (as the football's 2 × 1 level): a ray crosses its
    short layer in less than a slice spacing and mostly meets no vertical slice, only the
    horizontal one, which covers what the blades cover from straight above (0.34). Reaching it,
    the ray is made as opaque as the blades are from its elevation, counted on the blades'
    triangles (core/canopy.py BladeSides: a slice's mean alpha saturates there); the football's
    near half at `high` showed half its soil before."""
    import dataclasses

    from core.lod import LodConfig, LodLevel

    turf = get_scene("football").params
    scene = get_scene("patch-grid")
    one_slice = LodConfig((LodLevel("volume", 0.0, None, slices=1, macro=1),))
    scene = dataclasses.replace(scene, params=turf.replace(seed=scene.params.seed), lod=one_slice)
    grey, ground = _cover(headless, scene, "lod", camera)
    assert ground.mean() > 0.2
    diff = grey["lod"][ground].mean() - grey["geometry"][ground].mean()
    assert abs(diff) < 0.1, diff


def test_far_grass_seen_from_straight_above_has_the_blades_colour(headless):
    """The bench from 40 units above: the volume and image-based regions' mean colour close to
    all-geometry's in the same pixels (the sweep holds them to 0.03 at 480 × 270). The far
    grass was 0.08 off, 10-15 % darker: the top view covered less than the blades, steep
    volume rays counted the blades' side over their whole run instead of its horizontal part,
    and the far blades' attributes were read outside their triangles."""
    from core.quality import technique_regions
    from render.grass_type import technique_colors

    doc = get_scene("bench").document()
    camera = doc.camera("top")
    lod = headless(doc)
    shaded = lod.render(camera, SIZE, measure=False)[0]
    lod.pipeline.view = "techniques"
    techniques = lod.render(camera, SIZE, measure=False)[0]
    blades = headless(doc, mode="geometry").render(camera, SIZE, measure=False)[0]
    regions = technique_regions(shaded, techniques, technique_colors())
    for name in ("volume", "image"):
        mask = regions[name]
        assert mask.sum() > 500, name
        diff = (shaded[mask].mean(axis=0) - blades[mask].mean(axis=0)) / 255.0
        assert np.linalg.norm(diff) < 0.04, (name, diff)


def test_image_based_grass_thins_with_the_density_as_the_blades_do(headless):
    """A density below 1 keeps a share of the blades picked by their thresholds: together they
    still cover as a thinner union does (1 − exp(−share · depth)), not the share of what all of
    them cover. The image-based grass's coverage at density 0.3, against its own at 1, is the
    blades' within 0.15 (the share of the top view's cover gave 0.29 against the blades' 0.63)."""
    from render.grass_type import technique_colors

    colours = technique_colors()

    def cover(density: float, mode: str) -> float:
        doc = get_scene("bench").document()
        doc.density = density
        renderer = headless(doc, mode=mode)
        renderer.pipeline.view = "techniques"
        frame = renderer.render(doc.camera("default"), SIZE, measure=False)[0].astype(float)
        return frame[SIZE[1] // 2 :].reshape(-1, 3)

    ground = cover(0.0, "geometry")
    share = {}
    for mode in ("geometry", "image"):
        tint = 255.0 * np.asarray(colours[mode][0])
        covered = [
            (((cover(d, mode) - ground) * (tint - ground)).sum(1) / ((tint - ground) ** 2).sum(1))
            for d in (0.3, 1.0)
        ]
        share[mode] = covered[0].mean() / covered[1].mean()
    assert abs(share["image"] - share["geometry"]) < 0.15, share
