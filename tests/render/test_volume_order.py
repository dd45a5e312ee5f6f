"""The order of the volume passes (render/volume_order.py): bands of distance that cover every
cell once, far to near, and the parts of a grass type standing over another."""

import itertools

import numpy as np

from render.volume_order import INF, beneath_heights, distance_bands, stacked_parts


def test_distance_bands_take_every_cell_once_far_to_near():
    rng = np.random.default_rng(2)
    distances = [np.sort(rng.uniform(0, 100, n))[::-1] for n in (50, 7, 0, 120)]
    rows = distance_bands(distances, 8)
    assert len(rows) == 8
    for d, parts in zip(distances, zip(*rows, strict=True), strict=True):
        taken = np.concatenate([np.arange(d.size)[p] for p in parts])
        assert np.array_equal(taken, np.arange(d.size))  # each once, in order
    # a band's cells all lie farther than the next band's, across the arrays
    for near, far in zip(rows[1:], rows[:-1], strict=False):
        nearest = min(d[p].min() for d, p in zip(distances, far, strict=True) if p.stop > p.start)
        farthest = max(d[p].max() for d, p in zip(distances, near, strict=True) if p.stop > p.start)
        assert farthest <= nearest


def test_one_pass_is_one_band():
    d = [np.array([3.0, 2.0, 1.0])]
    assert distance_bands(d, 1) == [[slice(0, 3)]]


def test_types_among_each_other_are_drawn_in_bands_of_height_by_turns():
    beneath = beneath_heights([0.5, 0.2, None], [0.7, 0.3, 0.0])
    assert beneath == [0.3, None, None]
    assert beneath_heights([0.4, 0.4], [0.6, 0.6]) == [None, 0.6]  # as high: the later over
    assert stacked_parts([None, None]) == [[((0, 0), (0.0, INF))]] * 2  # one pass each
    tall, short, none = stacked_parts(beneath, bands=3)
    for parts in (tall, short, none):
        bands = [band for _, band in parts]
        assert bands[0][0] == 0.0 and bands[-1][1] == INF  # every height once, low to high
        assert all(a[1] == b[0] for a, b in itertools.pairwise(bands))
    order = sorted((key, name) for name, parts in (("tall", tall), ("short", short))
                   for key, _ in parts)  # fmt: skip
    # a type's parts at turns one right after the other are one pass over their bands
    assert [name for _, name in order] == ["short", "tall", "short", "tall"]


def test_a_pair_of_types_takes_three_passes_the_lower_drawn_whole_between():
    over, under = stacked_parts(beneath_heights([0.4, 0.2], [0.6, 0.3]))
    assert under == [((0, 1), (0.0, INF))]
    (first, low), (last, high) = over
    assert first < under[0][0] < last
    assert low == (0.0, 0.15) and high == (0.15, INF)
