"""Cells where a grass type's density map is zero are skipped before drawing: fewer instances,
the same image."""

import dataclasses

import numpy as np
import pytest

from app.scenes import get_scene


@pytest.fixture
def half_bare(headless):
    scene = get_scene("patch-grid")
    doc = dataclasses.replace(scene, params=scene.params.replace(blade_count=400)).document()
    w, h = doc.maps.size
    doc.maps.write("density", 0, 0, np.zeros((h, w // 2)))  # the left half is bare
    return headless(doc), doc


def test_bare_cells_are_not_drawn_and_the_image_is_unchanged(half_bare):
    headless, doc = half_bare
    camera = doc.camera("grazing")
    image, skipped = headless.render(camera, (320, 240))
    headless.pipeline.skip_bare_cells = False
    full_image, full = headless.render(camera, (320, 240))
    drawn = skipped.c_g + skipped.c_v + skipped.c_i
    assert drawn < 0.75 * (full.c_g + full.c_v + full.c_i)
    diff = np.abs(image.astype(int) - full_image.astype(int)).max(axis=-1)
    assert (diff > 2).mean() < 0.001  # (a bare cell's rays no longer run on into its neighbour)
    # painting grass back makes the cells count again
    headless.pipeline.skip_bare_cells = True
    maps = doc.maps
    maps.write("density", 0, 0, np.ones((maps.size[1], maps.size[0])))
    _, repainted = headless.render(camera, (320, 240))
    assert repainted.c_g + repainted.c_v + repainted.c_i == full.c_g + full.c_v + full.c_i


def test_slices_and_cuboids_keep_to_the_cells_where_their_grass_grows(headless, monkeypatch):
    """The meadow's tall grass grows in clumps: its image-based slices and volume cuboids keep
    to the rectangle of each block's cells where it can grow (core/occupancy.py rects), and
    the frame is the one they draw over their whole blocks."""
    from benchmarks.references import quarter
    from core.image_diff import flip
    from core.occupancy import DensityOccupancy

    def frame():
        document = get_scene("meadow").document()
        return headless(document).render(document.camera("default"), (320, 240))[0]

    kept = frame()

    def whole_blocks(self, channel, ix, iz, sx, sz):
        out = np.zeros((np.size(ix), 4), np.float32)
        out[:, 2], out[:, 3] = sx, sz
        return out

    monkeypatch.setattr(DensityOccupancy, "rects", whole_blocks)
    whole = frame()
    moved, _ = flip(quarter(whole), quarter(kept))
    assert moved < 0.002


def test_grass_painted_into_a_bare_block_is_drawn_at_once(headless):
    """Tall grass painted where the meadow had none: the blocks it reaches draw it at once
    (their cuboids and slices keep to the cells that can now grow it), as the frame that
    skips nothing does: the two differ no more than before the stroke (where a bare cell's
    rays no longer run on into its neighbour)."""
    doc = get_scene("meadow").document()
    renderer = headless(doc)
    camera = doc.camera("default")

    def skipped_against_full() -> float:
        renderer.pipeline.skip_bare_cells = True
        image, _ = renderer.render(camera, (320, 240))
        renderer.pipeline.skip_bare_cells = False
        full_image, _ = renderer.render(camera, (320, 240))
        renderer.pipeline.skip_bare_cells = True
        return float((np.abs(image.astype(int) - full_image.astype(int)).max(axis=-1) > 2).mean())

    before = skipped_against_full()
    assert before < 0.003
    density = doc.maps.layer("density")
    w, h = doc.maps.size
    patch = density[h // 2 : h // 2 + h // 16, w // 3 : w // 3 + w // 3].copy()
    patch[..., 1] = 1.0  # the tall grass's channel
    doc.maps.write("density", w // 3, h // 2, patch)
    assert skipped_against_full() < before + 0.0005
