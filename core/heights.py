"""Terrain heights from the design stack's height map (thesis 6.4.4): bilinear sampling exactly
as the GPU's linear filter does it, and per-cell height ranges for the quadtree's bounding
volumes, the volume cuboids' extrusion (min height, unplanarity) and the unplanarity LOD test."""

from __future__ import annotations

import numpy as np


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


def _block_extremes(values: np.ndarray, starts: np.ndarray, axis: int):
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
    cell border and texel-centre line on each axis), sampled once, a band of cell rows at a
    time; each cell takes the extremes of its block of the grid."""
    h, w = heights.shape
    xs, x_starts = _lines(columns, w)
    zs, z_starts = _lines(rows, h)
    lo = np.empty((columns, rows), np.float32)
    hi = np.empty((columns, rows), np.float32)
    margin = 1e-4 * max(scale, 1.0)
    band = max(1, 4_000_000 // max(xs.size * max(zs.size // rows, 1), 1))
    for r0 in range(0, rows, band):
        r1 = min(r0 + band, rows)
        a, b = z_starts[r0], z_starts[r1]
        # rounding to float32 keeps the order of values, so the extremes of the rounded samples
        # are the rounded extremes (half the memory traffic for the reductions)
        s = (bilinear_grid(heights, xs, zs[a : b + 1]) * scale).astype(np.float32)
        x_lo, x_hi = _block_extremes(s, x_starts, axis=0)  # (columns, z lines)
        starts = z_starts[r0 : r1 + 1] - a
        lo[:, r0:r1] = _block_extremes(x_lo, starts, axis=1)[0].astype(np.float64) - margin
        hi[:, r0:r1] = _block_extremes(x_hi, starts, axis=1)[1].astype(np.float64) + margin
    return lo, hi


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
# is under half a pixel; far away a single cell needs a quad or two where a fixed grid of 6 × 6
# gave llvmpipe dozens of triangles of a few pixels each.
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
    one block: level k's entry (i, j) is the largest over cells [i 2^k, (i + 1) 2^k) × …"""
    levels = [np.asarray(values, np.float32)]
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
    tolerance: float = 0.5,
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


# -- the ground mesh under the grass ---------------------------------------------------------
# The ground is drawn as a triangle grid whose vertices sample the height map; between them
# its triangles are chords of the bilinear surface, and in hollows the chords lie above it and
# hide the grass standing on the true ground (bare ovals in the landscape's volume zone). Each
# vertex is therefore lowered by the most any chord next to it rises over the surface, so that
# the mesh lies on or under the ground the grass stands on, for any height map.
MESH_LIMIT = 256  # grid quads per side at most: one per height-map texel up to this size
# The mesh is drawn in GROUND_CHUNKS × GROUND_CHUNKS chunks, each at the coarsest of its levels
# that stays within half a pixel of the finest seen from the eye (render/ground.py): far away
# the finest's triangles cover a few pixels each, and llvmpipe shades every 4 × 4 pixel block a
# triangle touches whole. Level k's quads are 2^k times as large, as far as a chunk has quads
# to merge; each level is sunk under the surface on its own (mesh_sink).
GROUND_CHUNKS = 8
GROUND_LEVELS = 4


def mesh_size(map_size: tuple[int, int]) -> tuple[int, int]:
    """Grid quads (along u, along v) of the ground mesh's finest level for a height map of
    (width, height) texels: one quad per texel, at most MESH_LIMIT per side, rounded up to
    whole chunks."""

    def whole(texels: int) -> int:
        return -(-min(int(texels), MESH_LIMIT) // GROUND_CHUNKS) * GROUND_CHUNKS

    return whole(map_size[0]), whole(map_size[1])


def mesh_levels(map_size: tuple[int, int]) -> list[tuple[int, int]]:
    """The quads (along u, along v) of each level of the ground mesh, finest first; a level
    that would merge no quads is left out."""
    nu, nv = mesh_size(map_size)
    per_u, per_v = nu // GROUND_CHUNKS, nv // GROUND_CHUNKS
    levels: list[tuple[int, int]] = []
    for k in range(GROUND_LEVELS):
        quads = (GROUND_CHUNKS * max(per_u >> k, 1), GROUND_CHUNKS * max(per_v >> k, 1))
        if not levels or quads != levels[-1]:
            levels.append(quads)
    return levels


def mesh_heights(heights: np.ndarray, quads: tuple[int, int], sink: np.ndarray) -> np.ndarray:
    """The height of each vertex of a ground mesh of `quads` (rows along v), sunk by `sink`
    (mesh_sink), in height-map units: the height map in the float16 the textures hold, sampled
    as GL_LINEAR does at the vertex (shaders/ground.glsl)."""
    nu, nv = quads
    h = np.asarray(heights, np.float32).astype(np.float16).astype(np.float64)
    return bilinear_grid(h, np.arange(nu + 1) / nu, np.arange(nv + 1) / nv).T - sink


def _mesh_at(mesh: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """A mesh's vertex heights (rows along v) interpolated over its triangles (split as
    render/ground.py grid_mesh splits them) at the vertices of a finer grid of `shape`."""
    nv, nu = mesh.shape[0] - 1, mesh.shape[1] - 1
    x = np.arange(shape[1]) * nu / (shape[1] - 1)
    z = np.arange(shape[0]) * nv / (shape[0] - 1)
    a = np.minimum(np.floor(x), nu - 1).astype(np.int64)
    b = np.minimum(np.floor(z), nv - 1).astype(np.int64)
    s, t = (x - a)[None, :], (z - b)[:, None]
    h00, h10 = mesh[b][:, a], mesh[b][:, a + 1]
    h01, h11 = mesh[b + 1][:, a], mesh[b + 1][:, a + 1]
    lower = h00 + s * (h10 - h00) + t * (h01 - h00)
    upper = h11 + (1.0 - s) * (h01 - h11) + (1.0 - t) * (h10 - h11)
    return np.where(s + t <= 1.0, lower, upper)


def chunk_deviation(
    heights: np.ndarray, levels: list[tuple[int, int]], sinks: list[np.ndarray]
) -> np.ndarray:
    """(levels, GROUND_CHUNKS along v, GROUND_CHUNKS along u), height-map units: how far each
    level's mesh lies from the finest's in each chunk, at the finest's vertices, plus how far
    the finest sinks there: what drawing the chunk at that level moves its ground by at most."""
    meshes = [mesh_heights(heights, q, s) for q, s in zip(levels, sinks, strict=True)]
    fine = meshes[0]
    nv, nu = fine.shape[0] - 1, fine.shape[1] - 1
    c = GROUND_CHUNKS

    def per_chunk(values: np.ndarray) -> np.ndarray:
        corners = np.maximum(
            np.maximum(values[:-1, :-1], values[1:, :-1]),
            np.maximum(values[:-1, 1:], values[1:, 1:]),
        )  # each quad's largest at its corners
        return corners.reshape(c, nv // c, c, nu // c).max(axis=(1, 3))

    own = per_chunk(sinks[0].astype(np.float64))
    return np.stack([own + per_chunk(np.abs(_mesh_at(m, fine.shape) - fine)) for m in meshes])


def _quad_lines(quads: int, texels: int, first: int, last: int):
    """Along one axis, in 0 … 1: the mesh lines of quads first … last and the texel-centre
    lines between them, sorted; each quad's index of its first line in that list; and each
    line's quad (the one it starts or lies inside; the last line belongs to quad last - 1)."""
    borders = np.arange(first, last + 1) / quads
    centres = (np.arange(texels) + 0.5) / texels
    centres = centres[(centres > borders[0]) & (centres < borders[-1])]
    lines = np.unique(np.concatenate([borders, centres]))
    owner = np.clip(np.floor(lines * quads + 1e-9).astype(np.int64), first, last - 1)
    return lines, np.searchsorted(lines, borders), owner


def quad_excess(heights: np.ndarray, quads: tuple[int, int], rows: tuple[int, int]) -> np.ndarray:
    """How far the triangles of the quad rows rows = (b0, b1) of a ground mesh of quads =
    (nu, nv) grid quads rise at most over the bilinear surface of `heights` (rows along v, as
    GL_LINEAR samples it, in the float16 the textures hold), in height-map units, ≥ 0:
    (b1 − b0, nu) float32. Vertex (i, j) stands at (u, v) = (i / nu, j / nv); quad (a, b) is
    split from (a + 1, b) to (a, b + 1), as render/ground.py's grid_mesh."""
    nu, nv = quads
    b0, b1 = rows
    h = np.asarray(heights, np.float32).astype(np.float16).astype(np.float64)
    th, tw = h.shape
    us, u_starts, ua = _quad_lines(nu, tw, 0, nu)
    vs, v_starts, vb = _quad_lines(nv, th, b0, b1)
    surface = bilinear_grid(h, us, vs).T  # (v lines, u lines)
    corner_u = np.arange(nu + 1) / nu
    corner_v = np.arange(b0, b1 + 1) / nv
    corner = bilinear_grid(h, corner_u, corner_v).T  # (b1 - b0 + 1, nu + 1)
    fu = us * nu - ua  # 0 … 1 inside the line's quad
    fv = vs * nv - vb
    j = vb - b0
    h00, h10 = corner[j][:, ua], corner[j][:, ua + 1]
    h01, h11 = corner[j + 1][:, ua], corner[j + 1][:, ua + 1]
    fu_, fv_ = fu[None, :], fv[:, None]
    lower = h00 + fu_ * (h10 - h00) + fv_ * (h01 - h00)
    upper = h11 + (1.0 - fu_) * (h01 - h11) + (1.0 - fv_) * (h10 - h11)
    plane = np.where(fu_ + fv_ <= 1.0, lower, upper)
    excess = plane - surface
    # per quad: the largest excess over its block of lines (both borders included), and the
    # spread of the surface there (the GPU's filter weights carry 8 bits: a margin of 1/256)
    rows_at = v_starts - v_starts[0]
    top = _block_extremes(_block_extremes(excess, u_starts, axis=1)[1], rows_at, axis=0)[1]
    lo_u, hi_u = _block_extremes(surface, u_starts, axis=1)
    lo = _block_extremes(lo_u, rows_at, axis=0)[0]
    hi = _block_extremes(hi_u, rows_at, axis=0)[1]
    # along each quad's diagonal the surface is piecewise quadratic, its pieces cut by the
    # texel-centre lines: the excess at every cut, and each piece's own extreme
    along = _diagonal_excess(h, corner, nu, nv, b0, b1)
    top = np.maximum(top, along)
    return (np.maximum(top, 0.0) + (hi - lo) / 256.0).astype(np.float32)


def _diagonal_excess(h, corner, nu: int, nv: int, b0: int, b1: int) -> np.ndarray:
    """The largest excess of the chord over the surface along each quad's diagonal, from
    (a + 1, b) to (a, b + 1) at t = 0 … 1 ((b1 − b0, nu)): exact, since between two cuts by
    texel-centre lines the surface along it is a parabola."""
    th, tw = h.shape
    a = np.arange(nu)[None, :, None]
    b = np.arange(b0, b1)[:, None, None]
    ku = np.arange(int(np.ceil(tw / nu)) + 2)[None, None, :]
    kv = np.arange(int(np.ceil(th / nv)) + 2)[None, None, :]
    # t where u = (k + 0.5) / tw, for the texel lines from just left of the quad; and for v
    cut_u = a + 1.0 - nu * (np.floor(a * tw / nu - 0.5) + ku + 0.5) / tw
    cut_v = nv * (np.floor(b * th / nv - 0.5) + kv + 0.5) / th - b
    shape = (b1 - b0, nu)
    cuts = np.concatenate(
        [np.zeros((*shape, 1)), np.ones((*shape, 1)),
         np.broadcast_to(cut_u, (*shape, cut_u.shape[-1])),
         np.broadcast_to(cut_v, (*shape, cut_v.shape[-1]))], axis=-1,
    )  # fmt: skip
    t = np.sort(np.clip(cuts, 0.0, 1.0), axis=-1)
    mid = 0.5 * (t[..., :-1] + t[..., 1:])
    c10 = corner[:-1, 1:][..., None]
    c01 = corner[1:, :-1][..., None]

    def excess(s):
        return c10 + s * (c01 - c10) - bilinear(h, (a + 1.0 - s) / nu, (b + s) / nv)

    f0, fm, f1 = excess(t[..., :-1]), excess(mid), excess(t[..., 1:])
    # the parabola through the three, in s = 0 … 1 across each piece
    lin = -3.0 * f0 + 4.0 * fm - f1
    quad = 2.0 * f0 - 4.0 * fm + 2.0 * f1
    s_star = np.where(quad < -1e-15, -lin / np.minimum(2.0 * quad, -1e-15), 0.0)
    inside = (s_star > 0.0) & (s_star < 1.0)
    peak = np.where(inside, f0 + s_star * lin + s_star * s_star * quad, f0)
    return np.maximum(np.maximum(f0, f1), peak).max(axis=-1)


def mesh_sink(heights: np.ndarray, quads: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """How far each vertex of the ground mesh must sink (height-map units): (nv + 1, nu + 1)
    float32, and the per-quad excesses it was made from (quad_excess of every row, kept so that
    an edit recomputes only the rows it touches). Computed a band of quad rows at a time."""
    nu, nv = quads
    texels_per_row = heights.shape[1] + nu
    band = max(1, 2_000_000 // (texels_per_row * max(heights.shape[0] // nv + 1, 1)))
    excess = np.concatenate(
        [quad_excess(heights, quads, (b, min(b + band, nv))) for b in range(0, nv, band)]
    )
    return vertex_sink(excess), excess


def vertex_sink(excess: np.ndarray) -> np.ndarray:
    """Per vertex, the largest excess of the (up to four) quads around it: (nv + 1, nu + 1)
    from (nv, nu) per-quad excesses."""
    nv, nu = excess.shape
    out = np.zeros((nv + 1, nu + 1), np.float32)
    for dj in (0, 1):
        for di in (0, 1):
            block = out[dj : dj + nv, di : di + nu]
            np.maximum(block, excess, out=block)
    return out
