"""Skipping cells without grass: a cell is dropped only if every bilinear sample of the density
map inside it is zero, edits update exactly like a full recomputation, a quadtree node is
occupied when any of its cells is."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core.heights import bilinear
from core.occupancy import DensityOccupancy


def sparse_map(rng, h, w, channels=2):
    d = np.zeros((h, w, channels), np.float32)
    for c in range(channels):
        for _ in range(rng.integers(0, 4)):
            y, x = rng.integers(0, h), rng.integers(0, w)
            d[y : y + rng.integers(1, 4), x : x + rng.integers(1, 4), c] = rng.random() + 0.01
    return d


def samples_nonzero(d, channel, columns, rows, k=9):
    """Brute force: does any bilinear sample inside each cell (a k × k grid, borders too) see
    grass?"""
    out = np.zeros((columns, rows), bool)
    t = np.linspace(0.0, 1.0, k)
    for c in range(columns):
        for r in range(rows):
            u, v = np.meshgrid((c + t) / columns, (r + t) / rows)
            out[c, r] = np.any(bilinear(d[..., channel], u, v) > 0)
    return out


@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    size=st.sampled_from([(16, 16), (24, 40), (7, 9), (64, 20)]),
    cells=st.sampled_from([(8, 8), (5, 3), (16, 16), (30, 12)]),
)
def test_no_cell_with_grass_is_ever_dropped(seed, size, cells):
    rng = np.random.default_rng(seed)
    d = sparse_map(rng, *size)
    occ = DensityOccupancy(*cells, d)
    for channel in range(2):
        seen = samples_nonzero(d, channel, *cells)
        kept = occ.grows(channel)
        assert not np.any(seen & ~kept)  # grass there: kept
        # conservative only near grass: a kept cell lies within 2 texels of a non-zero texel
        h, w = d.shape[:2]
        ty, tx = np.nonzero(d[..., channel] > 0)
        for c, r in zip(*np.nonzero(kept & ~seen), strict=True):
            gap_x = np.maximum(
                np.maximum(c * w / cells[0] - (tx + 0.5), (tx + 0.5) - (c + 1) * w / cells[0]), 0
            )
            gap_y = np.maximum(
                np.maximum(r * h / cells[1] - (ty + 0.5), (ty + 0.5) - (r + 1) * h / cells[1]), 0
            )
            assert np.min(np.maximum(gap_x, gap_y)) <= 2.0 + 1e-9


def test_bare_cells_are_dropped_and_nodes_ask_for_any_cell():
    d = np.zeros((64, 64, 1), np.float32)
    d[40:48, 8:16] = 1.0  # a clump: texels 8..15 × 40..47, cells of 8 texels: cell (1, 5)
    occ = DensityOccupancy(8, 8, d)
    grid = occ.grows(0)
    assert grid[1, 5] and grid.sum() <= 9  # the clump's cell and, at most, its neighbours
    assert not grid[6, 1]
    # level 2: nodes of 4 × 4 cells; (0, 1) holds cells 0..3 × 4..7, (1, 0) cells 4..7 × 0..3
    assert occ.levels[2][0, 1] & 1 and not occ.levels[2][1, 0] & 1
    assert occ.levels[3][0, 0] & 1  # the root


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 10_000), cells=st.sampled_from([(8, 8), (5, 3), (13, 30), (1, 7)]))
def test_a_node_is_occupied_when_any_of_its_cells_is(seed, cells):
    rng = np.random.default_rng(seed)
    occ = DensityOccupancy(*cells, sparse_map(rng, 24, 24, channels=3))
    for level, nodes in enumerate(occ.levels):
        step = 1 << level
        for x in range(nodes.shape[0]):
            for z in range(nodes.shape[1]):
                cells_bits = occ.levels[0][x * step : (x + 1) * step, z * step : (z + 1) * step]
                assert nodes[x, z] == np.bitwise_or.reduce(cells_bits, axis=None)


@pytest.mark.parametrize("rect", [(0, 0, 3, 3), (10, 20, 7, 1), (60, 60, 4, 4), (31, 0, 1, 64)])
def test_an_edit_updates_like_a_full_recomputation(rect):
    rng = np.random.default_rng(3)
    d = sparse_map(rng, 64, 64)
    occ = DensityOccupancy(12, 10, d)
    x, y, w, h = rect
    d[y : y + h, x : x + w, 0] = 0.0
    d[y : y + h, x : x + w, 1] = 0.7
    occ.update(d, rect)
    full = DensityOccupancy(12, 10, d)
    assert np.array_equal(occ.packed, full.packed)  # cells and every node above them


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000), block=st.sampled_from([(4, 4), (2, 4), (8, 8), (3, 1)]))
def test_a_block_rectangle_holds_every_cell_with_grass(seed, block):
    rng = np.random.default_rng(seed)
    d = sparse_map(rng, 32, 32)
    occupancy = DensityOccupancy(16, 16, d)
    w, h = block
    ix, iz = np.arange(0, 16 - w + 1, w), np.arange(0, 16 - h + 1, h)
    ix, iz = (a.ravel() for a in np.meshgrid(ix, iz, indexing="ij"))
    for channel in range(2):
        rects = occupancy.rects(channel, ix, iz, w, h)
        grows = occupancy.grows(channel)
        for (x, z), (x0, z0, x1, z1) in zip(zip(ix, iz, strict=True), rects, strict=True):
            cells = grows[x : x + w, z : z + h]
            if not cells.any():
                assert (x0, z0, x1, z1) == (0, 0, w, h)
                continue
            inside = np.zeros_like(cells)
            inside[int(x0) : int(x1), int(z0) : int(z1)] = True
            assert not np.any(cells & ~inside)  # every cell with grass lies in the rectangle
            # and the rectangle is the smallest: each of its edges touches such a cell
            assert cells[int(x0)].any() and cells[int(x1) - 1].any()
            assert cells[:, int(z0)].any() and cells[:, int(z1) - 1].any()
