"""Terrain heights from the design stack's height map (thesis 6.4.4): bilinear sampling exactly
as the GPU's linear filter does it, and per-cell height ranges for the quadtree's bounding
volumes, the volume cuboids' extrusion (min height, unplanarity) and the unplanarity LOD test."""

from __future__ import annotations

import math

import numpy as np


def bilinear(heights: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """heights (rows along v, columns along u) sampled at (u, v) in 0 … 1 like GL_LINEAR with
    clamp-to-edge: texel centres at (i + 0.5) / size."""
    h, w = heights.shape
    x = np.clip(np.asarray(u, np.float64) * w - 0.5, 0.0, w - 1)
    y = np.clip(np.asarray(v, np.float64) * h - 0.5, 0.0, h - 1)
    x0 = np.floor(x).astype(np.int64)
    y0 = np.floor(y).astype(np.int64)
    x1 = np.minimum(x0 + 1, w - 1)
    y1 = np.minimum(y0 + 1, h - 1)
    fx, fy = x - x0, y - y0
    top = heights[y0, x0] * (1 - fx) + heights[y0, x1] * fx
    bottom = heights[y1, x0] * (1 - fx) + heights[y1, x1] * fx
    return top * (1 - fy) + bottom * fy


def _positions(cells: int, texels: int) -> np.ndarray:
    """(cells, k) positions in 0 … 1 per cell: its two borders and every texel-centre line
    between them (padded with the first border)."""
    k = math.ceil(texels / cells) + 3
    out = np.empty((cells, k))
    v0 = np.arange(cells) / cells
    out[:] = v0[:, None]
    out[:, 1] = (np.arange(cells) + 1) / cells
    first = np.ceil(v0 * texels - 0.5).astype(np.int64)  # first texel centre at or after v0
    for extra in range(k - 2):
        j = first + extra
        c = (j + 0.5) / texels
        inside = c <= out[:, 1]
        out[inside, 2 + extra] = c[inside]
    return out


def cell_ranges(
    heights: np.ndarray, scale: float, columns: int, rows: int
) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) world heights of the ground in every cell, (columns, rows) arrays.

    The bilinear surface is bilinear between texel-centre lines, so its extremes inside a cell
    lie where those lines and the cell's borders cross: sampling exactly there is exact (a tiny
    margin covers float rounding)."""
    h, w = heights.shape
    px = _positions(columns, w)  # (columns, kx)
    pz = _positions(rows, h)  # (rows, kz)
    kx, kz = px.shape[1], pz.shape[1]
    lo = np.empty((columns, rows), np.float32)
    hi = np.empty((columns, rows), np.float32)
    margin = 1e-4 * max(scale, 1.0)
    chunk = max(1, 2_000_000 // (columns * kx * kz))
    for z0 in range(0, rows, chunk):
        z1 = min(z0 + chunk, rows)
        uu = np.broadcast_to(px[:, :, None, None], (columns, kx, z1 - z0, kz))
        vv = np.broadcast_to(pz[None, None, z0:z1, :], (columns, kx, z1 - z0, kz))
        s = bilinear(heights, uu, vv) * scale
        lo[:, z0:z1] = s.min(axis=(1, 3)) - margin
        hi[:, z0:z1] = s.max(axis=(1, 3)) + margin
    return lo, hi


def hills(width: int, seed: int = 0, period: int = 3) -> np.ndarray:
    """A smooth, tiling-free hilly height map in 0 … 1 (fractal Perlin noise)."""
    from core.noise import fractal_noise

    c = (np.arange(width) + 0.5) / width
    u, v = np.meshgrid(c, c, indexing="xy")
    n = fractal_noise(u, v, period=period, seed=seed, octaves=3)
    return ((n - n.min()) / max(float(np.ptp(n)), 1e-9)).astype(np.float32)
