"""Two levels that share macro-cells in their transition (core/traversal.py _pair_weight)
hand over by the distance of each sample, not by the macro-cell's centre: no block edges
(the football's staircase at `high`)."""

import dataclasses

from app.scenes import get_scene
from core.camera import Camera
from core.lod import LodConfig, LodLevel
from core.quality import level_steps
from render.grass_type import technique_colors

BASE = get_scene("bench")
# a long transition between a volume of 8 slices and one of 1 slice, drawn in 8-cell macro-cells
SCENE = dataclasses.replace(
    BASE,
    lod=LodConfig(
        (
            LodLevel("volume", 0.0, 34.0, slices=8, macro=8),
            LodLevel("volume", 10.0, None, slices=1, macro=8),
        )
    ),
)
CAMERA = Camera.from_eye_target((-10.0, 22.0, -10.0), (16.0, 0.0, 16.0), fov_y=50.0)
COLORS = [c for name in ("geometry", "volume", "image") for c in technique_colors()[name]]


def steps(headless, monkeypatch, per_sample: bool) -> dict:
    if not per_sample:  # every cell by its centre's w alone
        monkeypatch.setattr("core.draw_list.lod_fades", lambda config: {})
    renderer = headless(SCENE.document())
    size = (320, 240)
    shaded, _ = renderer.render(CAMERA, size)
    renderer.pipeline.view = "techniques"
    techniques, _ = renderer.render(CAMERA, size)
    return level_steps(shaded, techniques, COLORS)


def test_shared_macro_cells_hand_over_without_block_edges(headless, monkeypatch):
    by_centre = steps(headless, monkeypatch, per_sample=False)
    monkeypatch.undo()
    by_sample = steps(headless, monkeypatch, per_sample=True)
    assert by_centre["across_pairs"] > 50
    # the steps where the levels meet shrink to those the grass shows within one level
    assert by_sample["p95_across_over_inside"] < 0.9 * by_centre["p95_across_over_inside"]
    assert by_sample["across_over_inside"] < 0.85 * by_centre["across_over_inside"]
    assert by_sample["across_over_inside"] < 1.1
