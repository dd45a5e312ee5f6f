"""Blade segments fewer with distance (core/segments.py, render/geometry.py): blades far away
draw fewer triangles and the same picture, and a blade changing level shows no step."""

import dataclasses

import numpy as np

from app.scenes import get_scene
from core.document import CameraSpec
from core.lod import LodConfig, LodLevel
from core.quality import Comparison

SIZE = (320, 180)


def _tolerance(doc, pixels: float) -> None:
    doc.set_lods([dataclasses.replace(lod, segment_tolerance=pixels) for lod in doc.lods])


def test_far_blades_draw_fewer_segments_and_the_same_picture(headless):
    doc = get_scene("bench").document()
    _tolerance(doc, 0.5)  # the bench's curved blades coarsen in this small view
    renderer = headless(doc)
    camera = doc.camera("zones")
    images, triangles = {}, {}
    for on in (False, True):
        renderer.pipeline.segment_lod = on
        images[on], stats = renderer.render(camera, SIZE)
        triangles[on] = stats.triangles
    assert triangles[True] < 0.7 * triangles[False]
    assert Comparison.of(images[False], images[True]).flip_quarter <= 0.02


def test_a_blade_changing_level_shows_no_step(headless):
    """The camera moved across the distance where a cell's blades change level: the picture
    changes far less than the levels differ (their vertices have slid onto the coarser
    level's chords by then), where without the sliding it would jump."""
    one = LodConfig((LodLevel("geometry", 0.0, None),))
    doc = dataclasses.replace(get_scene("patch-grid"), grid=(1, 1), lod=one).document()
    _tolerance(doc, 0.5)  # a switch between 8 and 1.5 units away
    renderer = headless(doc)
    geometry = renderer.pipeline.grass_types[0].geometry

    def frame(z: float, on: bool = True):
        renderer.pipeline.segment_lod = on
        camera = CameraSpec((0.0, 1.0, float(z)), (0.0, 0.1, 0.0)).camera()
        image, _ = renderer.render(camera, SIZE, measure=False)
        return image.astype(np.float64), {level: n for level, _a, n, *_ in geometry._ranges}

    zs = np.linspace(8.0, 1.5, 27)
    levels = [frame(z)[1] for z in zs]
    i = next(i for i in range(len(zs) - 1) if levels[i] != levels[i + 1])  # the one cell's
    a, b = zs[i], zs[i + 1]
    for _ in range(22):  # to within a hair of the switch: the camera itself hardly moves
        middle = 0.5 * (a + b)
        if frame(middle)[1] == levels[i]:
            a = middle
        else:
            b = middle
    assert frame(a)[1] != frame(b)[1]
    step = np.abs(frame(a)[0] - frame(b)[0]).mean()
    levels_differ = np.abs(frame(a)[0] - frame(a, on=False)[0]).mean()
    # (the rest: the coarser strip's triangles split the same surface along other edges)
    assert step < 0.35 * levels_differ


def test_cells_in_a_transition_draw_only_the_blades_they_show(headless):
    """Across the geometry → volume hand-over a cell keeps only its blades below w · density
    (eq. 5.26): the geometry renderer draws just that run of them (render/geometry.py), the
    picture the same as drawing every blade of every cell."""
    doc = get_scene("bench").document()
    _tolerance(doc, 0.0)  # all segments: the runs alone
    renderer = headless(doc)
    camera = doc.camera("zones")
    geometry = renderer.pipeline.grass_types[0].geometry
    images, triangles = {}, {}
    for spans in (1, 16):
        geometry.spans = spans
        images[spans], stats = renderer.render(camera, SIZE)
        triangles[spans] = stats.triangles
    assert triangles[16] < 0.7 * triangles[1]
    # the same blades; only the cells' order differs, which decides a few ties in depth
    changed = np.abs(images[16].astype(int) - images[1].astype(int)).max(axis=2) > 2
    assert changed.mean() < 0.001


def test_full_strips_are_lit_by_their_vertices_normals_as_the_rows_are(headless):
    """A draw of the full strips (segment level 0) interpolates its vertices' normals (the
    WHOLE_STRIP variant) where the coarser levels rebuild the full strip's normals per fragment:
    with the wind bending the blades, both light them alike."""
    from core.wind import Wind

    one = LodConfig((LodLevel("geometry", 0.0, None),))
    doc = dataclasses.replace(get_scene("patch-grid"), grid=(2, 2), lod=one).document()
    doc.wind = Wind(enabled=True, gust_strength=0.8)
    renderer = headless(doc)
    renderer.pipeline.segment_lod = False  # every cell at level 0
    geometry = renderer.pipeline.grass_types[0].geometry
    camera = CameraSpec((1.0, 0.8, 3.2), (1.0, 0.2, 1.0)).camera()
    whole, _ = renderer.render(camera, SIZE, measure=False)
    prepare = geometry.prepare

    def rebuilt(frame, defines=()):  # level 0 drawn with the coarser levels' program
        prepare(frame, defines)
        geometry._variants[True] = geometry._variants[False]

    geometry.prepare = rebuilt
    rows, _ = renderer.render(camera, SIZE, measure=False)
    grass = np.abs(whole.astype(np.int16) - rows.astype(np.int16)).max(axis=2)
    assert whole.std() > 10  # blades in view
    assert (grass > 3).mean() < 0.002, (grass > 3).mean()
