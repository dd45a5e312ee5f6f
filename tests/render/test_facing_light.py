"""The image-based grass lights like the blades when the sun moves (render/facing.py): the
facing table is rebuilt for the new light and the far grass brightens and darkens with the
blades."""

import dataclasses

import numpy as np

from app.scenes import get_scene

SCENE = get_scene("patch-grid")
SIZE = (240, 135)


def grass_brightness(renderer, camera, sky) -> float:
    image = renderer.render(camera, SIZE, measure=False)[0].astype(np.float64)
    return float(image[~sky].mean())


def test_image_based_grass_follows_the_sun_like_the_blades(headless):
    doc = dataclasses.replace(SCENE, params=SCENE.params.replace(blade_count=800)).document()
    camera = doc.camera("default")
    geometry, image = headless(doc, mode="geometry"), headless(doc, mode="image")
    first = geometry.render(camera, SIZE, measure=False)[0].astype(np.int32)
    sky = np.abs(first - first[0, 0]).sum(axis=-1) < 4
    assert (~sky).mean() > 0.3
    change = {}
    for name, renderer in (("geometry", geometry), ("image", image)):
        seen = []
        for azimuth in (0.0, 180.0):  # low sun on one side of the blades, then the other
            doc.light = dataclasses.replace(doc.light, sun_elevation=15.0, sun_azimuth=azimuth)
            seen.append(grass_brightness(renderer, camera, sky))
        change[name] = seen[1] - seen[0]
    assert abs(change["geometry"]) > 3.0, change  # the camera sees the sun's side change
    assert np.sign(change["image"]) == np.sign(change["geometry"]), change
    assert 0.5 < change["image"] / change["geometry"] < 2.0, change
