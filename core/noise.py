"""Periodic 2D Perlin gradient noise on numpy arrays (Perlin 2002, improved fade curve).

The patch is tiled over the terrain, so the noise that clusters its blades must tile too: the
lattice wraps with the given period.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np


def _fade(t: np.ndarray) -> np.ndarray:
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


def perlin2d(x: np.ndarray, y: np.ndarray, period: int, seed: int) -> np.ndarray:
    """Noise in about [-0.7, 0.7] at points (x, y) of the unit square, tiling with the square.

    `period` lattice cells span the unit square in each direction.
    """
    rng = np.random.default_rng(seed)
    angles = rng.uniform(0.0, 2.0 * np.pi, size=(period, period))
    grad = np.stack([np.cos(angles), np.sin(angles)], axis=-1)

    px = np.asarray(x, dtype=np.float64) * period
    py = np.asarray(y, dtype=np.float64) * period
    x0 = np.floor(px).astype(np.int64)
    y0 = np.floor(py).astype(np.int64)
    fx = px - x0
    fy = py - y0

    def corner(dx: int, dy: int) -> np.ndarray:
        g = grad[(x0 + dx) % period, (y0 + dy) % period]
        return g[..., 0] * (fx - dx) + g[..., 1] * (fy - dy)

    u = _fade(fx)
    v = _fade(fy)
    bottom = corner(0, 0) * (1 - u) + corner(1, 0) * u
    top = corner(0, 1) * (1 - u) + corner(1, 1) * u
    return bottom * (1 - v) + top * v


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
