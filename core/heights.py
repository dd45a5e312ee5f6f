"""Terrain heights from the design stack's height map (thesis 6.4.4): bilinear sampling exactly
as the GPU's linear filter does it, and per-cell height ranges for the quadtree's bounding
volumes, the volume cuboids' extrusion (min height, unplanarity) and the unplanarity LOD test."""

from __future__ import annotations

import numba
import numpy as np

from core.quadtree import half_outward


def _texels(coord, size: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """GL_LINEAR with clamp-to-edge along one axis: the two texels around each coordinate in
    0 … 1 (texel centres at (i + 0.5) / size) and the weight of the second."""
    t = np.clip(np.asarray(coord, np.float64) * size - 0.5, 0.0, size - 1)
    i0 = np.floor(t).astype(np.int64)
    return i0, np.minimum(i0 + 1, size - 1), t - i0


def bilinear(heights: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """heights (rows along v, columns along u) sampled at (u, v) in 0 … 1 like GL_LINEAR with
    clamp-to-edge."""
    h, w = heights.shape
    x0, x1, fx = _texels(u, w)
    y0, y1, fy = _texels(v, h)
    top = heights[y0, x0] * (1 - fx) + heights[y0, x1] * fx
    bottom = heights[y1, x0] * (1 - fx) + heights[y1, x1] * fx
    return top * (1 - fy) + bottom * fy


def bilinear_grid(heights: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """bilinear(heights, U, V) on the grid of every u × every v, (u.size, v.size): the same
    arithmetic done separably, along u for each texel row and then along v."""
    h, w = heights.shape
    x0, x1, fx = _texels(u, w)
    y0, y1, fy = _texels(v, h)
    rows_needed = np.unique(np.concatenate([y0, y1]))
    sub = heights[rows_needed]  # only the texel rows the v lines reach
    along = sub[:, x0] * (1 - fx) + sub[:, x1] * fx  # (rows needed, u.size)
    i0 = np.searchsorted(rows_needed, y0)
    i1 = np.searchsorted(rows_needed, y1)
    out = along[i0] * (1 - fy)[:, None] + along[i1] * fy[:, None]  # (v.size, u.size)
    return out.T


def _lines(cells: int, texels: int) -> tuple[np.ndarray, np.ndarray]:
    """Along one axis, in 0 … 1: every cell border and every texel-centre line, sorted, and for
    each cell the index of its first border in that list (the cell's samples run from there
    to its second border, inclusive)."""
    borders = np.arange(cells + 1) / cells
    centres = (np.arange(texels) + 0.5) / texels
    lines = np.unique(np.concatenate([borders, centres]))
    return lines, np.searchsorted(lines, borders)


def block_extremes(values: np.ndarray, starts: np.ndarray, axis: int):
    """Min and max of `values` over each inclusive run [starts[i], starts[i + 1]] on `axis`."""
    lo = np.minimum.reduceat(values, starts[:-1], axis=axis)
    hi = np.maximum.reduceat(values, starts[:-1], axis=axis)
    ends = np.take(values, starts[1:], axis=axis)  # the second border, shared with the next cell
    return np.minimum(lo, ends), np.maximum(hi, ends)


def cell_ranges(
    heights: np.ndarray, scale: float, columns: int, rows: int
) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) world heights of the ground in every cell, (columns, rows) arrays.

    The bilinear surface is bilinear between texel-centre lines, so its extremes inside a cell
    lie where those lines and the cell's borders cross: sampling exactly there is exact (a tiny
    margin covers float rounding). Those crossings form one grid for the whole terrain (every
    cell border and texel-centre line on each axis), sampled once in one compiled pass, a row
    of cells at a time; each cell takes the extremes of its block of the grid."""
    h, w = heights.shape
    xs, x_starts = _lines(columns, w)
    zs, z_starts = _lines(rows, h)
    cell_x = np.minimum(np.searchsorted(xs[x_starts], xs, side="right") - 1, columns - 1)
    x0, x1, tx = _texels(xs, w)
    z0, z1, tz = _texels(zs, h)
    lo = np.empty((columns, rows), np.float32)
    hi = np.empty((columns, rows), np.float32)
    _ranges(
        np.ascontiguousarray(heights), float(scale), x0, x1, tx, cell_x, x_starts,
        z0, z1, tz, z_starts, 1e-4 * max(scale, 1.0), lo, hi,
    )  # fmt: skip
    return lo, hi


@numba.njit(cache=True, inline="always")
def _sample(heights, x0, x1, tx, z0, z1, tz, i, j):
    """The bilinear height where x line i crosses z line j, as bilinear_grid computes it: along
    x on the two texel rows, then along z."""
    top = heights[z0[j], x0[i]] * (1 - tx[i]) + heights[z0[j], x1[i]] * tx[i]
    bottom = heights[z1[j], x0[i]] * (1 - tx[i]) + heights[z1[j], x1[i]] * tx[i]
    return top * (1 - tz[j]) + bottom * tz[j]


@numba.njit(cache=True, inline="always")
def _widen(low, high, value, i, cell, x_starts):
    """A sample on x line i widens the extremes of its cell, and of the cell before it when
    the line is a border (it bounds the cell it begins and the one it ends)."""
    for c in (cell, cell - 1):
        if c == cell or (c >= 0 and i == x_starts[cell]):
            if value < low[c]:
                low[c] = value
            if value > high[c]:
                high[c] = value


@numba.njit(cache=True, parallel=True)
def _ranges(heights, scale, x0, x1, tx, cell_x, x_starts, z0, z1, tz, z_starts, margin, lo, hi):
    """cell_ranges' pass: per row of cells, every crossing of an x line with that row's z lines
    (its borders included) sampled as bilinear_grid samples it and rounded to float32 (which
    keeps the order of values), the extremes taken per cell over the lines that bound it."""
    columns = lo.shape[0]
    for r in numba.prange(lo.shape[1]):
        low = np.full(columns, np.inf, np.float32)
        high = np.full(columns, -np.inf, np.float32)
        for j in range(z_starts[r], z_starts[r + 1] + 1):
            for i in range(x0.shape[0]):
                v = np.float32(_sample(heights, x0, x1, tx, z0, z1, tz, i, j) * scale)
                cx = cell_x[i]
                _widen(low, high, v, i, cx, x_starts)
        for c in range(columns):
            lo[c, r] = np.float64(low[c]) - margin
            hi[c, r] = np.float64(high[c]) + margin


@numba.njit(cache=True, parallel=True)
def _grid(heights, scale, x0, x1, tx, z0, z1, tz, out):
    """bilinear_grid(heights, U, V) * scale into out (U lines, V lines), the same arithmetic."""
    for i in numba.prange(out.shape[0]):
        for j in range(out.shape[1]):
            out[i, j] = _sample(heights, x0, x1, tx, z0, z1, tz, i, j) * scale


def hills(width: int, seed: int = 0, period: int = 3) -> np.ndarray:
    """A smooth, tiling-free hilly height map in 0 … 1 (fractal Perlin noise)."""
    from core.noise import fractal_noise

    c = (np.arange(width) + 0.5) / width
    u, v = np.meshgrid(c, c, indexing="xy")
    n = fractal_noise(u, v, period=period, seed=seed, octaves=3)
    return ((n - n.min()) / max(float(np.ptp(n)), 1e-9)).astype(np.float32)


def ridged_hills(size: int, seed: int = 3) -> np.ndarray:
    """A stand-in for a real digital elevation model, heights 0 … 1: ridged, eroded-looking
    hills (1 − |noise| makes sharp crests where the noise crosses zero, over broad valleys)."""
    from core.noise import fractal_noise

    c = (np.arange(size) + 0.5) / size
    u, v = np.meshgrid(c, c, indexing="xy")
    crest = 1.0 - np.abs(fractal_noise(u, v, period=3, seed=seed, octaves=4))
    broad = fractal_noise(u, v, period=2, seed=seed + 1, octaves=2)
    h = 0.7 * crest**2 + 0.3 * broad
    return (h - h.min()) / max(float(np.ptp(h)), 1e-9)


# -- the image-based slices' grids ------------------------------------------------------------
# An image-based (macro-)cell on uneven ground is drawn as a grid of n × n quads whose vertices
# follow the ground (6.4.4); between them its triangles are chords of the ground. A chord of a
# surface whose second directional derivatives are at most M strays from it by at most
# M · r² / 2, r the triangle's circumradius: M (a² + b²) / 8 for half of an a × b quad, and never
# more than the cell's height range. A grid is fine enough where that error, seen from the eye,
# is under a pixel: the slice carries the top view read at its footprint's mip level, whose
# detail is a pixel wide, and a finer grid's small triangles cost a multisampled pass dearly
# (each pixel along a shared edge is shaded once per triangle that covers a sample of it; every
# 4 × 4 block a triangle touches is shaded whole on llvmpipe). Far away a single cell needs a
# quad or two where a fixed grid of 6 × 6 gave llvmpipe dozens of triangles of a few pixels each.
SLICE_GRIDS = (1, 2, 3, 4, 6)  # the grids an image-based slice is drawn with, quads per side


def _texel_bends(h: np.ndarray, scale: float, dx: float, dz: float) -> np.ndarray:
    """|h_xx| + |h_xz| + |h_zz| (world units) at the inner texels of `h` (rows along z;
    values 0 … 1 times `scale`), from its second differences; dx, dz: cells per texel."""
    hxx = np.abs(h[1:-1, 2:] - 2.0 * h[1:-1, 1:-1] + h[1:-1, :-2]) / (dx * dx)
    hzz = np.abs(h[2:, 1:-1] - 2.0 * h[1:-1, 1:-1] + h[:-2, 1:-1]) / (dz * dz)
    hxz = np.abs(h[2:, 2:] - h[2:, :-2] - h[:-2, 2:] + h[:-2, :-2]) / (4.0 * dx * dz)
    return (hxx + hxz + hzz) * scale


def ground_curvature(heights: np.ndarray, scale: float, columns: int, rows: int) -> float:
    """The largest |h_xx| + |h_xz| + |h_zz| of the ground (world units, cells 1 wide), from the
    height map's second differences (rows along z; values 0 … 1 times `scale`): a bound on
    any second directional derivative of the surface."""
    h = np.asarray(heights, np.float64)
    if h.shape[0] < 3 or h.shape[1] < 3 or scale <= 0.0:
        return 0.0
    return float(_texel_bends(h, scale, columns / h.shape[1], rows / h.shape[0]).max())


def _spread(values: np.ndarray, axis: int) -> np.ndarray:
    """Each entry the largest of itself and its two neighbours along `axis`."""
    n = values.shape[axis]
    p = np.concatenate([np.take(values, [0], axis), values, np.take(values, [n - 1], axis)], axis)
    return np.maximum(
        np.maximum(np.take(p, range(n), axis), np.take(p, range(1, n + 1), axis)),
        np.take(p, range(2, n + 2), axis),
    )


def cell_curvature(heights: np.ndarray, scale: float, columns: int, rows: int) -> np.ndarray:
    """ground_curvature of each cell's own ground, (columns, rows) float32: the largest bend of
    the texels within a texel of the cell (the map's edge texels' included, the surface held
    level beyond them). The bilinear surface bends only along texel-centre lines and across
    texel squares, each reckoned from the texels next to it, so a texel's bend reaches no
    further than a texel: a grid over a gentle cell need not be as fine as the steepest hollow
    of the terrain demands (slice_grids). A band of texel rows at a time."""
    h, w = heights.shape
    if h < 3 or w < 3 or scale <= 0.0:
        return np.zeros((columns, rows), np.float32)
    padded = np.pad(np.asarray(heights, np.float32), 1, mode="edge")
    dx, dz = columns / w, rows / h
    x_starts = (np.arange(columns) * w) // columns  # each cell's first texel
    z_starts = (np.arange(rows) * h) // rows
    by_row = np.empty((h, columns), np.float32)  # per texel row, the cells' largest bends
    band = max(1, 2_000_000 // w)
    for r0 in range(0, h, band):
        r1 = min(r0 + band, h)
        bends = _texel_bends(padded[r0 : r1 + 2].astype(np.float64), scale, dx, dz)
        by_row[r0:r1] = np.maximum.reduceat(_spread(bends, 1), x_starts, axis=1)
    return np.ascontiguousarray(np.maximum.reduceat(_spread(by_row, 0), z_starts, axis=0).T)


def block_maxima(values: np.ndarray) -> list[np.ndarray]:
    """`values` (columns, rows) and its maxima over blocks of 2 × 2, 4 × 4, … cells, down to
    one block: level k's entry (i, j) is the largest over cells [i 2^k, (i + 1) 2^k) × …; in
    the values' own float type."""
    levels = [np.asarray(values)]
    while max(levels[-1].shape) > 1:
        v = levels[-1]
        v = np.pad(v, ((0, v.shape[0] % 2), (0, v.shape[1] % 2)))
        levels.append(np.maximum(np.maximum(v[0::2, 0::2], v[1::2, 0::2]),
                                 np.maximum(v[0::2, 1::2], v[1::2, 1::2])))  # fmt: skip
    return levels


def blocks_max(levels: list[np.ndarray], ix, iz, sx, sz) -> np.ndarray:
    """The largest value over each block of sx × sz cells from cell (ix, iz) (integer arrays),
    from block_maxima: at the level whose blocks are as large as the block's longer side, the
    at most 2 × 2 blocks it reaches into (exact where it is one, as a quadtree's nodes are)."""
    ix, iz, sx, sz = (np.asarray(a, np.int64) for a in (ix, iz, sx, sz))
    out = np.zeros(ix.shape, np.float32)
    level = np.ceil(np.log2(np.maximum(np.maximum(sx, sz), 1))).astype(np.int64)
    level = np.minimum(level, len(levels) - 1)
    for k in np.unique(level):
        at = level == k
        grid = levels[k]
        i0, i1 = ix[at] >> k, np.minimum((ix[at] + sx[at] - 1) >> k, grid.shape[0] - 1)
        j0, j1 = iz[at] >> k, np.minimum((iz[at] + sz[at] - 1) >> k, grid.shape[1] - 1)
        i0, j0 = np.minimum(i0, grid.shape[0] - 1), np.minimum(j0, grid.shape[1] - 1)
        out[at] = np.maximum(
            np.maximum(grid[i0, j0], grid[i1, j0]), np.maximum(grid[i0, j1], grid[i1, j1])
        )
    return out


def slice_grids(
    instances: np.ndarray,
    eye: np.ndarray,
    pixel: float,
    curvature: float | np.ndarray,
    grids: tuple[int, ...] = SLICE_GRIDS,
    tolerance: float = 1.0,
) -> np.ndarray:
    """Per instance (core/grid.py INSTANCE_DTYPE), the coarsest of `grids` whose chords stray
    from the ground by less than `tolerance` pixels seen from `eye` (world x, y, z) at its
    nearest point, `pixel` radians a pixel; the finest where none does."""
    origin = instances["origin"].astype(np.float64)
    size = instances["size"].astype(np.float64)
    low = instances["ground"][:, 0].astype(np.float64)
    spread = instances["ground"][:, 1].astype(np.float64)
    eye = np.asarray(eye, np.float64)
    gap_x = np.maximum(np.maximum(origin[:, 0] - eye[0], eye[0] - origin[:, 0] - size[:, 0]), 0.0)
    gap_z = np.maximum(np.maximum(origin[:, 1] - eye[2], eye[2] - origin[:, 1] - size[:, 1]), 0.0)
    gap_y = np.maximum(np.maximum(low - eye[1], eye[1] - low - spread), 0.0)
    allowed = tolerance * pixel * np.sqrt(gap_x**2 + gap_y**2 + gap_z**2)
    out = np.full(len(instances), grids[-1], np.int32)
    for n in reversed(grids):
        quad = (size[:, 0] / n) ** 2 + (size[:, 1] / n) ** 2
        error = np.minimum(curvature * quad / 8.0, spread)
        out[error <= allowed] = n
    return out


def corner_deviations(
    heights: np.ndarray, scale: float, columns: int, rows: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ground at every cell corner ((columns + 1, rows + 1) world heights, float32: kept
    for the terrain's life, 64 MB more in float64 at 4096² cells, and its rounding lies far
    inside the deviations' margin) and, per cell ((columns, rows) each, float16 rounded
    outward), the least and the most the ground inside it lies above the
    bilinear blend of its four corners: sampled where cell_ranges samples, which is exact for
    the difference too (the blend is bilinear over the whole cell), with cell_ranges' margin.
    One compiled pass over the crossings, a row of cells at a time (_deviations)."""
    h, w = heights.shape
    xs, x_starts = _lines(columns, w)
    zs, z_starts = _lines(rows, h)
    corners = np.empty((columns + 1, rows + 1))  # bilinear_grid of the borders, times scale
    _grid(np.ascontiguousarray(heights), float(scale), *_texels(xs[x_starts], w),
          *_texels(zs[z_starts], h), corners)  # fmt: skip
    # each line's cell and its fraction across it (a border line: the cell it begins, or the
    # last cell for the last border), and the texels a linear filter reads there
    cell_x = np.minimum(np.searchsorted(xs[x_starts], xs, side="right") - 1, columns - 1)
    cell_z = np.minimum(np.searchsorted(zs[z_starts], zs, side="right") - 1, rows - 1)
    x0, x1, tx = _texels(xs, w)
    z0, z1, tz = _texels(zs, h)
    lo = np.empty((columns, rows), np.float32)
    hi = np.empty((columns, rows), np.float32)
    _deviations(
        np.ascontiguousarray(heights), float(scale), corners,
        x0, x1, tx, cell_x, xs * columns - cell_x, x_starts,
        z0, z1, tz, cell_z, zs * rows - cell_z, z_starts,
        1e-4 * max(scale, 1.0), lo, hi,
    )  # fmt: skip
    return corners.astype(np.float32), half_outward(lo, down=True), half_outward(hi, down=False)


@numba.njit(cache=True, parallel=True)
def _deviations(
    heights, scale, corners, x0, x1, tx, cell_x, fx, x_starts,
    z0, z1, tz, cell_z, fz, z_starts, margin, lo, hi,
):  # fmt: skip
    """Per row of cells r, every crossing of an x line with the z lines of that row (its
    borders included) sampled as bilinear_grid samples it, less the blend of the corners of
    the sample's own cell, and the extremes taken per cell over the lines that bound it: the
    arithmetic of the numpy bands, bit for bit, in one pass."""
    columns = lo.shape[0]
    for r in numba.prange(lo.shape[1]):
        low = np.full(columns, np.inf)
        high = np.full(columns, -np.inf)
        for j in range(z_starts[r], z_starts[r + 1] + 1):
            cz, gz = cell_z[j], fz[j]
            for i in range(x0.shape[0]):
                sample = _sample(heights, x0, x1, tx, z0, z1, tz, i, j) * scale
                cx, gx = cell_x[i], fx[i]
                near = corners[cx, cz] * (1 - gx) + corners[cx + 1, cz] * gx
                far = corners[cx, cz + 1] * (1 - gx) + corners[cx + 1, cz + 1] * gx
                d = sample - (near * (1 - gz) + far * gz)
                _widen(low, high, d, i, cx, x_starts)
        for c in range(columns):
            lo[c, r] = low[c] - margin
            hi[c, r] = high[c] + margin
