import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core.ground_mesh import mesh_sink, mesh_size, quad_excess, vertex_sink
from core.heights import (
    SLICE_GRIDS,
    bilinear,
    block_maxima,
    blocks_max,
    cell_curvature,
    cell_ranges,
    ground_curvature,
    hills,
    slice_grids,
)
from core.terrain import Terrain


def test_bilinear_hits_texel_centres_and_interpolates_between():
    h = np.array([[0.0, 1.0], [2.0, 3.0]], np.float32)  # rows along v
    assert bilinear(h, np.array([0.25]), np.array([0.25]))[0] == 0.0
    assert bilinear(h, np.array([0.75]), np.array([0.75]))[0] == 3.0
    assert bilinear(h, np.array([0.5]), np.array([0.25]))[0] == 0.5
    assert bilinear(h, np.array([0.0]), np.array([1.0]))[0] == 2.0  # clamped at the edge


@settings(max_examples=25, deadline=None)
@given(
    map_size=st.integers(2, 40),
    columns=st.integers(1, 30),
    rows=st.integers(1, 30),
    seed=st.integers(0, 100),
)
def test_cell_ranges_enclose_the_surface(map_size, columns, rows, seed):
    heights = np.random.default_rng(seed).random((map_size, map_size)).astype(np.float32)
    lo, hi = cell_ranges(heights, 5.0, columns, rows)
    # dense random points of every cell lie within its range
    rng = np.random.default_rng(seed + 1)
    ix = rng.integers(0, columns, 4000)
    iz = rng.integers(0, rows, 4000)
    u = (ix + rng.random(4000)) / columns
    v = (iz + rng.random(4000)) / rows
    y = bilinear(heights, u, v) * 5.0
    assert np.all(y >= lo[ix, iz]) and np.all(y <= hi[ix, iz])


@pytest.mark.parametrize(("map_size", "columns", "rows"), [(16, 5, 7), (64, 100, 48), (9, 9, 9)])
def test_cell_ranges_are_the_extremes_where_borders_and_texel_lines_cross(map_size, columns, rows):
    """Each cell's range is the least and the most of the surface sampled where its borders and
    the texel-centre lines inside it cross (where a bilinear surface takes its extremes), less
    and plus the margin: tight, not merely enclosing."""
    heights = np.random.default_rng(7).random((map_size, map_size)).astype(np.float32)
    lo, hi = cell_ranges(heights, 5.0, columns, rows)
    centres = (np.arange(map_size) + 0.5) / map_size
    for cx, cz in [(0, 0), (columns - 1, rows - 1), (columns // 2, rows // 3)]:
        u0, u1, v0, v1 = cx / columns, (cx + 1) / columns, cz / rows, (cz + 1) / rows
        us = np.unique([u0, u1, *centres[(centres > u0) & (centres < u1)]])
        vs = np.unique([v0, v1, *centres[(centres > v0) & (centres < v1)]])
        u, v = np.meshgrid(us, vs)
        y = (bilinear(heights, u.ravel(), v.ravel()) * 5.0).astype(np.float32)
        assert lo[cx, cz] == pytest.approx(float(y.min()) - 5e-4, abs=1e-5)
        assert hi[cx, cz] == pytest.approx(float(y.max()) + 5e-4, abs=1e-5)


def test_hills_span_zero_to_one_and_vary_smoothly():
    h = hills(64, seed=3)
    assert h.min() == 0.0 and h.max() == 1.0
    assert np.abs(np.diff(h, axis=0)).max() < 0.2


def _mesh_over_surface(heights, quads, sink, samples=60000, seed=0):
    """The most the ground mesh (vertices sunk by `sink`) rises over the bilinear surface at
    random points (height-map units)."""
    nu, nv = quads
    h = heights.astype(np.float16).astype(np.float64)  # what the textures hold
    rng = np.random.default_rng(seed)
    u, v = rng.random(samples), rng.random(samples)
    a = np.minimum((u * nu).astype(int), nu - 1)
    b = np.minimum((v * nv).astype(int), nv - 1)
    fu, fv = u * nu - a, v * nv - b
    iu, iv = np.meshgrid(np.arange(nu + 1) / nu, np.arange(nv + 1) / nv, indexing="xy")
    vertex = bilinear(h, iu, iv) - sink
    h00, h10, h01, h11 = vertex[b, a], vertex[b, a + 1], vertex[b + 1, a], vertex[b + 1, a + 1]
    mesh = np.where(
        fu + fv <= 1.0,
        h00 + fu * (h10 - h00) + fv * (h01 - h00),
        h11 + (1 - fu) * (h01 - h11) + (1 - fv) * (h10 - h11),
    )
    return float((mesh - bilinear(h, u, v)).max())


@settings(max_examples=20, deadline=None)
@given(
    width=st.integers(2, 70),
    height=st.integers(2, 70),
    nu=st.integers(1, 40),
    nv=st.integers(1, 40),
    seed=st.integers(0, 100),
)
def test_sunk_ground_mesh_lies_under_the_surface(width, height, nu, nv, seed):
    heights = np.random.default_rng(seed).random((height, width)).astype(np.float32)
    sink, _ = mesh_sink(heights, (nu, nv))
    assert sink.shape == (nv + 1, nu + 1) and sink.min() >= 0.0
    assert _mesh_over_surface(heights, (nu, nv), sink, seed=seed) <= 1e-9


def test_unsunk_mesh_of_hollows_would_rise_over_the_surface_and_sinks_only_that_far():
    heights = hills(256, seed=11, period=5)
    quads = (64, 64)  # four texels a quad: chords across the hollows
    assert _mesh_over_surface(heights, quads, np.zeros((65, 65))) > 0.002
    sink, _ = mesh_sink(heights, quads)
    assert _mesh_over_surface(heights, quads, sink) <= 1e-9
    # no deeper than the chords' own rise: a ramp (bilinear = planar) sinks by the margin only
    ramp = np.tile(np.linspace(0.0, 1.0, 50, dtype=np.float32), (40, 1))
    assert mesh_sink(ramp, (25, 20))[0].max() < 0.01


def test_an_edit_redoes_only_the_rows_it_reaches_with_the_same_result():
    heights = hills(96, seed=2)
    quads = mesh_size((96, 96))
    assert quads == (96, 96)  # a quad per texel up to MESH_LIMIT
    _, excess = mesh_sink(heights, quads)
    edited = heights.copy()
    edited[40:50, 10:30] += 0.2
    excess[38:52] = quad_excess(edited, quads, (38, 52))
    assert np.array_equal(vertex_sink(excess), mesh_sink(edited, quads)[0])


def _chord_error(heights, scale, terrain, instance, n, samples=36):
    """The most the n × n grid of chords over an instance's cell strays from its ground, from
    samples (triangles split as core/ground_mesh.py grid_mesh splits them)."""
    ox, oz = instance["origin"] - np.asarray(terrain.origin, np.float32)
    sx, sz = instance["size"]

    def ground(x, z):  # cell coordinates -> world height
        return bilinear(heights, x / terrain.columns, z / terrain.rows) * scale

    t = (np.arange(samples) + 0.5) / samples
    fx, fz = np.meshgrid(t * n, t * n, indexing="ij")
    a, b = np.minimum(np.floor(fx), n - 1), np.minimum(np.floor(fz), n - 1)
    fu, fv = fx - a, fz - b

    def corner(i, j):
        return ground(ox + (a + i) * sx / n, oz + (b + j) * sz / n)

    h00, h10, h01, h11 = corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)
    lower = h00 + fu * (h10 - h00) + fv * (h01 - h00)
    upper = h11 + (1.0 - fu) * (h01 - h11) + (1.0 - fv) * (h10 - h11)
    chord = np.where(fu + fv <= 1.0, lower, upper)
    return float(np.abs(chord - ground(ox + fx * sx / n, oz + fz * sz / n)).max())


@pytest.mark.parametrize(
    ("size", "distance"), [(1, 6.0), (1, 20.0), (1, 60.0), (4, 320.0), (4, 960.0)]
)
def test_slice_grids_keep_their_chords_within_a_pixel_of_the_ground(distance, size):
    """Each cell's grid from the bends of its own ground (Terrain.curvature_of), for single
    cells and for macro-cells."""
    heights = hills(64, seed=5)
    terrain = Terrain.centred(24, 24, heights=heights, height_scale=3.0)
    ix, iz = np.meshgrid(np.arange(0, 24, 2 * size), np.arange(0, 24, 2 * size), indexing="ij")
    ix, iz = ix.ravel(), iz.ravel()
    cell_min, cell_max = terrain.cell_min, terrain.cell_max  # each a copy made per call
    lo = np.array([cell_min[x : x + size, z : z + size].min() for x, z in zip(ix, iz, strict=True)])
    hi = np.array([cell_max[x : x + size, z : z + size].max() for x, z in zip(ix, iz, strict=True)])
    singles = terrain.cells(ix, iz, size, size, ground=(lo, hi))
    eye = np.array([0.0, 3.0 + distance, -12.0 - distance])
    pixel = 2.0 * np.tan(np.radians(25.0)) / 270
    grids = slice_grids(singles, eye, pixel, terrain.curvature_of(singles))
    assert set(np.unique(grids)) <= set(SLICE_GRIDS)
    checked = 0
    for instance, n in zip(singles, grids, strict=True):
        nearest = np.array(
            [
                np.clip(eye[0], instance["origin"][0], instance["origin"][0] + instance["size"][0]),
                np.clip(eye[1], instance["ground"][0], instance["ground"].sum()),
                np.clip(eye[2], instance["origin"][1], instance["origin"][1] + instance["size"][1]),
            ]
        )
        allowed = pixel * np.linalg.norm(eye - nearest)
        if n < SLICE_GRIDS[-1]:
            checked += 1
            assert _chord_error(heights, 3.0, terrain, instance, n) <= allowed
    assert checked > 0  # some cells take a coarser grid than the finest


def test_slice_grids_coarsen_with_distance_and_are_one_quad_on_flat_ground():
    heights = hills(64, seed=5)
    terrain = Terrain.centred(24, 24, heights=heights, height_scale=3.0)
    cells = terrain.cells(np.arange(24), np.full(24, 12))  # a row of cells along x
    pixel = 2.0 * np.tan(np.radians(25.0)) / 270
    near = slice_grids(cells, np.array([-12.0, 4.0, 0.0]), pixel, terrain.curvature)
    far = slice_grids(cells, np.array([-200.0, 4.0, 0.0]), pixel, terrain.curvature)
    assert np.all(far <= near) and far.sum() < near.sum()
    flat = Terrain.centred(24, 24)
    assert np.all(
        slice_grids(
            flat.cells(np.arange(24), np.zeros(24, int)),
            np.array([0.0, 1.0, 0.0]),
            pixel,
            flat.curvature,
        )
        == 1
    )


@settings(max_examples=25, deadline=None)
@given(
    st.integers(8, 40), st.integers(8, 40), st.integers(0, 10_000),
    st.integers(0, 39), st.integers(0, 39), st.integers(1, 16), st.integers(1, 16),
)  # fmt: skip
def test_blocks_max_bounds_every_block_and_is_exact_on_aligned_ones(cols, rows, seed, x, z, sx, sz):
    values = np.random.default_rng(seed).random((cols, rows)).astype(np.float32)
    x, z = x % cols, z % rows
    sx, sz = min(sx, cols - x), min(sz, rows - z)
    levels = block_maxima(values)
    got = blocks_max(levels, [x], [z], [sx], [sz])[0]
    assert got >= values[x : x + sx, z : z + sz].max()
    k = max(sx, sz).bit_length() - 1  # an aligned power-of-two block: exactly its maximum
    bx, bz = (x >> k) << k, (z >> k) << k
    block = values[bx : bx + (1 << k), bz : bz + (1 << k)]
    assert blocks_max(levels, [bx], [bz], [block.shape[0]], [block.shape[1]])[0] == block.max()


def test_cell_curvature_is_the_ground_s_bound_cell_by_cell():
    """Its largest is the whole ground's bound (or more, at the map's edge, where the surface
    is held level); a cell on gentle ground gets less than one in the steepest hollow, so its
    slice's grid is coarser there at the same distance, and never finer."""
    heights = hills(64, seed=5)
    bends = cell_curvature(heights, 3.0, 24, 24)
    assert bends.shape == (24, 24) and bends.dtype == np.float32
    assert bends.max() >= np.float32(ground_curvature(heights, 3.0, 24, 24))
    assert np.percentile(bends, 50) < 0.7 * bends.max()
    terrain = Terrain.centred(24, 24, heights=heights, height_scale=3.0)
    cells = terrain.all_cells()
    pixel = 2.0 * np.tan(np.radians(25.0)) / 270
    eye = np.array([0.0, 20.0, -40.0])
    own = slice_grids(cells, eye, pixel, terrain.curvature_of(cells))
    worst = slice_grids(cells, eye, pixel, terrain.curvature)
    assert np.all(own <= worst) and own.sum() < worst.sum()
    flat = cell_curvature(np.full((16, 16), 0.5, np.float32), 3.0, 8, 8)
    assert np.all(flat == 0.0)


def test_a_terrain_keeps_its_ranges_and_bends_in_half_floats_that_stay_bounds():
    """A 4096² terrain keeps each cell's ground range and bend for its life: in half floats
    (the quadtree's leaves are the ranges, no float32 copy beside them), each rounded outward,
    so every instance's ground still encloses the surface and every bend still bounds it."""
    heights = hills(64, seed=2)
    scale = 40.0  # a landscape's heights, where a half float's step is hundredths of a unit
    lo, hi = cell_ranges(heights, scale, 30, 20)
    bends = cell_curvature(heights, scale, 30, 20)
    terrain = Terrain(30, 20, heights=heights, height_scale=scale)
    assert terrain.tree.y_min[0].dtype == np.float16 and terrain.bends[0].dtype == np.float16
    cells = terrain.all_cells()
    ix, iz = terrain.blocks_of(cells)[:2]
    ground = cells["ground"]
    assert np.all(ground[:, 0] <= lo[ix, iz])
    assert np.all(ground[:, 0] + ground[:, 1] >= hi[ix, iz] - 1e-4 * scale)
    assert np.all(lo[ix, iz] - ground[:, 0] < 0.05)  # and close: a half float's step is 1/32
    assert np.all(terrain.curvature_of(cells) >= bends[ix, iz])
    assert terrain.curvature >= bends.max()


def test_ground_mesh_levels_halve_in_whole_chunks_and_each_is_sunk_on_its_own():
    from core.ground_mesh import GROUND_CHUNKS, chunk_deviation, mesh_levels

    assert mesh_levels((256, 200)) == [(256, 200), (128, 96), (64, 48), (32, 24)]
    assert mesh_levels((8, 8)) == [(8, 8)]  # a quad a chunk: nothing to merge
    assert all(q % GROUND_CHUNKS == 0 for level in mesh_levels((50, 37)) for q in level)
    heights = hills(64, seed=3)
    levels = mesh_levels(heights.shape[::-1])
    sinks = [mesh_sink(heights, q)[0] for q in levels]
    deviation = chunk_deviation(heights, levels, sinks)
    assert deviation.shape == (len(levels), GROUND_CHUNKS, GROUND_CHUNKS)
    # the finest moves by its own sink only; a coarser level by more, somewhere
    own = sinks[0][:-1, :-1].reshape(8, 8, 8, 8).max(axis=(1, 3))
    assert np.all(deviation[0] >= own - 1e-7)
    assert np.all(deviation[1:] >= deviation[0] - 1e-7) and deviation[-1].max() > deviation[0].max()
