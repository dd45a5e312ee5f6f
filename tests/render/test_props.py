"""Objects standing in the grass are partly hidden by it: the volume renderer writes the depth of
its first opaque hit (thesis 5.2), the blades their own."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene
from core.camera import Camera
from core.props import boxes
from render.props import _cube, _rock

SCENE = get_scene("patch-grid")
PARAMS = SCENE.params.replace(blade_count=1500)
SIZE = (240, 180)
CAMERA = Camera.from_eye_target((0.0, 0.45, 3.2), (0.0, 0.25, 0.0))
BOX = ((0.0, 0.0), (0.5, 0.9, 0.5), (0.85, 0.1, 0.1))


def red(image):
    r, g, b = (image[..., c].astype(int) for c in range(3))
    return (r > 90) & (r > 2.2 * g) & (r > 2.2 * b)


def test_cube_faces_point_outward():
    cube = _cube()
    p, n = cube[:, :3], cube[:, 3:6]
    assert np.allclose(np.abs(n).sum(axis=1), 1)
    tri = p.reshape(-1, 3, 3)
    face_n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert np.all(np.sum(face_n * n.reshape(-1, 3, 3)[:, 0], axis=1) > 0)  # counter-clockwise


def test_bad_prop_size_is_refused():
    with pytest.raises(ValueError, match="prop 0"):
        boxes([((0, 0), (1, 0, 1), (1, 1, 1))])


@pytest.mark.parametrize("only", ["geometry", "volume"])
def test_prop_standing_in_grass_is_partly_hidden(headless, only):
    doc = dataclasses.replace(SCENE, params=PARAMS, density=0.0, props=(BOX,)).document()
    renderer = headless(doc, mode=only)
    bare, _ = renderer.render(CAMERA, SIZE)
    doc.density = 1.0
    grass, _ = renderer.render(CAMERA, SIZE)
    box = red(bare)
    rows = np.nonzero(box.any(axis=1))[0]
    assert rows.size > 40  # the box fills a good part of the view
    top, bottom = rows[: rows.size // 4], rows[-rows.size // 5 :]
    seen_top = red(grass)[top].sum() / box[top].sum()
    seen_bottom = red(grass)[bottom].sum() / box[bottom].sum()
    assert seen_top > 0.9  # grass around and behind it does not draw over its upper part
    assert seen_bottom < 0.5  # its foot stands in the grass


def test_rock_mesh_is_closed_faces_outward_and_fills_its_box():
    rock = _rock()
    p, n = rock[:, :3], rock[:, 3:6]
    assert np.allclose(p.min(axis=0), -0.5, atol=1e-5) and np.allclose(
        p.max(axis=0), 0.5, atol=1e-5
    )
    tri = p.reshape(-1, 3, 3)
    face_n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    outward = np.sum(face_n * (tri.mean(axis=1) - p.mean(axis=0)), axis=1) > 0
    assert outward.mean() > 0.97  # a lumpy sphere: nearly every face points away from its middle
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-4)


def test_a_rock_is_not_a_box(headless):
    """The same prop as a box and as a rock: the rock's outline is round, not its bounding
    rectangle, and its surface is shaded with hollows and grain, not flat faces."""
    side = Camera.from_eye_target((0.0, 0.6, 3.0), (0.0, 0.45, 0.0))
    grey = ((0.0, 0.0), (0.8, 0.9, 0.8), (0.6, 0.58, 0.55))
    images = {}
    for shape in ("box", "rock"):
        prop = (*grey, 0.0, shape)
        doc = dataclasses.replace(SCENE, params=PARAMS, density=0.0, props=(prop,)).document()
        bare = dataclasses.replace(SCENE, params=PARAMS, density=0.0).document()
        image, _ = headless(doc).render(side, SIZE)
        ground, _ = headless(bare).render(side, SIZE)
        images[shape] = (image, np.abs(image.astype(int) - ground.astype(int)).max(axis=-1) > 12)
    box, rock = images["box"][1], images["rock"][1]
    assert box.sum() > 2000 and rock.sum() > 0.4 * box.sum()

    def fill(mask):  # of the bounding rectangle
        rows, cols = np.nonzero(mask)
        return mask.sum() / ((np.ptp(rows) + 1) * (np.ptp(cols) + 1))

    assert fill(box) > 0.9 and fill(rock) < 0.85
    luma = [images[s][0][images[s][1]].astype(float).mean(axis=-1) for s in ("box", "rock")]
    assert luma[1].std() > 2 * luma[0].std()  # light and dark within the rock, flat on a face


def test_a_rock_stands_on_ground_raised_under_it_in_the_drawn_frame(headless):
    """A height stroke under a rock, then the terrain rebuilt (as the designer does after a
    stroke): the frame of the renderer that followed the edit shows the rock standing on the
    mound, as a renderer started on the edited document draws it, not buried at its old
    height."""
    meadow = get_scene("meadow")
    doc = meadow.document()
    doc.density = 0.0  # the rock and the ground alone
    renderer = headless(doc)
    spec = doc.terrain_spec
    (x, z) = doc.props[0].position
    column, row = (np.array([x, z]) / [spec.columns, spec.rows] + 0.5) * doc.maps.size
    doc.maps.write("height", int(column) - 10, int(row) - 10, np.ones((20, 20, 1), np.float32))
    doc.rebuild_terrain()
    centre = doc.prop_boxes()["centre"][0]
    size = doc.prop_boxes()["size"][0]
    eye = (centre[0], centre[1] + 0.4 * size[1], centre[2] + 4.0 * size[2])
    camera = Camera.from_eye_target(eye, tuple(centre))
    followed, _ = renderer.render(camera, SIZE)
    fresh_doc = meadow.document()
    fresh_doc.density = 0.0
    fresh_doc.maps.write("height", 0, 0, doc.maps.layer("height").copy())
    fresh_doc.rebuild_terrain()
    fresh, _ = headless(fresh_doc).render(camera, SIZE)

    def rock(image):  # grey: the rock; the ground is brown or green, the sky blue
        rgb = image.astype(int)
        return (rgb.max(axis=-1) - rgb.min(axis=-1) < 14) & (rgb.max(axis=-1) > 40)

    assert rock(fresh).mean() > 0.05  # the rock fills a good part of the view
    assert (rock(followed) == rock(fresh)).mean() > 0.99
