import numpy as np
import pytest

from core.mipmaps import (
    alpha_weighted_reduce,
    bleed_colors,
    box_reduce,
    build_mips,
)

GREEN = np.array([0.25, 0.6, 0.1], dtype=np.float32)
REF = 0.5


def blade_slice(w=256, h=64, seed=0, count=40) -> np.ndarray:
    """Thin blades (1-3 texels wide, anti-aliased edges) over a transparent black background,
    like a rendered slice."""
    rng = np.random.default_rng(seed)
    img = np.zeros((h, w, 4), dtype=np.float32)
    for x in rng.integers(0, w - 3, count):  # test fixture, not product code
        width = rng.integers(1, 4)
        top = rng.integers(h // 3, h)
        img[h - top :, x : x + width, :3] = GREEN
        img[h - top :, x : x + width, 3] = 1.0
        edge = rng.uniform(0.2, 0.8)
        for side in (x - 1, x + width):
            if 0 <= side < w and img[h - 1, side, 3] == 0.0:
                img[h - top :, side, :3] = GREEN
                img[h - top :, side, 3] = edge
    return img


def coverage(alpha: np.ndarray) -> float:
    """The share of texels an alpha test at REF passes (eq. 4.11)."""
    return float(np.mean(alpha > REF))


@pytest.mark.parametrize("count", [16, 40])
def test_every_level_keeps_the_share_the_blades_cover(count):
    """Alpha stays the covered share at every level (the volume composites it as the blades'
    opacity, the image-based grass covers that share of a pixel's samples), where an alpha
    test of a box-filtered level loses thin blades (the thesis's Fig. 4.8)."""
    base = blade_slice(count=count)
    covered = float(base[..., 3].mean())
    assert 0.03 < covered < 0.5
    ours = build_mips(base)
    assert len(ours) == 9  # 256 × 64 down to 1 × 1
    for level in ours[1:]:
        assert float(level[..., 3].mean()) == pytest.approx(covered, rel=1e-4)
    if count == 16:  # sparse thin blades: an alpha test of the reduced level passes few
        assert coverage(ours[3][..., 3]) < 0.5 * coverage(base[..., 3])


def test_max_alpha_saturates_on_thin_blades():
    """Why build_mips carries mean alpha: eq. 4.12's max leaves no room for a rescale."""
    level = blade_slice()
    for _ in range(4):
        level = alpha_weighted_reduce(level, alpha="max")
    assert np.unique(level[..., 3]).size <= 2 and coverage(level[..., 3]) > 0.7


def test_alpha_weighted_colour_ignores_transparent_texels():
    img = np.zeros((2, 2, 4), np.float32)
    img[0, 0] = [*GREEN, 1.0]  # one opaque blade texel, three transparent black ones
    out = alpha_weighted_reduce(img)
    assert np.allclose(out[0, 0, :3], GREEN) and out[0, 0, 3] == 0.25
    assert alpha_weighted_reduce(img, alpha="max")[0, 0, 3] == 1.0
    assert np.allclose(box_reduce(img)[0, 0, :3], GREEN / 4)  # the box filter greys it


def test_bleeding_fills_transparent_texels_with_blade_colour():
    base = blade_slice()
    bled = build_mips(base)[0]
    edge = (base[..., 3] == 0.0) & (np.roll(base[..., 3], 1, axis=1) == 1.0)  # next to a blade
    assert edge.sum() > 10
    # before: black; after: the blade's green (no grey halo when bilinear filtering mixes it in)
    assert np.allclose(base[edge][:, :3], 0.0)
    assert np.allclose(bled[edge][:, :3], GREEN, atol=0.02)
    # opaque texels keep their colour exactly
    opaque = base[..., 3] == 1.0
    assert np.allclose(bled[opaque][:, :3], GREEN)


def test_bleeding_mixes_partially_transparent_texels_by_alpha():
    top = np.array([[[0.0, 1.0, 0.0, 1.0]]], np.float32)
    base = np.zeros((2, 2, 4), np.float32)
    base[..., 3] = 0.25  # a quarter-opaque black texel
    out = bleed_colors([base, top])[0]
    assert np.allclose(out[..., 1], 0.75)


def test_odd_sizes_are_refused():
    with pytest.raises(ValueError, match="even"):
        alpha_weighted_reduce(np.zeros((3, 4, 4), np.float32))


def test_threshold_spread_grows_from_one_blade_to_all_of_them():
    """0 at the base level (one blade a texel); over many independent uniform thresholds the
    spread of a uniform distribution, 1/√12; thresholds that agree spread by nothing."""
    from core.mipmaps import threshold_spread

    rng = np.random.default_rng(2)
    alpha = np.ones((2, 64, 64), np.float32)
    spread = threshold_spread(rng.random((2, 64, 64)), alpha, 7)
    assert spread[0] == 0.0
    assert np.all(np.diff(spread) >= 0)
    assert abs(spread[-1] - 12**-0.5) < 0.02
    assert threshold_spread(np.full((2, 64, 64), 0.4), alpha, 7).max() < 1e-3


def test_upper_rows_hide_the_lower_ones_in_a_vertical_slices_levels():
    """An opaque upper row's colour is the reduced texel's; alpha stays the covered share."""
    from core.mipmaps import build_mips_stack

    image = np.zeros((1, 2, 2, 4), np.float32)
    image[0, 1, :, :] = (1.0, 1.0, 1.0, 1.0)  # upper row (rows run upward): white, opaque
    image[0, 0, :, :] = (0.0, 0.0, 0.0, 1.0)  # lower row: black, opaque
    upper = build_mips_stack(image, upper_first=True)[1][0, 0, 0]
    plain = build_mips_stack(image)[1][0, 0, 0]
    np.testing.assert_allclose(upper[:3], 1.0, atol=1e-6)
    np.testing.assert_allclose(plain[:3], 0.5, atol=1e-6)
    assert upper[3] == plain[3]


def test_a_reduced_levels_rows_hold_less_depth_than_the_rows_they_average():
    """core/mipmaps.py row_depths: per level and row the depth −ln(1 − ā) of each slice's
    row-mean alpha, averaged over the slices. A reduced level averages alpha over two rows, one
    dense and one empty: a ray crossing the slices at both heights meets the mean of their
    depths, more than the depth of their mean alpha that the reduced level holds (why the
    volume scales a reduced texel's depth by its row's at the base level, shaders/volume.glsl)."""
    from core.mipmaps import row_depths, stacked_slice_mips

    stack = np.zeros((2, 4, 8, 4), np.float32)
    stack[:, 0::2, :, 3] = 0.9  # rows 0 and 2 dense, 1 and 3 empty
    stack[1, :, ::2, 3] = 0.0  # the second slice has every other column empty
    table = row_depths(stacked_slice_mips(stack, 3), 2)
    assert table.shape == (3, 4)
    a = 230 / 255  # 0.9 as 8 bits
    dense = 0.5 * (-np.log(1.0 - a) - np.log(1.0 - 0.5 * a))
    np.testing.assert_allclose(table[0], [dense, 0.0, dense, 0.0], rtol=1e-5)
    reduced = 0.5 * (-np.log(1.0 - 0.5 * a) - np.log(1.0 - 0.25 * a))
    np.testing.assert_allclose(table[1], reduced, rtol=1e-2)  # one row per pair of rows
    assert reduced < 0.6 * (0.5 * dense)  # the two rows' mean depth
