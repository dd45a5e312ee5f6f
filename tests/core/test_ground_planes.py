"""The volume cuboids on a slope (core/ground_planes.py, core/terrain.py planes_of): the
two planes hold the ground of their block wherever it is, and on a slope they lie closer than
the block's height range."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from core.ground_planes import ground_planes
from core.heights import (
    bilinear,
    cell_ranges,
    corner_deviations,
    hills,
)
from core.quadtree import half_outward
from core.terrain import Terrain


@settings(max_examples=25, deadline=None)
@given(
    map_size=st.integers(2, 40),
    columns=st.integers(4, 24),
    rows=st.integers(4, 24),
    block=st.sampled_from([1, 2, 3, 4]),
    seed=st.integers(0, 100),
)
def test_planes_hold_the_ground_of_their_block(map_size, columns, rows, block, seed):
    rng = np.random.default_rng(seed)
    heights = rng.random((map_size, map_size)).astype(np.float32)
    corners, below, above = corner_deviations(heights, 5.0, columns, rows)
    lo, _ = cell_ranges(heights, 5.0, columns, rows)
    ix = rng.integers(0, columns - block + 1, 20)
    iz = rng.integers(0, rows - block + 1, 20)
    base = np.array([lo[a : a + block, b : b + block].min() for a, b in zip(ix, iz, strict=True)])
    planes = ground_planes(corners, below, above, ix, iz, block, block, base)
    # dense random points of every block lie between its two planes
    k = np.repeat(np.arange(20), 500)
    x, z = rng.random(k.size) * block, rng.random(k.size) * block
    y = bilinear(heights, (ix[k] + x) / columns, (iz[k] + z) / rows) * 5.0
    over = y - base[k] - planes[k, 0] * x - planes[k, 1] * z
    assert np.all(over >= planes[k, 2] - 1e-4) and np.all(over <= planes[k, 3] + 1e-4)


def test_a_ramp_is_followed_exactly_and_flat_ground_keeps_the_range():
    ramp = np.tile(np.linspace(0.0, 1.0, 64, dtype=np.float32), (64, 1))  # rises along x
    terrain = Terrain(32, 32, heights=ramp, height_scale=8.0)
    cells = terrain.cells([8, 16], [0, 8], 8, 8, ground=([2.0, 4.0], [4.0, 6.0]))  # off the edges
    planes = terrain.planes_of(cells)
    assert np.allclose(planes[:, 0], 8.0 / 32.0 * 64 / 63, rtol=0.02)  # the ramp's rise a cell
    assert np.allclose(planes[:, 1], 0.0, atol=1e-6)
    assert np.all(planes[:, 3] - planes[:, 2] < 0.05)  # the ramp lies in the plane
    flat = Terrain(32, 32)
    level = flat.planes_of(flat.cells([0], [0], 8, 8))
    assert np.array_equal(level, np.zeros((1, 4), np.float32))


def test_planes_are_closer_than_the_range_on_hills():
    terrain = Terrain(48, 48, heights=hills(256, seed=7, period=3), height_scale=3.0)
    ix, iz = np.meshgrid(np.arange(0, 48, 4), np.arange(0, 48, 4), indexing="ij")
    ix, iz = ix.ravel(), iz.ravel()
    cell_min, cell_max = terrain.cell_min, terrain.cell_max  # each a copy made per call
    lo = np.array([cell_min[a : a + 4, b : b + 4].min() for a, b in zip(ix, iz, strict=True)])
    hi = np.array([cell_max[a : a + 4, b : b + 4].max() for a, b in zip(ix, iz, strict=True)])
    cells = terrain.cells(ix, iz, 4, 4, ground=(lo, hi))
    planes = terrain.planes_of(cells)
    thickness = planes[:, 3] - planes[:, 2]
    assert np.all(thickness <= cells["ground"][:, 1] + 1e-6)
    assert thickness.mean() < 0.6 * cells["ground"][:, 1].mean()


def test_half_outward_is_the_next_half_float_either_way():
    """Every half float stays itself; a value between two neighbours goes to the lower one
    down and the upper one up, in float32 and float64, subnormals, zeros and the largest
    value included (beyond it: the largest down, infinity up)."""
    halves = np.arange(0, 65536, dtype=np.uint16).view(np.float16)
    halves = halves[np.isfinite(halves)]
    for dtype in (np.float32, np.float64):
        exact = halves.astype(dtype)
        for down in (True, False):
            got = half_outward(exact, down=down)
            assert np.array_equal(got.view(np.uint16), halves.view(np.uint16))
    ordered = np.unique(halves.astype(np.float64))  # -0 and +0 as one
    between = 0.5 * (ordered[:-1] + ordered[1:])
    for dtype in (np.float32, np.float64):
        assert np.array_equal(half_outward(between.astype(dtype), down=True), ordered[:-1])
        assert np.array_equal(half_outward(between.astype(dtype), down=False), ordered[1:])
    beyond = np.array([65519.0, -65519.0, 1e6], np.float32)
    assert half_outward(beyond, down=True).tolist() == [65504.0, -np.inf, 65504.0]
    assert half_outward(beyond, down=False).tolist() == [np.inf, -65504.0, np.inf]


def test_deviations_kept_in_half_precision_stay_bounds():
    """The per-cell deviations are kept in float16 (half the memory of a 4096² terrain's two
    tables): each is rounded away from the ground it bounds, never across it."""
    values = np.random.default_rng(3).normal(0.0, 3.0, 100_000).astype(np.float32)
    # and the edges of half floats: values that round to zero, to the largest, beyond it
    edges = [1e-9, -1e-9, 0.0, -0.0, 3e-8, -3e-8, 65510.0, -65510.0, 70000.0, -70000.0, 1.0]
    values = np.concatenate([values, np.array(edges, np.float32)])
    below, above = half_outward(values, down=True), half_outward(values, down=False)
    assert below.dtype == above.dtype == np.float16
    assert np.all(below.astype(np.float32) <= values)
    assert np.all(above.astype(np.float32) >= values)
    assert np.abs(above.astype(np.float32) - values)[:100_000].max() < 0.01  # and close
    _, lo, hi = corner_deviations(hills(33), 5.0, 20, 20)
    assert lo.dtype == hi.dtype == np.float16
