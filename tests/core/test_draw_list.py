"""The draw list: what each renderer draws, selected without GL."""

import numpy as np

from app.scenes import get_scene
from core.draw_list import draw_list
from core.lod import LodConfig, LodLevel
from core.occupancy import DensityOccupancy

FOOTBALL = get_scene("football").document()
TERRAIN = FOOTBALL.terrain
EYE = FOOTBALL.camera("player").eye


def cells(batch) -> int:
    """Cells covered, counting a macro-cell by its area."""
    return int(np.sum(np.rint(batch["size"][:, 0]) * np.rint(batch["size"][:, 1])))


def test_levels_that_share_a_renderer_are_drawn_in_one_batch():
    lod = LodConfig(
        (
            LodLevel("geometry", 0.0, 20.0),
            LodLevel("volume", 5.0, 80.0, slices=2, macro=4),
            LodLevel("volume", 60.0, 160.0, slices=2, macro=16),
            LodLevel("image", 140.0, None, macro=64),
        )
    )
    drawn = draw_list("lod", lod, EYE, TERRAIN, TERRAIN.all_cells(), None, 8)
    assert set(drawn.batches) == {("geometry", 0), ("volume", 2), ("image", 0)}
    # the volume batch holds both volume levels' (macro-)cells
    counts = drawn.counts()
    assert counts[("volume", 2)] == drawn.batches[("volume", 2)].size > 0
    sizes = set(np.rint(drawn.batches[("volume", 2)]["size"][:, 0]).astype(int))
    assert max(sizes) > 4  # the second level's larger macro-cells are in it too


def test_a_single_representation_draws_every_cell_once_without_macro_cells():
    drawn = draw_list("volume", FOOTBALL.lod(0), EYE, TERRAIN, TERRAIN.all_cells(), None, 4)
    assert list(drawn.batches) == [("volume", 4)]
    batch = drawn.batches[("volume", 4)]
    assert batch.size == TERRAIN.columns * TERRAIN.rows == cells(batch)


def test_cells_without_grass_of_a_type_are_left_out():
    density = np.ones((FOOTBALL.maps.size[1], FOOTBALL.maps.size[0], 4), np.float32)
    density[:, : density.shape[1] // 2, 1] = 0.0  # the second type grows on one half only
    occupancy = DensityOccupancy(TERRAIN.columns, TERRAIN.rows, density)
    mode, lod, all_cells = "geometry", FOOTBALL.lod(0), TERRAIN.all_cells()
    first = draw_list(mode, lod, EYE, TERRAIN, all_cells, None, 8, occupancy, channel=0)
    second = draw_list(mode, lod, EYE, TERRAIN, all_cells, None, 8, occupancy, channel=1)
    a, b = first.batches[("geometry", 0)], second.batches[("geometry", 0)]
    assert a.size == TERRAIN.columns * TERRAIN.rows
    assert abs(b.size - a.size / 2) <= TERRAIN.rows  # one column of cells may straddle the edge
    centre_x = b["origin"][:, 0] + 0.5 * b["size"][:, 0]
    assert centre_x.min() > -1.0  # only cells on the x > 0 half (u > 0.5)


def test_without_a_terrain_a_fixed_set_of_cells_is_split_by_distance():
    grid = get_scene("patch-grid").document()
    instances = grid.terrain.all_cells()
    drawn = draw_list("lod", grid.lod(0), grid.camera("grazing").eye, None, instances, None, 8)
    total = sum(drawn.counts().values())
    assert total >= instances.size  # every cell at least once, in transitions twice
    assert set(drawn.batches) == {("geometry", 0), ("volume", 8), ("image", 0)}


def test_volume_cells_are_drawn_farthest_first():
    """A volume fragment blends over what is drawn and writes depth: the cells behind must be
    drawn before it (shaders/volume.glsl, core/draw_list.py: back_to_front)."""
    meadow = get_scene("meadow").document()
    eye = meadow.camera("default").eye
    drawn = draw_list("lod", meadow.lod(0), eye, meadow.terrain, None, None, 8)
    volume = drawn.batches[("volume", 8)]
    assert volume.size > 10
    centre = volume["origin"] + 0.5 * volume["size"]
    distance = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
    assert np.all(np.diff(distance) <= 1e-6)
