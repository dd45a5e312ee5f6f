import itertools

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from core.grid import grid_instances
from core.lod import (
    HAND_OVER_BAND,
    LodConfig,
    LodLevel,
    classify,
    opacity,
    select,
    shown_thresholds,
    weight_near,
)


@given(
    w=st.floats(0.0, 1.0),
    ld=st.floats(0.05, 1.0),
    eps=st.floats(0.0, 0.2),
)
def test_each_blade_is_shared_out_exactly_once(w, ld, eps):
    t = np.linspace(1e-4, 1.0, 400)
    near = opacity(t, w, ld, eps, far=False)
    far = opacity(t, w, ld, eps, far=True)
    visible = t <= ld
    assert np.allclose((near + far)[visible], 1.0)
    assert np.all((near + far)[~visible] == 0.0)
    assert np.all((near >= 0) & (near <= 1) & (far >= 0) & (far <= 1))


def test_blades_move_over_gradually_with_distance():
    t = np.random.default_rng(0).random(5000)
    d = np.linspace(2.0, 4.0, 41)
    w = weight_near(d, 2.5, 3.5)
    assert w[0] == 1.0 and w[-1] == 0.0 and np.all(np.diff(w) <= 0)
    near_share = [opacity(t, wi, 1.0, 0.05, far=False).mean() for wi in w]
    assert np.all(np.diff(near_share) <= 1e-9)  # monotone hand-over, no jumps
    assert np.max(np.abs(np.diff(near_share))) < 0.06


def test_smoothstep_window_only_touches_blades_near_w():
    t = np.array([0.3, 0.49, 0.5, 0.51, 0.7])
    near = opacity(t, 0.5, 1.0, 0.05, far=False)
    assert near[0] == 1.0 and near[-1] == 0.0 and 0.0 < near[2] < 1.0


def test_select_puts_every_cell_in_a_zone_and_band_cells_in_two():
    cells = grid_instances(16, 16)
    config = LodConfig.zones(geometry_end=3.0, volume_end=6.0, transition=1.0)
    geometry, volume, image = select(cells, np.array([0.0, 1.0, 0.0]), config)
    total = geometry.size + volume.size + image.size
    in_two = total - cells.size
    assert in_two > 0  # transition bands exist
    both = geometry[geometry["lod"][:, 0] < 2.0]
    assert both.size and np.all(both["lod"][:, 1] == 0.0)
    far_side = volume[volume["lod"][:, 1] == 1.0]
    assert far_side.size == both.size  # the same band cells, on the far side
    assert np.array_equal(np.sort(far_side["origin"], axis=0), np.sort(both["origin"], axis=0))
    assert image.size > 0


def test_thesis_football_levels_are_accepted_and_hand_over_pairwise():
    levels = (
        LodLevel("geometry", 0, 20),
        LodLevel("volume", 5, 80, slices=8),
        LodLevel("volume", 50, 160, slices=2, macro=32),
        LodLevel("volume", 100, 300, slices=1, macro=32),
        LodLevel("image", 200, None, macro=512),
    )
    config = LodConfig(levels)
    d = np.linspace(0, 400, 4001)
    parts = classify(d, config)
    drawn = sum(inside.astype(int) for inside, _ in parts)
    assert drawn.min() == 1 and drawn.max() == 2  # every distance drawn, at most by two levels
    # in every overlap the near level keeps blades below w, the far one the rest, same w
    for (a_in, a_lod), (b_in, b_lod) in itertools.pairwise(parts):
        band = a_in & b_in
        assert band.any()
        assert np.all(a_lod[band, 1] == 0) and np.all(b_lod[band, 1] == 1)
        assert np.allclose(a_lod[band, 0], b_lod[band, 0])
        w = a_lod[band, 0]
        assert np.all(np.diff(w) <= 1e-6) and w[0] > 0.99 and w[-1] < 0.01


@pytest.mark.parametrize(
    ("levels", "message"),
    [
        (
            (LodLevel("geometry", 0, 5), LodLevel("volume", 6, None)),
            "begin after the geometry zone",
        ),
        ((LodLevel("geometry", 1, None),), "begin at distance 0"),
        ((LodLevel("geometry", 0, 5),), "run to the horizon"),
        (
            (
                LodLevel("geometry", 0, 10),
                LodLevel("volume", 2, 12),
                LodLevel("image", 8, None),
            ),
            "overlap",
        ),
    ],
)
def test_bad_levels_are_refused(levels, message):
    with pytest.raises(ValueError, match=message):
        LodConfig(levels)


def test_bad_zones_are_refused():
    with pytest.raises(ValueError, match="increasing"):
        LodConfig.zones(geometry_end=5.0, volume_end=2.0)
    with pytest.raises(ValueError, match="macro-cells"):
        LodLevel("geometry", 0, 5, macro=4)
    with pytest.raises(ValueError, match="not one of"):
        LodLevel("billboard", 0, 5)


def test_share_of_many_blades_is_their_mean_opacity():
    """A reduced texel's share equals the mean of eq. 5.26 over blades whose thresholds spread
    uniformly around the texel's mean; near + far keep each blade once; spread 0 is one blade."""
    from core.lod import SPREAD_WIDTH, share

    rng = np.random.default_rng(5)
    for mean, spread, density, w in [
        (0.5, 0.29, 0.6, 2.0),
        (0.3, 0.1, 0.8, 0.5),
        (0.6, 0.2, 1.0, 0.6),
    ]:
        half = 0.5 * SPREAD_WIDTH * spread
        t = rng.uniform(mean - half, mean + half, 200000)
        for far in (False, True):
            blades = opacity(t, w, density, 1e-4, far).mean()
            assert abs(share(mean, spread, w, density, 1e-4, far) - blades) < 0.02
        total = share(mean, spread, w, density, 0.05, False) + share(
            mean, spread, w, density, 0.05, True
        )
        assert abs(total - np.mean(t < density)) < 0.02
    # a bare cell keeps nothing of any texel, however far its thresholds spread
    means = np.linspace(0.0, 1.0, 11)
    assert share(means, 0.29, 2.0, 0.0, 0.05, False).max() < 1e-5
    t = rng.random(1000)
    for far in (False, True):
        single = share(t, 0.0, 0.5, 0.8, 0.05, far)
        assert np.abs(single - opacity(t, 0.5, 0.8, 0.05, far)).max() < 1e-3


def test_distances_set_for_a_view_height_scale_with_the_views_pixels_per_radian():
    config = LodConfig(
        (LodLevel("geometry", 0.0, 4.0), LodLevel("volume", 3.0, 9.0), LodLevel("image", 8.0)),
        view_height=270,
    )
    assert config.view_scale(270, 50.0) == pytest.approx(1.0)
    same = config.for_view(270, 50.0)
    assert [(lv.begin, lv.end) for lv in same.levels] == [(0, 4), (3, 9), (8, None)]
    taller = config.for_view(540, 50.0)  # twice the pixels: every zone twice as far
    assert [lv.begin for lv in taller.levels] == pytest.approx([0, 6, 16])
    assert [lv.end for lv in taller.levels[:2]] == pytest.approx([8, 18])
    assert taller.levels[2].end is None
    assert taller.view_height is None  # world units now: not scaled twice
    assert config.view_scale(270, 25.0) > 2.0  # zoomed in: more pixels per radian
    assert config.view_scale(135, 50.0) == pytest.approx(0.5)
    world = LodConfig(config.levels)  # no view height: world units for any view
    assert world.for_view(2160, 20.0) is world


def test_a_view_height_out_of_range_is_refused():
    for bad in (0.0, 15.0, 20000.0):
        with pytest.raises(ValueError, match="view height"):
            LodConfig(view_height=bad)


def test_a_taller_view_selects_geometry_farther_out_as_the_scaled_levels_do():
    cells = grid_instances(40, 40)
    eye = (0.0, 2.0, 0.0)
    config = LodConfig(
        (LodLevel("geometry", 0.0, 4.0), LodLevel("volume", 3.0, 9.0), LodLevel("image", 8.0)),
        view_height=300,
    )
    small = select(cells, eye, config.for_view(300, 50.0))
    large = select(cells, eye, config.for_view(900, 50.0))
    by_hand = LodConfig(
        (LodLevel("geometry", 0.0, 12.0), LodLevel("volume", 9.0, 27.0), LodLevel("image", 24.0))
    )
    expected = select(cells, eye, by_hand)
    assert len(large[0]) > 4 * len(small[0])
    for got, want in zip(large, expected, strict=True):
        assert np.array_equal(got["origin"], want["origin"])
        assert np.allclose(got["lod"], want["lod"])


def test_the_winds_blade_reach_moves_the_hand_over_from_the_blades_out():
    config = LodConfig(
        (LodLevel("geometry", 0.0, 4.0), LodLevel("volume", 3.0, 9.0), LodLevel("image", 8.0)),
    )
    assert config.with_blade_reach(1.0) is config
    # the volume begins farther out; the blades keep their end while it lies beyond that
    near = config.with_blade_reach(1.25)
    assert [(lv.begin, lv.end) for lv in near.levels] == [(0, 4), (3.75, 9), (8, None)]
    # beyond it, the blades run on past the volume's begin to blend with it
    reached = config.with_blade_reach(1.5)
    assert reached.levels[1].begin == pytest.approx(4.5)
    assert reached.levels[0].end == pytest.approx(4.5 * (1.0 + HAND_OVER_BAND))
    cells = grid_instances(40, 40)
    eye = (0.0, 2.0, 0.0)
    assert len(select(cells, eye, reached)[0]) > len(select(cells, eye, config)[0])
    # held inside the levels after it: the volume begins before the image level does, and
    # the image level (beginning at 8) never overlaps the blades
    far = config.with_blade_reach(2.0)
    assert [far.levels[0].end, far.levels[1].begin] == pytest.approx([6.3, 5.5])
    tight = LodConfig(
        (LodLevel("geometry", 0.0, 4.0), LodLevel("volume", 3.0, 9.0), LodLevel("image", 4.5)),
    )
    assert tight.with_blade_reach(2.0).levels[0].end == pytest.approx(4.5)


@given(
    ends=st.lists(st.floats(0.5, 50.0), min_size=1, max_size=3, unique=True),
    overlap=st.floats(0.0, 0.99),
    reach=st.floats(1.0, 2.0),
    order=st.sampled_from([("geometry", "volume", "image"), ("volume", "geometry", "image")]),
)
def test_any_valid_levels_stay_valid_with_any_blade_reach(ends, overlap, reach, order):
    ends = sorted(ends)
    levels, begin = [], 0.0
    for i, end in enumerate([*ends, None]):
        levels.append(LodLevel(order[i % 3], begin, end))
        if end is not None:  # the next level begins inside this one and after the one before
            previous_end = levels[i - 1].end if i > 0 else 0.0
            begin = max(begin, previous_end) + (1.0 - overlap) * (end - max(begin, previous_end))
            begin = min(max(begin, previous_end), end)
            if begin <= levels[i].begin:
                return
    try:
        config = LodConfig(tuple(levels))
    except ValueError:
        return
    reached = config.with_blade_reach(reach)  # raises if the levels it builds are invalid
    for before, after in zip(config.levels, reached.levels, strict=True):
        assert after.begin >= before.begin
        if before.representation == "geometry" and before.end is not None:
            assert after.end >= before.end


def test_fades_give_each_renderer_its_levels_transitions_as_the_cells_weights_use():
    from core.lod import NO_FADE, fades

    config = LodConfig(
        (
            LodLevel("geometry", 0.0, 20.0),
            LodLevel("volume", 5.0, 80.0, slices=8, macro=32),
            LodLevel("volume", 50.0, 160.0, slices=2, macro=32),
            LodLevel("image", 100.0, None, macro=64),
        )
    )
    out = fades(config)
    assert out[("geometry", 0)] == (0.0, 0.0, 5.0, 20.0)
    assert out[("volume", 8)] == (5.0, 20.0, 50.0, 80.0)
    assert out[("volume", 2)] == (50.0, 80.0, 100.0, 160.0)
    assert out[("image", 0)] == (100.0, 160.0, 0.0, 0.0)
    # the same w as the cells' own at any distance in a transition (eq. 5.23)
    d = np.array([60.0, 70.0])
    ((_, lod),) = [classify(d, config)[2]]
    e1, e2 = out[("volume", 2)][:2]
    assert np.allclose(lod[:, 0], weight_near(d, e1, e2))
    # two levels drawn by one renderer: their cells keep their own weights
    twice = LodConfig(
        (
            LodLevel("volume", 0.0, 40.0, slices=4),
            LodLevel("image", 30.0, 90.0),
            LodLevel("volume", 80.0, None, slices=4),
        )
    )
    assert fades(twice)[("volume", 4)] == NO_FADE


@given(
    st.floats(0.0, 1.0),
    st.floats(0.0, 2.0),
    st.booleans(),
    st.floats(0.0, 0.2),
)
def test_the_blades_a_cell_can_show_lie_between_its_shown_thresholds(density, w, far, epsilon):
    """The geometry renderer draws each cell only the blades whose thresholds lie in
    shown_thresholds (render/geometry.py): every blade outside shows nothing, and the run is
    no wider than the blades that show plus the crossover window."""
    t = np.linspace(0.0, 1.0, 4001)
    lo, hi = shown_thresholds(np.array([density]), np.array([[w, float(far)]]), epsilon)
    shown = opacity(t, w, density, epsilon, far) > 0.0
    assert not shown[(t < lo[0]) | (t > hi[0])].any()
    if shown.any():
        window = 2.0 * max(epsilon, 1e-4) * density + 1e-3
        assert hi[0] - lo[0] <= t[shown].max() - t[shown].min() + window
