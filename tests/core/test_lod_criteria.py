"""The LOD tests of the traversal, one node and one level (or pair of levels) at a time."""

import numpy as np

from core import lod_criteria
from core.lod import LodConfig, LodLevel

CONFIG = LodConfig(
    (
        LodLevel("geometry", 0, 10),
        LodLevel("volume", 8, 30, macro=4),
        LodLevel("image", 25, None, macro=16, max_unplanarity=0.5),
    )
)
TABLE = lod_criteria.Levels.of(CONFIG).table


def mask(test, dmin, dmax, span=4, levels=3):
    """(nodes × levels) results of one test for nodes given by their distance ranges."""
    return [
        [bool(test(TABLE, t, float(a), float(b), span)) for t in range(levels)]
        for a, b in zip(dmin, dmax, strict=True)
    ]


def test_distance_keeps_the_levels_a_node_reaches():
    def reach(table, t, dmin, dmax, _span):
        return lod_criteria.distance(table, t, dmin, dmax)

    assert mask(reach, [0, 9, 40], [5, 12, 60]) == [
        [True, False, False],
        [True, True, False],
        [False, False, True],
    ]


def test_macro_cells_only_in_a_levels_own_zone_and_within_its_limit():
    m = mask(lod_criteria.macro_cell, [12, 12, 26, 40], [20, 29, 28, 70])
    assert m[0] == [False, True, False]  # inside volume's own zone
    assert not any(m[1])  # reaches into the volume-image transition
    assert not any(m[2])  # inside the transition
    assert m[3] == [False, False, True]
    assert not any(mask(lod_criteria.macro_cell, [40], [70], span=32)[0])  # too large


def test_unplanar_nodes_are_no_macro_cells_where_a_limit_is_set():
    y_lo, y_hi = np.float32(0.0), np.float32(2.0)
    assert [bool(lod_criteria.flat(TABLE, t, y_lo, y_hi)) for t in range(3)] == [
        True,
        True,
        False,
    ]
    assert lod_criteria.flat(TABLE, 2, y_lo, np.float32(0.5))  # at the limit


def test_shared_nodes_lie_in_two_neighbouring_levels_only():
    s = mask(lod_criteria.shared, [26, 9, 9], [29, 9.5, 29])
    assert s[0] == [False, True, False]  # volume-image band, both limits allow 4
    assert s[1] == [False, False, False]  # geometry-volume: geometry draws no macro-cells
    assert s[2] == [False, False, False]  # reaches into three levels; no pair after the last
