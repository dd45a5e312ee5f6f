"""Aperiodic tiling (thesis 6.3, after Boulanger 2008): one patch, each instance mirrored along x
and/or z, decided per cell from a small high-frequency noise map sampled at the cell's origin.

s = 2 · step(0.5, noise(x, y)) − 1 (eq. 6.4), with (x, y) = sampleRate · cell origin (eq. 6.5).
The renderers apply s the same way: geometry mirrors the vertices about the cell centre
(eq. 6.7), volume and image-based mirror their slice lookups (eq. 6.6).
"""

from __future__ import annotations

from functools import lru_cache

import numba
import numpy as np

NOISE_RESOLUTION = 64  # texels per side of the noise map; it wraps


@lru_cache(maxsize=4)
def noise_map(seed: int, resolution: int = NOISE_RESOLUTION) -> np.ndarray:
    """(resolution, resolution, 2) white noise on [0, 1): red for x, green for z."""
    out = np.random.default_rng(seed).random((resolution, resolution, 2)).astype(np.float32)
    out.flags.writeable = False  # cached and shared
    return out


def mirror_bits(origins: np.ndarray, seed: int = 0, sample_rate: float = 1.0) -> np.ndarray:
    """(n, 2) float32 symmetry vectors (s_x, s_z) in {−1, 1} for cell origins (n, 2) (eq. 6.4)."""
    origins = np.asarray(origins, dtype=np.float64).reshape(-1, 2)
    out = np.empty(origins.shape, np.float32)
    _mirror_all(out, origins, noise_map(seed), float(sample_rate))
    return out


@numba.njit(cache=True)
def _mirror_all(out, origins, noise, sample_rate):
    for k in range(origins.shape[0]):
        out[k, 0] = mirror_sign(noise, origins[k, 0], origins[k, 1], sample_rate, 0)
        out[k, 1] = mirror_sign(noise, origins[k, 0], origins[k, 1], sample_rate, 1)


@numba.njit(cache=True)
def mirror_sign(noise, x, z, sample_rate, axis):
    """s (eq. 6.4) along `axis` (0: x, 1: z) for the cell whose origin is (x, z): the noise map
    (wrapping) sampled at sampleRate · origin (eq. 6.5). Also called per cell inside the
    compiled traversal (core/terrain.py)."""
    res = noise.shape[0]
    i = np.int64(np.floor(x * sample_rate)) % res
    j = np.int64(np.floor(z * sample_rate)) % res
    return np.float32(1.0) if noise[i, j, axis] >= 0.5 else np.float32(-1.0)
