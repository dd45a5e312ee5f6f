"""One traversal of the quadtree per frame for all LOD levels (thesis 6.1.2-6.1.4, 6.2).

Breadth-first and vectorised: each tree level is one set of numpy operations over the nodes
still in play, never a Python loop over nodes or cells. Per node and LOD level the distance
test decides draw / discard / split; a skip flag per LOD level is cleared when a level discards
a node and children inherit the flags (Fig. 6.3); the macro-cell test draws a whole node as one
instance when it is small enough and lies wholly inside the level's range (see _macro for transition zones);
sphere + cone culling drops nodes outside the view. Leaves are classified exactly as
core/lod.select classifies cells, so without culling both give the same cells per level.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.frustum import Frustum
from core.grid import INSTANCE_DTYPE
from core.lod import ALL_IN, LodConfig, classify, weight_near
from core.terrain import Terrain

MARGIN = 1e-4  # node-level distance decisions are conservative by this much; leaves decide


@dataclass
class DrawList:
    """Per LOD level, the instances to draw (macro-cells have size > 1)."""

    levels: list[np.ndarray]
    visited: int  # nodes tested

    def count(self, level: int) -> int:
        return int(self.levels[level].size)


def traverse(terrain: Terrain, eye, config: LodConfig, frustum: Frustum | None = None) -> DrawList:
    tree = terrain.tree
    levels = config.levels
    n_levels = len(levels)
    eye = np.asarray(eye, np.float64)
    begin = np.array([lv.begin for lv in levels])
    end = np.array([np.inf if lv.end is None else lv.end for lv in levels])
    macro = np.array([lv.macro for lv in levels])
    max_unplanarity = [
        np.inf if lv.max_unplanarity is None else lv.max_unplanarity for lv in levels
    ]
    ox, oz = terrain.origin

    out: list[list[np.ndarray]] = [[] for _ in range(n_levels)]
    ix = np.zeros(1, np.int64)
    iz = np.zeros(1, np.int64)
    flags = np.full(1, (1 << n_levels) - 1, np.int64)
    visited = 0
    for level in range(tree.depth - 1, -1, -1):
        visited += ix.size
        x0, z0, x1, z1 = tree.extent(level, ix, iz)
        if frustum is not None:
            lo = np.stack([ox + x0, tree.y_min[level][ix, iz], oz + z0], axis=1)
            hi = np.stack(
                [ox + x1, tree.y_max[level][ix, iz] + terrain.grass_height, oz + z1], axis=1
            )
            centre = (lo + hi) / 2.0
            radius = np.linalg.norm(hi - lo, axis=1) / 2.0
            flags[~frustum.visible(centre, radius)] = 0
        if level == 0:
            cells = terrain.cells(ix, iz)
            centre = cells["origin"] + 0.5 * cells["size"]
            d = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
            for t, (inside, lod) in enumerate(classify(d, config)):
                draw = inside & ((flags >> t) & 1 == 1)
                part = cells[draw]
                part["lod"] = lod[draw]
                out[t].append(part)
            break
        # horizontal distances from the eye to the nearest and farthest cell centre in the node
        cx0, cx1 = ox + x0 + 0.5, ox + x1 - 0.5
        cz0, cz1 = oz + z0 + 0.5, oz + z1 - 0.5
        dx = np.maximum(np.maximum(cx0 - eye[0], eye[0] - cx1), 0.0)
        dz = np.maximum(np.maximum(cz0 - eye[2], eye[2] - cz1), 0.0)
        dmin = np.hypot(dx, dz)
        dmax = np.hypot(
            np.maximum(np.abs(eye[0] - cx0), np.abs(eye[0] - cx1)),
            np.maximum(np.abs(eye[2] - cz0), np.abs(eye[2] - cz1)),
        )
        span = 1 << level  # node edge in cells
        y_lo = tree.y_min[level][ix, iz].astype(np.float32)
        y_hi = tree.y_max[level][ix, iz].astype(np.float32)
        # the unplanarity LOD test (6.4.4): macro-cells only on nearly flat ground
        flat = [(y_hi - y_lo) <= limit for limit in max_unplanarity]
        for t in range(n_levels):
            bit = 1 << t
            active = (flags & bit) != 0
            gone = active & ((dmax < begin[t] - MARGIN) | (dmin >= end[t] + MARGIN))
            flags[gone] &= ~bit
            whole = _macro(t, span, active & ~gone, dmin, dmax, begin, end, macro)
            whole &= flat[t]
            if whole.any():
                cells = terrain.cells(
                    x0[whole],
                    z0[whole],
                    x1[whole] - x0[whole],
                    z1[whole] - z0[whole],
                    (y_lo[whole], y_hi[whole]),
                )
                centre = cells["origin"] + 0.5 * cells["size"]
                d = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
                cells["lod"] = (ALL_IN, 0.0)
                out[t].append(cells)
                flags[whole] &= ~bit
        if span > 1:
            box = (x0, z0, x1, z1, y_lo, y_hi)
            _pairs(terrain, eye, span, flags, box, flat, dmin, dmax, begin, end, macro, out)
        keep = flags != 0
        ix, iz, parent = tree.children(level, ix[keep], iz[keep])
        flags = flags[keep][parent]
    levels_out = [np.concatenate(parts) if parts else np.zeros(0, INSTANCE_DTYPE) for parts in out]
    if config.silhouettes:
        _silhouettes(levels_out, config, eye, terrain.grass_height)
    return DrawList(levels_out, visited)


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


def _macro(t, span, active, dmin, dmax, begin, end, macro) -> np.ndarray:
    """Nodes that lie wholly in level t's own zone (no other level draws there) and are no
    larger than its macro-cell limit (thesis 6.2): drawn whole, every blade."""
    n = len(begin)
    prev_end = end[t - 1] if t > 0 else -np.inf
    next_begin = begin[t + 1] if t + 1 < n else np.inf
    core = (
        active
        & (dmin >= max(begin[t], prev_end) + MARGIN)
        & (dmax < min(end[t], next_begin) - MARGIN)
    )
    return core & (span <= macro[t])


def _pairs(terrain, eye, span, flags, box, flat, dmin, dmax, begin, end, macro, out) -> None:
    """Nodes that reach into two neighbouring levels t, t+1 and no third, and fit both levels'
    macro-cell limits: both levels draw the very same node with one w, taken at its centre (the
    near one keeps threshold < w, the far one the rest), so every blade is drawn once. Within
    such a node the boundary between the levels blurs to the node's size, as macro-cells do in
    the thesis (Fig. 6.5); the cells of the node no longer follow their own distances."""
    x0, z0, x1, z1, y_lo, y_hi = box
    n = len(begin)
    for t in range(n - 1):
        if span > min(macro[t], macro[t + 1]):
            continue
        a, b = 1 << t, 1 << (t + 1)
        lo = end[t - 1] + MARGIN if t > 0 else -np.inf  # no cell reaches back into level t-1
        hi = begin[t + 2] - MARGIN if t + 2 < n else np.inf  # nor on into level t+2
        pair = ((flags & a) != 0) & ((flags & b) != 0) & (dmin >= lo) & (dmax < hi)
        pair &= flat[t] & flat[t + 1]
        if not pair.any():
            continue
        cells = terrain.cells(
            x0[pair], z0[pair], x1[pair] - x0[pair], z1[pair] - z0[pair], (y_lo[pair], y_hi[pair])
        )
        centre = cells["origin"] + 0.5 * cells["size"]
        d = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
        w = weight_near(d, begin[t + 1], end[t]).astype(np.float32)
        near, far = cells.copy(), cells
        near["lod"][:, 0], near["lod"][:, 1] = w, 0.0
        far["lod"][:, 0], far["lod"][:, 1] = w, 1.0
        out[t].append(near[w > 0.0])
        out[t + 1].append(far[w < 1.0])
        flags[pair] &= ~(a | b)
