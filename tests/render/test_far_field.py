"""Far away, the image-based grass shows what the blades show: level with the grass a ray meets
the tips and covers the ground (shaders/image.glsl), so its colour agrees with the blades' band
by band down the frame (scripts/representation_bands.py measures the same)."""

import numpy as np

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
    its slices obliquely, meet them as high as the geometry's (opacity correction for the
    crossing angle, shaders/volume.glsl; without it the volume met them 10/255 lower here)."""
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
    assert abs(diff) < 7.5, diff  # 5.8 now; 10.3 without the correction
