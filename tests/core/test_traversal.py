"""The quadtree traversal (thesis 6.1-6.2) against brute force: the same cells per LOD level,
macro-cells covering each cell once, culling that never drops a visible cell."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.scenes import get_scene
from core.camera import Camera
from core.frustum import Frustum
from core.lod import LodConfig, LodLevel, select
from core.quadtree import QuadTree, depth_bound, node_bound
from core.terrain import Terrain
from core.traversal import traverse

FOOTBALL = get_scene("football").lod  # the thesis's five levels (ch. 7)


def expand(instances: np.ndarray) -> dict[tuple[int, int], tuple[float, float]]:
    """(cell x, cell z) → lod for every cell an instance list covers; a cell twice fails."""
    out: dict[tuple[int, int], tuple[float, float]] = {}
    for inst in instances:
        x0, z0 = (round(float(v)) for v in inst["origin"])
        sx, sz = (round(float(v)) for v in inst["size"])
        for x in range(x0, x0 + sx):
            for z in range(z0, z0 + sz):
                assert (x, z) not in out, f"cell {(x, z)} drawn twice in one level"
                out[(x, z)] = tuple(round(float(v), 5) for v in inst["lod"])
    return out


def scaled(config: LodConfig, k: float) -> LodConfig:
    return LodConfig(
        tuple(
            LodLevel(
                lv.representation,
                lv.begin * k,
                None if lv.end is None else lv.end * k,
                lv.slices,
                lv.macro,
            )
            for lv in config.levels
        )
    )


def check_equal(terrain: Terrain, eye, config: LodConfig) -> None:
    """Without macro-cells the traversal draws exactly the cells, (w, side), brute force
    selects, level by level."""
    drawn = traverse(terrain, eye, config)
    brute = select(terrain.all_cells(), eye, config)
    for level, (mine, theirs) in enumerate(zip(drawn.levels, brute, strict=True)):
        assert expand(mine) == expand(theirs), f"level {level}"


def check_blades_once(terrain: Terrain, eye, config: LodConfig) -> None:
    """With macro-cells: every cell's blades are drawn exactly once over all levels. A cell in
    one level keeps all its blades; a cell in two consecutive levels is split by one w, the near
    level keeping threshold < w (side 0), the far one the rest (side 1)."""
    drawn = traverse(terrain, eye, config)
    per_level = [expand(level) for level in drawn.levels]
    for x in range(terrain.columns):
        for z in range(terrain.rows):
            cell = (int(terrain.origin[0]) + x, int(terrain.origin[1]) + z)
            entries = [(t, lv[cell]) for t, lv in enumerate(per_level) if cell in lv]
            assert entries, f"cell {cell} is not drawn"
            if len(entries) == 1:
                _, (w, side) = entries[0]
                assert (side == 0 and w >= 1) or (side == 1 and w <= 0), (cell, entries)
            else:
                assert len(entries) == 2, (cell, entries)
                (t0, (w0, s0)), (t1, (w1, s1)) = entries
                assert t1 == t0 + 1 and s0 == 0 and s1 == 1 and w0 == w1, (cell, entries)


def without_macro(config: LodConfig) -> LodConfig:
    return LodConfig(
        tuple(LodLevel(lv.representation, lv.begin, lv.end, lv.slices, 1) for lv in config.levels)
    )


@settings(max_examples=40, deadline=None)
@given(
    columns=st.integers(1, 70),
    rows=st.integers(1, 70),
    ex=st.floats(-30, 100),
    ez=st.floats(-30, 100),
    k=st.floats(0.05, 0.5),
)
def test_traversal_equals_brute_force_classification(columns, rows, ex, ez, k):
    terrain, eye, config = Terrain(columns, rows), np.array([ex, 2.0, ez]), scaled(FOOTBALL, k)
    check_equal(terrain, eye, without_macro(config))
    check_blades_once(terrain, eye, config)


@pytest.mark.parametrize(("columns", "rows"), [(380, 532), (7, 3)])
def test_every_cell_once_per_level_on_the_thesis_sizes(columns, rows):
    terrain = Terrain(columns, rows)
    k = 1.0 if columns > 100 else 0.05
    for eye in ([190.0, 30.0, -40.0], [10.0, 2.0, 400.0], [0.0, 5.0, 0.0]):
        check_blades_once(terrain, np.array(eye), scaled(FOOTBALL, k))


def test_far_cells_become_macro_cells():
    terrain = Terrain(380, 532)
    drawn = traverse(terrain, np.array([190.0, 30.0, -40.0]), FOOTBALL)
    image = drawn.levels[-1]
    assert image["size"].max() > 16  # far away: large macro-cells (thesis 6.2)
    assert drawn.visited < terrain.tree.node_count / 10  # most branches never visited
    assert sum(level.size for level in drawn.levels) < 1000  # instances, not 200,000 cells
    # at the terrain's edges the macro-cells are cut to fit
    assert np.all(image["origin"] + image["size"] <= np.array(terrain.rect[2:]))


@pytest.mark.parametrize(("columns", "rows"), [(1, 1), (7, 3), (380, 532), (1024, 1024)])
def test_tree_stays_within_eq_6_1(columns, rows):
    tree = QuadTree.build(columns, rows)
    assert tree.depth <= depth_bound(columns, rows)
    assert tree.node_count <= node_bound(columns, rows)
    assert tree.shape(tree.depth - 1) == (1, 1)


def test_height_ranges_aggregate_upwards():
    rng = np.random.default_rng(0)
    lo = rng.uniform(0, 5, (13, 9)).astype(np.float32)
    hi = lo + rng.uniform(0, 2, (13, 9)).astype(np.float32)
    tree = QuadTree.build(13, 9, lo, hi)
    # stored as half floats rounded outwards: never tighter than the truth, off by < 0.01
    assert lo.min() - 0.01 < tree.y_min[-1][0, 0] <= lo.min()
    assert hi.max() <= tree.y_max[-1][0, 0] < hi.max() + 0.01
    assert np.all(tree.y_min[0] <= lo) and np.all(tree.y_max[0] >= hi)
    assert tree.y_min[1][0, 0] <= lo[:2, :2].min() and tree.y_max[1][6, 4] >= hi[12, 8]


def test_bad_terrain_size_is_refused():
    with pytest.raises(ValueError, match="at least 1 × 1"):
        QuadTree.build(0, 5)


def inside_frustum(camera: Camera, aspect: float, points: np.ndarray) -> np.ndarray:
    m = camera.projection(aspect) @ camera.view()
    clip = np.c_[points, np.ones(len(points))] @ m.T
    w = clip[:, 3:4]
    return np.all(np.abs(clip[:, :3]) <= w, axis=1) & (w[:, 0] > 0)


@settings(max_examples=30, deadline=None)
@given(
    ex=st.floats(-20, 60),
    ez=st.floats(-20, 60),
    height=st.floats(0.3, 30),
    yaw=st.floats(0, 2 * math.pi),
    pitch=st.floats(-0.2, 1.4),
    aspect=st.floats(0.5, 2.5),
)
def test_culling_never_drops_a_visible_cell(ex, ez, height, yaw, pitch, aspect):
    terrain = Terrain(40, 30, grass_height=0.5)
    eye = np.array([ex, height, ez])
    look = np.array(
        [math.cos(pitch) * math.sin(yaw), -math.sin(pitch), math.cos(pitch) * math.cos(yaw)]
    )
    camera = Camera.from_eye_target(eye, eye + 10 * look, far=60.0)
    config = LodConfig.zones(geometry_end=6.0, volume_end=15.0, transition=2.0)
    frustum = Frustum.from_camera(camera, aspect)
    culled = traverse(terrain, eye, config, frustum)
    full = traverse(terrain, eye, config)
    for level, (mine, every) in enumerate(zip(culled.levels, full.levels, strict=True)):
        kept, allc = expand(mine), expand(every)
        assert kept.items() <= allc.items()  # culling only removes
        # cells with a point inside the exact frustum (corners, centre, at two heights)
        cells = np.array(sorted(allc))
        if not len(cells):
            continue
        u = np.array([0.0, 1.0, 0.0, 1.0, 0.5])
        v = np.array([0.0, 0.0, 1.0, 1.0, 0.5])
        pts = []
        for y in (0.0, 0.5):
            px = cells[:, 0:1] + u[None, :]
            pz = cells[:, 1:2] + v[None, :]
            pts.append(np.stack([px, np.full_like(px, y), pz], axis=-1))
        pts = np.concatenate(pts, axis=1)
        seen = inside_frustum(camera, aspect, pts.reshape(-1, 3)).reshape(len(cells), -1).any(1)
        for cell in map(tuple, cells[seen]):
            assert cell in kept, f"level {level}: visible cell {cell} was culled"
    assert culled.visited <= full.visited


def test_hilltops_seen_from_below_get_volume_silhouettes():
    from core.heights import hills

    heights = hills(64, seed=2)
    terrain = Terrain(64, 64, heights=heights, height_scale=12.0, grass_height=0.4)
    levels = (
        LodLevel("geometry", 0, 4),
        LodLevel("volume", 3, 12, macro=4),
        LodLevel("image", 10, None, macro=8),
    )
    plain = LodConfig(levels)
    with_tops = LodConfig(levels, silhouettes=True)
    low_eye = np.array([2.0, 8.0, 2.0])
    a = traverse(terrain, low_eye, plain)
    b = traverse(terrain, low_eye, with_tops)
    image = a.levels[2]
    reaching = image[image["ground"].sum(axis=1) + 0.4 > low_eye[1]]
    assert reaching.size > 0 and reaching.size < image.size
    assert b.levels[1].size == a.levels[1].size + reaching.size
    assert np.array_equal(b.levels[2], a.levels[2])  # the image-based cells stay
    high_eye = np.array([2.0, 40.0, 2.0])  # from above no cell is on the skyline
    assert traverse(terrain, high_eye, with_tops).levels[1].size == (
        traverse(terrain, high_eye, plain).levels[1].size
    )


@pytest.mark.parametrize("ex", [0.0, 10.0, 10.5, 23.7])
def test_a_hand_over_without_transition_switches_at_its_distance(ex):
    """A level that ends where the next begins (a person typed End = the next Begin): no
    transition, every cell in exactly one level, the same cells as brute force, and no
    division by the zero width (it stopped the render processes)."""
    hard = LodConfig(
        (
            LodLevel("geometry", 0.0, 5.0, 8, 1),
            LodLevel("volume", 5.0, 12.0, 8, 4),
            LodLevel("image", 12.0, None, 8, 16),
        )
    )
    terrain, eye = Terrain(40, 40), np.array([ex, 1.5, 20.0])
    check_equal(terrain, eye, without_macro(hard))
    check_blades_once(terrain, eye, hard)
    for level, drawn in zip(hard.levels, select(terrain.all_cells(), eye, hard), strict=True):
        lod = drawn["lod"]
        assert np.isfinite(lod).all(), level
        assert ((lod[:, 1] == 0) & (lod[:, 0] >= 1) | (lod[:, 1] == 1) & (lod[:, 0] <= 0)).all()
