"""One traversal of the quadtree per frame for all LOD levels (thesis 6.1.2-6.1.4, 6.2).

Breadth-first and vectorised: each tree level is one set of numpy operations over the nodes
still in play, never a Python loop over nodes or cells. A (nodes × LOD levels) mask holds which
levels still have to decide a node; the LOD criteria of core/lod_criteria.py clear entries (discard),
draw a node whole as a macro-cell, or leave it to its children, which inherit the mask (the skip
flags of Fig. 6.3). Sphere + cone culling drops nodes outside the view. Leaves are classified
exactly as core/lod.select classifies cells, so without culling both give the same cells.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core import lod_criteria
from core.frustum import Frustum
from core.grid import INSTANCE_DTYPE
from core.lod import ALL_IN, LodConfig, classify, weight_near
from core.lod_criteria import Levels
from core.terrain import Terrain


@dataclass
class DrawList:
    """Per LOD level, the instances to draw (macro-cells have size > 1)."""

    levels: list[np.ndarray]
    visited: int  # nodes tested


def traverse(terrain: Terrain, eye, config: LodConfig, frustum: Frustum | None = None) -> DrawList:
    tree = terrain.tree
    lv = Levels.of(config)
    n_levels = lv.count
    eye = np.asarray(eye, np.float64)
    ox, oz = terrain.origin

    records: list[tuple] = []  # (x0, z0, sx, sz, y_lo, y_hi, level, w, side) arrays
    ix = np.zeros(1, np.int64)
    iz = np.zeros(1, np.int64)
    active = np.ones((1, n_levels), bool)  # per node and LOD level: still to be decided
    visited = 0
    for level in range(tree.depth - 1, -1, -1):
        visited += ix.size
        x0, z0, x1, z1 = tree.extent(level, ix, iz)
        y_lo = tree.y_min[level][ix, iz].astype(np.float32)
        y_hi = tree.y_max[level][ix, iz].astype(np.float32)
        if frustum is not None:
            lo = np.stack([ox + x0, y_lo, oz + z0], axis=1)
            hi = np.stack([ox + x1, y_hi + terrain.grass_height, oz + z1], axis=1)
            visible = frustum.visible((lo + hi) / 2.0, np.linalg.norm(hi - lo, axis=1) / 2.0)
            active &= visible[:, None]
        if level == 0:
            records.append(_leaves(terrain, eye, config, ix, iz, active))
            break
        nodes = _nodes(eye, ox, oz, (x0, z0, x1, z1), 1 << level, y_lo, y_hi)
        active &= lod_criteria.distance(nodes, lv)
        is_flat = lod_criteria.flat(nodes, lv)
        box = (x0, z0, x1 - x0, z1 - z0, y_lo, y_hi)
        node, t = np.nonzero(active & is_flat & lod_criteria.macro_cell(nodes, lv))
        if node.size:
            lod_w = np.full(node.size, ALL_IN, np.float32)
            records.append((*(a[node] for a in box), t, lod_w, np.zeros(node.size, np.float32)))
            active[node, t] = False
        pair = active[:, :-1] & active[:, 1:] & is_flat[:, :-1] & is_flat[:, 1:]
        node, t = np.nonzero(pair & lod_criteria.shared(nodes, lv))
        if node.size:
            records.extend(_pair_records(eye, ox, oz, box, node, t, lv.begin, lv.end))
            active[node, t] = False
            active[node, t + 1] = False
        keep = active.any(axis=1)
        ix, iz, parent = tree.children(level, ix[keep], iz[keep])
        active = active[keep][parent]
    levels_out = _instances(terrain, records, n_levels)
    if config.silhouettes:
        _silhouettes(levels_out, config, eye, terrain.grass_height)
    return DrawList(levels_out, visited)


def _nodes(eye, ox, oz, extent, span, y_lo, y_hi) -> lod_criteria.Nodes:
    """Horizontal distances from the eye to the nearest and farthest cell centre of each node."""
    x0, z0, x1, z1 = extent
    cx0, cx1 = ox + x0 + 0.5, ox + x1 - 0.5
    cz0, cz1 = oz + z0 + 0.5, oz + z1 - 0.5
    dx = np.maximum(np.maximum(cx0 - eye[0], eye[0] - cx1), 0.0)
    dz = np.maximum(np.maximum(cz0 - eye[2], eye[2] - cz1), 0.0)
    dmax = np.hypot(
        np.maximum(np.abs(eye[0] - cx0), np.abs(eye[0] - cx1)),
        np.maximum(np.abs(eye[2] - cz0), np.abs(eye[2] - cz1)),
    )
    return lod_criteria.Nodes(np.hypot(dx, dz)[:, None], dmax[:, None], span, y_lo, y_hi)


def _leaves(terrain, eye, config, ix, iz, active) -> tuple:
    """Records for single cells: classified by their centre's distance exactly as
    core/lod.select does, for every level still active."""
    ox, oz = terrain.origin
    centre_x = (np.float32(ox) + ix.astype(np.float32)) + np.float32(0.5)
    centre_z = (np.float32(oz) + iz.astype(np.float32)) + np.float32(0.5)
    d = np.hypot(centre_x - eye[0], centre_z - eye[2])
    nodes, ts, ws, sides = [], [], [], []
    for t, (inside, lod) in enumerate(classify(d, config)):
        node = np.nonzero(inside & active[:, t])[0]
        nodes.append(node)
        ts.append(np.full(node.size, t))
        ws.append(lod[node, 0])
        sides.append(lod[node, 1])
    node = np.concatenate(nodes)
    one = np.ones(node.size, np.int64)
    return (
        ix[node],
        iz[node],
        one,
        one,
        terrain.cell_min[ix[node], iz[node]],
        terrain.cell_max[ix[node], iz[node]],
        np.concatenate(ts),
        np.concatenate(ws),
        np.concatenate(sides),
    )


def _pair_records(eye, ox, oz, box, node, t, begin, end) -> list[tuple]:
    """Nodes that reach into two neighbouring levels t, t+1 and no third, and fit both levels'
    macro-cell limits: both levels draw the very same node with one w, taken at its centre (the
    near one keeps threshold < w, the far one the rest), so every blade is drawn once. Within
    such a node the boundary between the levels blurs to the node's size, as macro-cells do in
    the thesis (Fig. 6.5); the cells of the node no longer follow their own distances."""
    x0, z0, sx, sz, y_lo, y_hi = (a[node] for a in box)
    cx = (np.float32(ox) + x0.astype(np.float32)) + np.float32(0.5) * sx.astype(np.float32)
    cz = (np.float32(oz) + z0.astype(np.float32)) + np.float32(0.5) * sz.astype(np.float32)
    d = np.hypot(cx - eye[0], cz - eye[2])
    w = weight_near(d, begin[t + 1], end[t]).astype(np.float32)
    near, far = w > 0.0, w < 1.0
    out = []
    for keep, level, side in ((near, t, 0.0), (far, t + 1, 1.0)):
        out.append(
            (
                x0[keep],
                z0[keep],
                sx[keep],
                sz[keep],
                y_lo[keep],
                y_hi[keep],
                level[keep],
                w[keep],
                np.full(int(keep.sum()), side, np.float32),
            )
        )
    return out


def _instances(terrain: Terrain, records: list[tuple], n_levels: int) -> list[np.ndarray]:
    """All records turned into instances at once, then split by LOD level."""
    if not records:
        return [np.zeros(0, INSTANCE_DTYPE) for _ in range(n_levels)]
    x0, z0, sx, sz, y_lo, y_hi, t, w, side = (np.concatenate(a) for a in zip(*records, strict=True))
    cells = terrain.cells(x0, z0, sx, sz, (y_lo, y_hi))
    cells["lod"][:, 0] = w
    cells["lod"][:, 1] = side
    order = np.argsort(t, kind="stable")
    bounds = np.searchsorted(t[order], np.arange(n_levels + 1))
    return [cells[order[bounds[k] : bounds[k + 1]]] for k in range(n_levels)]


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
