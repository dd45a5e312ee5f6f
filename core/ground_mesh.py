"""The ground mesh under the grass (thesis 6.4.4): a grid over the grassed cells whose vertices
sample the height map, each sunk so that the mesh lies under the ground the grass stands on, in
levels of detail drawn chunk by chunk (render/ground.py)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from core.heights import bilinear, bilinear_grid, block_extremes

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
    grid_mesh splits them) at the vertices of a finer grid of `shape`."""
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
    split from (a + 1, b) to (a, b + 1), as grid_mesh."""
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
    top = block_extremes(block_extremes(excess, u_starts, axis=1)[1], rows_at, axis=0)[1]
    lo_u, hi_u = block_extremes(surface, u_starts, axis=1)
    lo = block_extremes(lo_u, rows_at, axis=0)[0]
    hi = block_extremes(hi_u, rows_at, axis=0)[1]
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


def grid_mesh(nu: int, nv: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (0 … 1)² and triangle indices of an nu × nv grid (nv = nu if not given), each
    quad split from its (u + 1, v) corner to its (u, v + 1) corner (mesh_sink
    assumes this split)."""
    nv = nu if nv is None else nv
    u, v = np.meshgrid(
        np.linspace(0.0, 1.0, nu + 1, dtype=np.float32),
        np.linspace(0.0, 1.0, nv + 1, dtype=np.float32),
        indexing="xy",
    )
    verts = np.stack([u.ravel(), v.ravel()], axis=1)
    i = np.arange(nv)[:, None] * (nu + 1) + np.arange(nu)[None, :]  # lower-left of each quad
    quads = np.stack([i, i + 1, i + nu + 1, i + 1, i + nu + 2, i + nu + 1], axis=-1)
    return verts, quads.astype(np.uint32).ravel()


@lru_cache(maxsize=2 * GROUND_LEVELS)
def chunked_mesh(nu: int, nv: int, chunks: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """grid_mesh(nu, nv) in chunks × chunks chunks (rows along v), each with vertices of its
    own (llvmpipe shades every vertex between a draw's lowest and highest index) and one run
    of the indices: its triangles, then its skirts, along each of its edges inside the grid a
    strip down from the edge to a copy of its vertices that the shader lowers (in_drop 1; 0 on
    the grid's outer border, where a skirt's end would show below the terrain's edge).
    Vertices (u, v, drop); indices; each chunk's (first index, count), (chunks, chunks, 2).
    Kept for the levels asked for last (the arrays are shared: not to be written)."""
    cu, cv = nu // chunks, nv // chunks
    # a chunk's own grid of (cu + 1) × (cv + 1) vertices, and its quads' corners in it
    ii, jj = np.meshgrid(np.arange(cu + 1), np.arange(cv + 1), indexing="xy")
    q = (np.arange(cv)[:, None] * (cu + 1) + np.arange(cu)[None, :]).ravel()
    quads = np.stack([q, q + 1, q + cu + 1, q + 1, q + cu + 2, q + cu + 1], -1).ravel()
    below = (cu + 1) * (cv + 1)  # a vertex's lowered copy
    edges = {  # the chunk's vertices along each of its edges, in order
        "low_v": np.arange(cu + 1),
        "high_v": cv * (cu + 1) + np.arange(cu + 1),
        "low_u": np.arange(cv + 1) * (cu + 1),
        "high_u": np.arange(cv + 1) * (cu + 1) + cu,
    }
    verts, runs, ranges = [], [], np.zeros((chunks, chunks, 2), np.int64)
    first = base = 0
    for b in range(chunks):
        for a in range(chunks):
            u = ((a * cu + ii) / nu).ravel().astype(np.float32)
            v = ((b * cv + jj) / nv).ravel().astype(np.float32)
            top = np.stack([u, v, np.zeros_like(u)], axis=1)
            # a skirt ends on the terrain's outer border (seen from outside, it hung below it)
            inside = (u > 0.0) & (u < 1.0) & (v > 0.0) & (v < 1.0)
            verts += [top, top + np.c_[np.zeros((u.size, 2), np.float32), inside]]
            inner = {"low_v": b > 0, "high_v": b < chunks - 1, "low_u": a > 0,
                     "high_u": a < chunks - 1}  # fmt: skip
            tris = [quads]
            for name, line in edges.items():
                if inner[name]:
                    p0, p1 = line[:-1], line[1:]
                    tris.append(
                        np.stack([p0, p1, p1 + below, p0, p1 + below, p0 + below], -1).ravel()
                    )
            run = (np.concatenate(tris) + base).astype(np.uint32)
            ranges[b, a] = (first, run.size)
            first += run.size
            base += 2 * below
            runs.append(run)
    return np.concatenate(verts), np.concatenate(runs), ranges
