"""The image-based renderer draws a cell on flat ground as one quad and a cell on uneven ground
as a grid that follows the height map (render/image.py): on flat ground both give the same
picture, and only the cells whose ground varies are drawn as grids."""

import dataclasses

import numpy as np

from app.scenes import get_scene
from core.camera import Camera

SIZE = (240, 160)
CAMERA = Camera.from_eye_target((0.0, 3.0, 7.0), (0.0, 0.0, 0.0), fov_y=50.0)


def test_flat_cells_are_one_quad_and_look_as_the_grid_does(headless):
    doc = get_scene("patch-grid").document()
    renderer = headless(doc, mode="image")
    quads, _ = renderer.render(CAMERA, SIZE)
    image = renderer.pipeline.image
    assert image.instance_count > 0
    assert image.flat.instance_count == image.instance_count  # every cell of the flat grid
    assert image.uneven.instance_count == 0
    image.flat_ground = -1.0  # every cell a grid, as before there were two batches
    grids, _ = renderer.render(CAMERA, SIZE)
    assert image.uneven.instance_count == image.instance_count
    grass = np.abs(grids.astype(int) - quads.astype(int)).max(axis=-1)
    assert (grass > 24).mean() < 0.002  # the same picture but for a few edge pixels


def test_cells_on_a_slope_are_grids(headless):
    base = get_scene("patch-grid")
    ramp = dataclasses.replace(
        base,
        # the left half of the map flat, the right half rising along x
        height_map=lambda w, h: np.tile(np.clip((np.arange(w) + 0.5) / w - 0.5, 0, 1), (h, 1)),
        height_scale=2.0,
        map_size=(64, 64),
    )
    renderer = headless(ramp.document(), mode="image")
    renderer.render(CAMERA, SIZE)
    image = renderer.pipeline.image
    assert image.flat.instance_count > 0
    assert image.uneven.instance_count > 0
    assert image.flat.instance_count + image.uneven.instance_count == image.instance_count
