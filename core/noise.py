"""Periodic 2D Perlin gradient noise on numpy arrays (Perlin 2002, improved fade curve).

The patch is tiled over the terrain, so the noise that clusters its blades must tile too: the
lattice wraps with the given period.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numba
import numpy as np


def perlin2d(x: np.ndarray, y: np.ndarray, period: int, seed: int) -> np.ndarray:
    """Noise in about [-0.7, 0.7] at points (x, y) of the unit square, tiling with the square.

    `period` lattice cells span the unit square in each direction.
    """
    rng = np.random.default_rng(seed)
    angles = rng.uniform(0.0, 2.0 * np.pi, size=(period, period))
    grad = np.stack([np.cos(angles), np.sin(angles)], axis=-1)
    px, py = np.broadcast_arrays(
        np.asarray(x, np.float64) * period, np.asarray(y, np.float64) * period
    )
    out = np.empty(px.shape)
    _perlin_into(np.ravel(px), np.ravel(py), grad, period, out.reshape(-1))
    return out


@numba.njit(cache=True)
def _perlin_into(px, py, grad, period, out):
    """Per point: the gradients of its lattice cell's four corners, faded together (compiled:
    the array version gathered the gradients four times over every point, 36 ms a patch)."""
    for i in range(px.size):
        x0, y0 = math.floor(px[i]), math.floor(py[i])
        fx, fy = px[i] - x0, py[i] - y0
        c = np.empty(4)
        for k in range(4):
            dx, dy = k & 1, k >> 1
            g = grad[(x0 + dx) % period, (y0 + dy) % period]
            c[k] = g[0] * (fx - dx) + g[1] * (fy - dy)
        u = fx * fx * fx * (fx * (fx * 6.0 - 15.0) + 10.0)
        v = fy * fy * fy * (fy * (fy * 6.0 - 15.0) + 10.0)
        bottom = c[0] * (1 - u) + c[1] * u
        top = c[2] * (1 - u) + c[3] * u
        out[i] = bottom * (1 - v) + top * v


def fractal_noise(
    x: np.ndarray, y: np.ndarray, period: int, seed: int, octaves: int = 2
) -> np.ndarray:
    """Low-frequency noise: a few octaves of periodic Perlin noise, amplitude halving."""
    total = np.zeros(np.broadcast(x, y).shape)
    amplitude = 1.0
    for octave in range(octaves):
        total += amplitude * perlin2d(x, y, period * 2**octave, seed + 7919 * octave)
        amplitude *= 0.5
    return total


@lru_cache(maxsize=8)
def equalized_noise_map(resolution: int, period: int, seed: int) -> np.ndarray:
    """A (resolution, resolution) noise map, histogram-equalised to a uniform spread on (0, 1].

    Thesis 4.1.3, Fig. 4.4: raw noise heaps around its mean; equalising by rank spreads its
    values evenly over the interval. Indexed [ix, iy].
    """
    c = (np.arange(resolution) + 0.5) / resolution
    gx, gy = np.meshgrid(c, c, indexing="ij")
    raw = fractal_noise(gx, gy, period, seed)
    ranks = np.argsort(np.argsort(raw, axis=None), axis=None)
    out = ((ranks + 1) / ranks.size).reshape(raw.shape)
    out.flags.writeable = False  # cached and shared
    return out
