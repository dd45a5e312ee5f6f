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
