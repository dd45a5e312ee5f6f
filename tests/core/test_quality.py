"""The figures of `sward quality` (core/quality.py) on images made to have known answers."""

import numpy as np
import pytest

from core.quality import (
    Comparison,
    bare_blocks,
    block_color_difference,
    heat_map,
    level_steps,
    popping,
    quarter_mask,
    technique_regions,
)

RNG = np.random.default_rng(3)
COLORS = {
    "geometry": [(1.0, 0.15, 0.1)],
    "volume": [(1.0, 0.85, 0.1), (1.0, 0.95, 0.45)],
    "image": [(0.15, 0.35, 1.0)],
}


def grass(h=64, w=96):
    """A noisy green picture, uint8."""
    base = np.array([60, 110, 40], np.float32)
    return np.clip(base + RNG.normal(0, 25, (h, w, 3)), 0, 255).astype(np.uint8)


def test_block_colour_difference_sees_a_darker_area_and_not_noise():
    a = grass()
    assert block_color_difference(a, a) == 0.0
    darker = a.copy()
    darker[:, :48] = (darker[:, :48] * 0.75).astype(np.uint8)  # the left half 25 % darker
    shuffled = a.copy()
    for row in shuffled:  # the same colours, moved about within each row of 8 × 8 blocks
        RNG.shuffle(row[:8])
    assert block_color_difference(a, darker) > 0.03
    assert block_color_difference(a, shuffled) < 0.5 * block_color_difference(a, darker)


def test_technique_regions_from_the_technique_view():
    shaded = grass()
    tech = shaded.copy()
    tech[:20, :30] = (np.array(COLORS["geometry"][0]) * 180).astype(np.uint8)
    tech[20:40, :30] = (np.array(COLORS["volume"][1]) * 150).astype(np.uint8)  # a paler level
    tech[40:, :30] = (np.array(COLORS["image"][0]) * 200).astype(np.uint8)
    regions = technique_regions(shaded, tech, COLORS)
    assert regions["geometry"][:20, :30].all() and regions["geometry"].sum() == 600
    assert regions["volume"][20:40, :30].all() and regions["volume"].sum() == 600
    assert regions["image"][40:, :30].all() and regions["image"].sum() == 24 * 30
    # what the view left alone (sky, soil, props) is no technique's
    assert not any(m[:, 30:].any() for m in regions.values())


def test_quarter_mask_keeps_blocks_mostly_inside():
    mask = np.zeros((16, 16), bool)
    mask[:8, :6] = True
    q = quarter_mask(mask)
    assert q.shape == (4, 4)
    assert q[:2, 0].all() and not q[:2, 1].any() and not q[2:].any()


def test_comparison_of_identical_frames_is_zero_and_of_a_changed_one_is_not():
    a = grass(128, 96)
    same = Comparison.of(a, a)
    assert (same.flip_full, same.flip_quarter, same.block_color) == (0.0, 0.0, 0.0)
    b = a.copy()
    b[:64] = 255 - b[:64]  # the top half inverted
    changed = Comparison.of(a, b)
    assert changed.flip_quarter > 0.1 and changed.block_color > 0.1
    top, bottom = np.zeros((32, 24), bool), np.zeros((32, 24), bool)
    top[:12], bottom[20:] = True, True  # quarter resolution, away from the edge FLIP blurs
    assert changed.region(top) > 10 * changed.region(bottom)
    assert changed.region(np.zeros((32, 24), bool)) is None


def test_popping_is_the_lods_largest_step_over_the_references():
    frames = [grass() for _ in range(4)]
    assert popping(frames, frames)["popping"] == pytest.approx(1.0)
    # a LOD sequence that holds still and then jumps, against a reference that changes evenly
    reference = [np.clip(frames[0].astype(int) + 6 * k, 0, 255).astype(np.uint8) for k in range(4)]
    jump = [reference[0]] * 3 + [np.clip(reference[0].astype(int) + 18, 0, 255).astype(np.uint8)]
    result = popping(jump, reference)
    assert result["popping"] > 1.5
    with pytest.raises(ValueError, match="two frames"):
        popping(frames[:1], frames[:1])


def test_heat_map_runs_from_black_to_white():
    h = heat_map(np.array([[0.0, 0.5, 1.0, 2.0]]))
    assert h.dtype == np.uint8 and h.shape == (1, 4, 3)
    assert h[0, 0].tolist() == [0, 0, 0] and h[0, 2].tolist() == [255, 255, 255]
    assert h[0, 1, 0] == 255 and h[0, 1, 2] == 0  # half way: red, some yellow
    assert h[0, 3].tolist() == [255, 255, 255]  # clipped


def _two_levels(step_at_boundary: float, blocks: bool):
    """A grass picture drawn by two levels, the far one (top) in the technique view's second
    colour; the boundary runs as a staircase of 16-pixel steps (blocks) or straight. The far
    level is `step_at_boundary` brighter."""
    h, w = 128, 128
    shaded = grass(h, w).astype(np.float32)
    rows = np.arange(h)[:, None]
    cols = np.arange(w)[None, :]
    edge = 64 + (16 * ((cols // 16) % 3) if blocks else 0 * cols)
    far = rows < edge
    shaded[far] += step_at_boundary
    shaded = np.clip(shaded, 0, 255).astype(np.uint8)
    technique = np.where(far[..., None], (255, 240, 110), (255, 215, 25)).astype(np.uint8)
    return shaded, technique


def test_level_steps_see_a_brighter_level_as_a_step_and_not_the_grass_texture():
    colors = [(1.0, 0.85, 0.1), (1.0, 0.95, 0.45)]
    even = level_steps(*_two_levels(0.0, blocks=True), colors)
    stair = level_steps(*_two_levels(25.0, blocks=True), colors)
    assert even["across_pairs"] > 20 and even["inside_pairs"] > 100
    assert even["p95_across_over_inside"] < 1.3
    assert stair["p95_across_over_inside"] > 2.0
    assert stair["across_over_inside"] > even["across_over_inside"]
    # against a reference drawn by one level: the same pairs' step there
    reference, _ = _two_levels(0.0, blocks=True)
    shaded, technique = _two_levels(25.0, blocks=True)
    with_ref = level_steps(shaded, technique, colors, reference=reference)
    assert with_ref["across_over_reference"] > 2.0


def test_bare_blocks_counts_terrain_whose_soil_shows_and_not_the_sky():
    h, w = 64, 64
    shaded = grass(h, w)
    shaded[:16] = (150, 190, 230)  # sky
    techniques = shaded.copy()
    techniques[16:] = (255, 40, 25)  # the grass, recoloured
    magenta = shaded.copy()
    magenta[48:, :32] = (230, 20, 220)  # a bare patch: the soil, now magenta, shows
    out = bare_blocks(shaded, magenta, techniques)
    assert out["terrain_blocks"] == 48  # 6 of 8 block rows, not the sky's
    assert out["bare_blocks"] == pytest.approx(8 / 48)
    assert bare_blocks(shaded, shaded, techniques)["bare_blocks"] == 0.0


def test_a_dashed_line_has_gaps_and_a_fading_one_has_none():
    """core/quality.py line_gaps on a grey image with a white line along row 20: whole but
    fading from 0.5 to 0.1 over its length, it has no gaps; dashed (3 pixels on, 3 off), about
    half its points are gaps; drawn nowhere, it is not judged."""
    from core.quality import line_gaps, screen_path

    rng = np.random.default_rng(0)
    base = 0.3 + 0.01 * rng.standard_normal((40, 200, 3))
    x = np.arange(200)
    points = np.c_[x, np.full(200, 20.0)]
    across = np.tile((0.0, 1.0), (200, 1))
    fading, dashed = base.copy(), base.copy()
    fading[20, :, :] += np.linspace(0.5, 0.1, 200)[:, None]
    dashed[20, (x // 3) % 2 == 0, :] += 0.4
    assert line_gaps(fading, points, across)["gaps"] < 0.02
    assert 0.35 < line_gaps(dashed, points, across)["gaps"] < 0.65
    assert line_gaps(base, points, across)["gaps"] is None
    # a line on the ground seen from above projects to pixels about one apart
    from core.camera import Camera

    camera = Camera.from_eye_target((0.0, 10.0, 0.1), (0.0, 0.0, 0.0))
    world = np.c_[np.linspace(-2, 2, 500), np.zeros(500), np.zeros(500)]
    xy, normal = screen_path(world, camera.projection(1.0) @ camera.view(), (100, 100))
    steps = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    assert len(xy) > 20 and np.all(steps >= 1.0) and np.all(steps < 1.5)
    assert np.allclose(np.abs(normal[:, 1]), 1.0, atol=1e-3)  # across a level line: vertical


def test_stripes_across_a_region_raise_its_stripe_contrast():
    """core/quality.py stripe_contrast: a frame whose region shows regular stripes 6 pixels
    apart over the reference's fine noise has more pattern at that scale than the reference;
    the same region smooth has less; outside the mask nothing counts."""
    from core.quality import stripe_contrast

    rng = np.random.default_rng(1)
    reference = 0.4 + 0.05 * rng.standard_normal((96, 128, 3))
    smooth = np.full_like(reference, 0.4)
    striped = smooth + 0.08 * (np.arange(128) // 3 % 2)[None, :, None]
    mask = np.zeros((96, 128), bool)
    mask[16:80, 16:112] = True
    assert stripe_contrast(striped, reference, mask) > 1.5
    assert stripe_contrast(smooth, reference, mask) < 0.2
    assert stripe_contrast(striped, reference, np.zeros_like(mask)) is None
