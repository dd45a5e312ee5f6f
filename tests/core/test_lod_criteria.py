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
LV = lod_criteria.Levels.of(CONFIG)


def nodes(dmin, dmax, span=4, unplanarity=0.0):
    d0 = np.array(dmin, float)[:, None]
    d1 = np.array(dmax, float)[:, None]
    y = np.zeros(len(dmin), np.float32)
    return lod_criteria.Nodes(d0, d1, span, y, y + unplanarity)


def test_distance_keeps_the_levels_a_node_reaches():
    m = lod_criteria.distance(nodes([0, 9, 40], [5, 12, 60]), LV)
    assert m.tolist() == [[True, False, False], [True, True, False], [False, False, True]]


def test_macro_cells_only_in_a_levels_own_zone_and_within_its_limit():
    m = lod_criteria.macro_cell(nodes([12, 12, 26, 40], [20, 29, 28, 70], span=4), LV)
    assert m[0].tolist() == [False, True, False]  # inside volume's own zone
    assert not m[1].any()  # reaches into the volume-image transition
    assert not m[2].any()  # inside the transition
    assert m[3].tolist() == [False, False, True]
    assert not lod_criteria.macro_cell(nodes([40], [70], span=32), LV).any()  # too large


def test_unplanar_nodes_are_no_macro_cells_where_a_limit_is_set():
    assert lod_criteria.flat(nodes([40], [70], unplanarity=2.0), LV).tolist() == [
        [True, True, False]
    ]


def test_shared_nodes_lie_in_two_neighbouring_levels_only():
    s = lod_criteria.shared(nodes([26, 9, 9], [29, 9.5, 29], span=4), LV)
    assert s[0].tolist() == [False, True]  # volume-image band, both limits allow 4
    assert s[1].tolist() == [False, False]  # geometry-volume: geometry draws no macro-cells
    assert s[2].tolist() == [False, False]  # reaches into three levels
