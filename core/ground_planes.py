"""The planes a volume cuboid on a slope keeps between (core/terrain.py planes_of): per block of
cells, a plane fitted to the ground at its cell corners and the lowest and highest ground over it.

On a slope a cuboid extruded over the block's whole height range holds air above the grass that a
ray crosses for nothing; between these two planes it does not. The first frame of a 4096² terrain
fits every block of each size its quadtree draws (16 M corners a size), so the fit is one compiled
pass over the corners, blocks in parallel, with no temporaries.
"""

from __future__ import annotations

import numba
import numpy as np

from core.quadtree import half_value


def ground_planes(
    corners: np.ndarray, below: np.ndarray, above: np.ndarray, ix, iz, sx, sz, base
) -> np.ndarray:
    """(n, 4) float32, per block of sx × sz cells from cell (ix, iz) (integer arrays) whose
    lowest ground is `base`: a plane's slope along x and z per cell, fitted to the ground at
    the block's cell corners (least squares), and the lowest and highest ground over that
    plane, both relative to `base`: over the block, plane(x, z) + [2] ≤ the ground ≤
    plane(x, z) + [3], plane(x, z) = [0] x + [1] z (x, z in cells from the block's corner).
    From core/heights.py corner_deviations' corners and per-cell deviations (float16): in a
    cell the ground lies between the blend of its corners plus `below` and plus `above`, and
    the blend minus the plane is bilinear, its extremes at the corners."""
    ix, iz = (np.asarray(a, np.int64).reshape(-1) for a in (ix, iz))
    sx, sz = (np.broadcast_to(np.asarray(a, np.int64), ix.shape).copy() for a in (sx, sz))
    base = np.broadcast_to(np.asarray(base, np.float64), ix.shape).copy()
    out = np.zeros((ix.size, 4), np.float32)
    if ix.size:
        _fit(
            np.asarray(corners, np.float32),
            below.view(np.uint16),
            above.view(np.uint16),
            ix, iz, sx, sz, base, out,
        )  # fmt: skip
    return out


@numba.njit(cache=True, parallel=True)
def _fit(corners, below, above, ix, iz, sx, sz, base, out):
    """ground_planes, block by block. The fit in double precision: over a full grid of
    corners the least-squares slopes separate by axis, gx = Σ c(x, z) (x − w/2) /
    ((h + 1) Σ (x − w/2)²), and gz alike."""
    columns, rows = below.shape
    for k in numba.prange(ix.shape[0]):
        w, h, x0, z0 = sx[k], sz[k], ix[k], iz[k]
        sxx = 0.0
        for x in range(w + 1):
            sxx += (x - 0.5 * w) ** 2
        szz = 0.0
        for z in range(h + 1):
            szz += (z - 0.5 * h) ** 2
        gx = 0.0
        gz = 0.0
        for x in range(w + 1):
            cx = min(x0 + x, columns)
            for z in range(h + 1):
                c = np.float64(corners[cx, min(z0 + z, rows)])
                gx += c * (x - 0.5 * w)
                gz += c * (z - 0.5 * h)
        gx /= (h + 1) * max(sxx, 1e-12)
        gz /= (w + 1) * max(szz, 1e-12)
        lo = np.inf
        hi = -np.inf
        for x in range(w):
            cx0, cx1 = min(x0 + x, columns), min(x0 + x + 1, columns)
            for z in range(h):
                cz0, cz1 = min(z0 + z, rows), min(z0 + z + 1, rows)
                r00 = corners[cx0, cz0] - gx * x - gz * z
                r10 = corners[cx1, cz0] - gx * (x + 1) - gz * z
                r01 = corners[cx0, cz1] - gx * x - gz * (z + 1)
                r11 = corners[cx1, cz1] - gx * (x + 1) - gz * (z + 1)
                cell_x, cell_z = min(x0 + x, columns - 1), min(z0 + z, rows - 1)
                low = min(min(r00, r10), min(r01, r11)) + half_value(below[cell_x, cell_z])
                high = max(max(r00, r10), max(r01, r11)) + half_value(above[cell_x, cell_z])
                lo = min(lo, low)
                hi = max(hi, high)
        out[k, 0] = gx
        out[k, 1] = gz
        out[k, 2] = lo - base[k]
        out[k, 3] = hi - base[k]
