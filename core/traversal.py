"""One traversal of the quadtree per frame for all LOD levels (thesis 6.1.2-6.1.4, 6.2).

Breadth-first, compiled with numba (`_walk`): per tree level the nodes still in play and a
(nodes × LOD levels) mask of which levels still have to decide each node; the LOD criteria of
core/lod_criteria.py clear entries (discard), draw a node whole as a macro-cell, or leave it to
its children, which inherit the mask (the skip flags of Fig. 6.3). Sphere + cone culling drops
nodes outside the view. Leaves are classified exactly as core/lod.select classifies cells, so
without culling both give the same cells. The same compiled call turns the walk's records into
instances (Terrain.instances' fill: mirror bits, config transforms). Compiled, because as numpy
operations per tree level the overhead of each call would be most of a traversal.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from core import lod_criteria
from core.frustum import Frustum
from core.grid import INSTANCE_DTYPE
from core.lod import ALL_IN, LodConfig
from core.lod_criteria import Levels
from core.occupancy import DensityOccupancy
from core.quadtree import half_value
from core.terrain import LEVEL, SIDE, SX, SZ, X0, Y_HI, Y_LO, Z0, Terrain, W, fill_instances


@dataclass
class DrawList:
    """Per LOD level, the instances to draw (macro-cells have size > 1)."""

    levels: list[np.ndarray]
    visited: int  # nodes tested


def traverse(
    terrain: Terrain,
    eye,
    config: LodConfig,
    frustum: Frustum | None = None,
    occupancy: DensityOccupancy | None = None,
    channel: int = 0,
) -> DrawList:
    """With `occupancy`, nodes and cells where the grass of density channel `channel` cannot
    grow (core/occupancy.py) are left out, subtrees and all."""
    tree = terrain.tree
    lv = Levels.of(config)
    eye = np.asarray(eye, np.float64)
    ox, oz = terrain.origin
    if frustum is None:
        cone = np.zeros(12)
    else:
        cone = np.concatenate(
            [
                frustum.centre,
                [frustum.radius],
                frustum.forward,
                frustum.eye,
                [frustum.sin_angle, frustum.cos_angle],
            ]
        )
    cells, bounds, visited = _select(
        tree.packed_min,
        tree.packed_max,
        tree.offsets,
        tree.shapes,
        tree.columns,
        tree.rows,
        eye,
        float(ox),
        float(oz),
        float(terrain.grass_height),
        lv.table,
        frustum is not None,
        cone,
        occupancy is not None,
        _NO_CELLS if occupancy is None else occupancy.packed,
        1 << channel,
        terrain.noise,
        terrain.mirror_seed is not None,
    )
    cells = cells.view(INSTANCE_DTYPE).reshape(cells.shape[0])
    levels_out = [cells[bounds[k] : bounds[k + 1]] for k in range(lv.count)]
    if config.silhouettes:
        _silhouettes(levels_out, config, eye, terrain.grass_height)
    return DrawList(levels_out, visited)


_NO_CELLS = np.zeros(1, np.uint8)


def warm() -> None:
    """Load the compiled walk (numba's on-disk cache) with a traversal of a 2 × 2 terrain: the
    load is LLVM's work, mostly outside the interpreter's lock, so a thread that runs this while
    a renderer is being set up spares its first frame that wait (render/frame.py)."""
    terrain = Terrain(2, 2, mirror_seed=0)
    occupancy = DensityOccupancy(2, 2, np.ones((2, 2, 1), np.float32))
    frustum = Frustum.from_view((1.0, 1.0, -1.0), (1.0, 0.0, 1.0), 50.0, 1.0, 0.1, 10.0)
    traverse(terrain, (1.0, 1.0, -1.0), LodConfig(), frustum, occupancy, 0)


@numba.njit(cache=True)
def _select(lo16, hi16, offsets, shapes, columns, rows, eye, ox, oz, grass_height, table, cull,
            cone, skip_bare, grows, bit, noise, mirrored):  # fmt: skip
    """The walk's records as instances (15 float32s each, INSTANCE_DTYPE's layout), sorted by
    LOD level; where each level's instances begin (and the last ends); the nodes tested. One
    compiled call per traversal: inside a frame on llvmpipe every Python-level step costs."""
    records, visited = _walk(lo16, hi16, offsets, shapes, columns, rows, eye, ox, oz,
                             grass_height, table, cull, cone, skip_bare, grows, bit)  # fmt: skip
    out = np.empty((records.shape[0], 15), np.float32)
    fill_instances(out, records, ox, oz, columns, rows, noise, mirrored)
    bounds = np.searchsorted(records[:, LEVEL], np.arange(table.shape[0] + 1) - 0.5)
    return out, bounds, visited


@numba.njit(cache=True)
def _walk(lo16, hi16, offsets, shapes, columns, rows, eye, ox, oz, grass_height, table, cull, cone,
          skip_bare, grows, bit):  # fmt: skip
    """Breadth-first from the root: per tree level, the nodes still in play and per node and
    LOD level whether that level still has to decide it (the skip flags of Fig. 6.3). A node is
    culled (sphere + cone), discarded by a level it does not reach, drawn whole as a macro-cell
    or as a node shared by two neighbouring levels, or left to its children, which inherit its
    flags; leaves are classified as core/lod.select classifies cells. Records (x0, z0, sx, sz,
    y_lo, y_hi, level, w, side), in the order levels, macro-cells, shared near, shared far,
    leaves by LOD level (then sorted by LOD level); and the count of nodes tested. With
    `skip_bare`, nodes whose occupancy byte in `grows` (core/occupancy.py, packed like the
    tree) lacks `bit` are dropped like culled ones."""
    n_lv = table.shape[0]
    out = np.empty((64, 9))
    n = 0
    ix = np.zeros(1, np.int64)
    iz = np.zeros(1, np.int64)
    active = np.ones((1, n_lv), np.bool_)
    visited = 0
    gh = np.float32(grass_height)
    for level in range(shapes.shape[0] - 1, -1, -1):
        m = ix.size
        visited += m
        step = 1 << level
        base, nz = offsets[level], shapes[level, 1]
        y_lo = np.empty(m, np.float32)
        y_hi = np.empty(m, np.float32)
        for i in range(m):
            k = base + ix[i] * nz + iz[i]
            y_lo[i] = half_value(lo16[k])
            y_hi[i] = half_value(hi16[k])
            if skip_bare and not grows[k] & bit:
                for t in range(n_lv):
                    active[i, t] = False
            if cull:
                x0, z0 = ix[i] * step, iz[i] * step
                x1, z1 = min(x0 + step, columns), min(z0 + step, rows)
                top = y_hi[i] + gh
                if not _visible(cone, ox + x0, y_lo[i], oz + z0, ox + x1, top, oz + z1):
                    for t in range(n_lv):
                        active[i, t] = False
        if level == 0:
            for t in range(n_lv):
                for i in range(m):
                    if active[i, t]:
                        w, side, inside = _classify(table, t, eye, ox, oz, ix[i], iz[i])
                        if inside:
                            out, n = _push(out, n, *_record(ix[i], iz[i], 1, 1, y_lo[i], y_hi[i],
                                                             t, w, side))  # fmt: skip
            break
        pairs = np.empty((m * n_lv, 2), np.int64)
        n_pairs = 0
        keep = np.zeros(m, np.bool_)
        for i in range(m):
            x0, z0 = ix[i] * step, iz[i] * step
            x1, z1 = min(x0 + step, columns), min(z0 + step, rows)
            dmin, dmax = _node_distances(eye, ox + x0, oz + z0, ox + x1, oz + z1)
            for t in range(n_lv):
                if active[i, t] and not lod_criteria.distance(table, t, dmin, dmax):
                    active[i, t] = False
            for t in range(n_lv):
                if (
                    active[i, t]
                    and lod_criteria.flat(table, t, y_lo[i], y_hi[i])
                    and lod_criteria.macro_cell(table, t, dmin, dmax, step)
                ):
                    sx, sz = x1 - x0, z1 - z0
                    out, n = _push(
                        out, n, *_record(x0, z0, sx, sz, y_lo[i], y_hi[i], t, ALL_IN, 0.0)
                    )
                    active[i, t] = False
            first = n_pairs
            for t in range(n_lv - 1):
                if (
                    active[i, t]
                    and active[i, t + 1]
                    and lod_criteria.flat(table, t, y_lo[i], y_hi[i])
                    and lod_criteria.flat(table, t + 1, y_lo[i], y_hi[i])
                    and lod_criteria.shared(table, t, dmin, dmax, step)
                ):
                    pairs[n_pairs, 0] = i
                    pairs[n_pairs, 1] = t
                    n_pairs += 1
            for p in range(first, n_pairs):
                active[i, pairs[p, 1]] = False
                active[i, pairs[p, 1] + 1] = False
            for t in range(n_lv):
                keep[i] |= active[i, t]
        # shared nodes (see _pair_weight): the near level's records, then the far level's
        for far in range(2):
            for p in range(n_pairs):
                i, t = pairs[p, 0], pairs[p, 1]
                x0, z0 = ix[i] * step, iz[i] * step
                sx, sz = min(x0 + step, columns) - x0, min(z0 + step, rows) - z0
                w = _pair_weight(table, t, eye, ox, oz, x0, z0, sx, sz)
                if (far == 0 and w > 0.0) or (far == 1 and w < 1.0):
                    out, n = _push(
                        out, n, *_record(x0, z0, sx, sz, y_lo[i], y_hi[i], t + far, w, far)
                    )
        ix, iz, active = _children(ix, iz, active, keep, shapes[level - 1, 0], shapes[level - 1, 1])
    return _by_level(out[:n], n_lv), visited


@numba.njit(cache=True)
def _by_level(records, n_levels):
    """The records sorted by LOD level, each level's in the order they were made (stable)."""
    starts = np.zeros(n_levels + 1, np.int64)
    for r in range(records.shape[0]):
        starts[int(records[r, LEVEL]) + 1] += 1
    starts = np.cumsum(starts)
    out = np.empty_like(records)
    fill = starts[:-1].copy()
    for r in range(records.shape[0]):
        t = int(records[r, LEVEL])
        for c in range(9):
            out[fill[t], c] = records[r, c]
        fill[t] += 1
    return out


@numba.njit(cache=True, inline="always")
def _record(x0, z0, sx, sz, y_lo, y_hi, level, w, side):
    """A record's values, all as float64."""
    return (float(x0), float(z0), float(sx), float(sz), float(y_lo), float(y_hi), float(level),
            float(w), float(side))  # fmt: skip


@numba.njit(cache=True)
def _push(out, n, x0, z0, sx, sz, y_lo, y_hi, level, w, side):
    """Append one record to `out` (grown by doubling when full); the array and the new count.
    Every value is passed as a float (see _record), so it compiles once, lazily."""
    if n == out.shape[0]:
        grown = np.empty((2 * n, 9))
        grown[:n] = out
        out = grown
    out[n, X0] = x0
    out[n, Z0] = z0
    out[n, SX] = sx
    out[n, SZ] = sz
    out[n, Y_LO] = y_lo
    out[n, Y_HI] = y_hi
    out[n, LEVEL] = level
    out[n, W] = w
    out[n, SIDE] = side
    return out, n + 1


@numba.njit(cache=True)
def _children(ix, iz, active, keep, nx, nz):
    """The existing children of the kept nodes in the level below (nx × nz nodes), each with
    its parent's flags."""
    count = 0
    for i in range(ix.size):
        if keep[i]:
            count += 4
    cx = np.empty(count, np.int64)
    cz = np.empty(count, np.int64)
    flags = np.empty((count, active.shape[1]), np.bool_)
    c = 0
    for i in range(ix.size):
        if not keep[i]:
            continue
        for q in range(4):
            x, z = 2 * ix[i] + (q & 1), 2 * iz[i] + (q >> 1)
            if x < nx and z < nz:
                cx[c], cz[c] = x, z
                for t in range(active.shape[1]):
                    flags[c, t] = active[i, t]
                c += 1
    return cx[:c], cz[:c], flags[:c]


@numba.njit(cache=True)
def _node_distances(eye, x0, z0, x1, z1):
    """Horizontal distances from the eye to the nearest and farthest cell centre of the node
    covering world [x0, x1) × [z0, z1)."""
    cx0, cx1, cz0, cz1 = x0 + 0.5, x1 - 0.5, z0 + 0.5, z1 - 0.5
    dx = max(max(cx0 - eye[0], eye[0] - cx1), 0.0)
    dz = max(max(cz0 - eye[2], eye[2] - cz1), 0.0)
    far_x = max(abs(eye[0] - cx0), abs(eye[0] - cx1))
    far_z = max(abs(eye[2] - cz0), abs(eye[2] - cz1))
    return np.hypot(dx, dz), np.hypot(far_x, far_z)


@numba.njit(cache=True)
def _weight_near(d, e1, e2):
    """w_1(d) = 1 − linearstep(e1, e2, d) (eq. 5.23), as core/lod.weight_near (a step at e1
    where a level ends as the next begins)."""
    if e2 <= e1:
        return 1.0 if d < e1 else 0.0
    return 1.0 - min(max((d - e1) / (e2 - e1), 0.0), 1.0)


@numba.njit(cache=True)
def _classify(table, t, eye, ox, oz, ix, iz):
    """A single cell in LOD level t, by its centre's distance, as core/lod.classify: (w, side,
    whether level t draws it)."""
    cx = (np.float32(ox) + np.float32(ix)) + np.float32(0.5)
    cz = (np.float32(oz) + np.float32(iz)) + np.float32(0.5)
    d = np.hypot(np.float64(cx) - eye[0], np.float64(cz) - eye[2])
    begin, end = table[t, lod_criteria.BEGIN], table[t, lod_criteria.END]
    w, side = np.float32(ALL_IN), np.float32(0.0)
    if t > 0:  # the far side of the transition from the previous level
        prev_end = table[t - 1, lod_criteria.END]
        if d < prev_end:
            w, side = np.float32(_weight_near(d, begin, prev_end)), np.float32(1.0)
    if t + 1 < table.shape[0]:  # the near side of the transition to the next level
        nxt = table[t + 1, lod_criteria.BEGIN]
        if d >= nxt:
            w, side = np.float32(_weight_near(d, nxt, end)), np.float32(0.0)
    return w, side, d >= begin and d < end


@numba.njit(cache=True)
def _pair_weight(table, t, eye, ox, oz, x0, z0, sx, sz):
    """Nodes that reach into two neighbouring levels t, t+1 and no third, and fit both levels'
    macro-cell limits: both levels draw the very same node with one w, taken at its centre (the
    near one keeps threshold < w, the far one the rest), so every blade is drawn once. Within
    such a node the boundary between the levels blurs to the node's size, as macro-cells do in
    the thesis (Fig. 6.5); the cells of the node no longer follow their own distances."""
    cx = (np.float32(ox) + np.float32(x0)) + np.float32(0.5) * np.float32(sx)
    cz = (np.float32(oz) + np.float32(z0)) + np.float32(0.5) * np.float32(sz)
    d = np.hypot(np.float64(cx) - eye[0], np.float64(cz) - eye[2])
    e1, e2 = table[t + 1, lod_criteria.BEGIN], table[t, lod_criteria.END]
    return np.float32(_weight_near(d, e1, e2))


@numba.njit(cache=True)
def _visible(cone, x0, y0, z0, x1, y1, z1) -> bool:
    """core/frustum.Frustum.visible for the bounding sphere of one box; `cone` packs the
    frustum's sphere centre (3), radius, view direction (3), eye (3), sin and cos of the cone's
    half angle."""
    sx, sy, sz = (x0 + x1) / 2.0, (y0 + y1) / 2.0, (z0 + z1) / 2.0
    r = np.sqrt((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) / 2.0
    if (sx - cone[0]) ** 2 + (sy - cone[1]) ** 2 + (sz - cone[2]) ** 2 > (r + cone[3]) ** 2:
        return False
    fx, fy, fz, sin_a, cos_a = cone[4], cone[5], cone[6], cone[10], cone[11]
    ux, uy, uz = cone[7] - r / sin_a * fx, cone[8] - r / sin_a * fy, cone[9] - r / sin_a * fz
    dx, dy, dz = sx - ux, sy - uy, sz - uz
    e = dx * fx + dy * fy + dz * fz
    if not (e > 0 and e * e >= (dx * dx + dy * dy + dz * dz) * cos_a**2):
        return False
    dx, dy, dz = sx - cone[7], sy - cone[8], sz - cone[9]
    d_len2 = dx * dx + dy * dy + dz * dz
    e = -(dx * fx + dy * fy + dz * fz)
    behind_apex = e > 0 and e * e >= d_len2 * sin_a**2
    return not behind_apex or d_len2 <= r * r


def _silhouettes(out: list[np.ndarray], config: LodConfig, eye, grass_height: float) -> None:
    """Hilltop silhouettes (thesis 6.4.6): image-based (macro-)cells whose grass reaches above
    the eye, seen from the side and so possibly on the skyline, are added to the last volume
    level as whole instances (every blade), drawn over their flat image-based slice."""
    kinds = [lv.representation for lv in config.levels]
    if "image" not in kinds or "volume" not in kinds:
        return
    image = kinds.index("image")
    volume = len(kinds) - 1 - kinds[::-1].index("volume")
    cells = out[image]
    top = cells["ground"][:, 0] + cells["ground"][:, 1] + grass_height
    extra = cells[top > eye[1]].copy()
    extra["lod"] = (ALL_IN, 0.0)
    if extra.size:
        out[volume] = np.concatenate([out[volume], extra])
