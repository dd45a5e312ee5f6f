"""The image-based renderer draws a cell on flat ground as one quad and a cell on uneven ground
as a grid that follows the height map (render/image.py): on flat ground both give the same
picture, only the cells whose ground varies are drawn as grids, and a grid is no finer than
the ground's bends seen from the eye need."""

import dataclasses

import numpy as np

from app.scenes import get_scene
from core.camera import Camera

SIZE = (240, 160)
CAMERA = Camera.from_eye_target((0.0, 3.0, 7.0), (0.0, 0.0, 0.0), fov_y=50.0)


def test_flat_cells_are_one_quad_and_look_as_the_grid_does(headless, monkeypatch):
    doc = get_scene("patch-grid").document()
    renderer = headless(doc, mode="image")
    quads, _ = renderer.render(CAMERA, SIZE)
    image = renderer.pipeline.grass_types[0].image
    assert image.instance_count > 0
    assert image.batches[1].instance_count == image.instance_count  # every cell of the flat grid
    image.flat_ground = -1.0  # every cell a grid of the finest kind
    monkeypatch.setattr(
        "render.image.slice_grids", lambda instances, *_: np.full(instances.size, 6, np.int32)
    )
    grids, _ = renderer.render(CAMERA, SIZE)
    assert image.batches[6].instance_count == image.instance_count
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
    image = renderer.pipeline.grass_types[0].image
    counts = {n: batch.instance_count for n, batch in image.batches.items()}
    assert counts[1] > 0
    assert sum(counts.values()) - counts[1] > 0
    assert sum(counts.values()) == image.instance_count


def test_far_cells_on_the_meadow_take_coarser_grids_and_the_same_picture(headless):
    doc = get_scene("meadow").document()
    camera = doc.camera("default")
    renderer = headless(doc, mode="lod")
    adaptive, _ = renderer.render(camera, SIZE)
    grass = renderer.pipeline.grass_types[0]
    counts = {n: batch.instance_count for n, batch in grass.image.batches.items()}
    assert sum(c for n, c in counts.items() if n < 6) > counts[6]  # most cells need less
    terrain = renderer.pipeline.terrain  # every grid the finest
    object.__setattr__(terrain, "curvature_of", lambda cells: np.full(len(cells), np.inf))
    finest, _ = renderer.render(camera, SIZE)
    counts = {n: batch.instance_count for n, batch in grass.image.batches.items()}
    assert counts[6] == sum(c for n, c in counts.items() if n > 1)
    moved = np.abs(adaptive.astype(int) - finest.astype(int)).max(axis=-1)
    assert (moved > 24).mean() < 0.001  # under a pixel's shift: a few edge pixels
