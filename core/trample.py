"""Trampled grass (the thesis's future work: treading through an animation map): a painted map
that lays the blades over along a direction — a path where people walk, a player's track.

The trample map (core/design_maps.py, layer "trample") holds a tip displacement per texel, as
the wind's lean is one: (x, z) as a fraction of a blade's length, stored 0.5 + 0.5 · lean /
MAX_LEAN per component (0.5, 0.5: upright), so that painting and bilinear filtering mix leans
linearly and the map stays in 0 … 1 like the others (and exports as an engine's flow map).
Every representation bends its grass by the wind's lean and the trampled one added, no further
than MAX_LEAN (core/wind.py grass_lean; shaders/_wind.glsl does the same on the GPU), through
the wind's bend and shear: the blades' curves bend about their roots, the slices and the top
view are read where the bent blades came from.
"""

from __future__ import annotations

import math

import numpy as np

from core.heights import bilinear
from core.wind import MAX_LEAN

UPRIGHT = 0.5  # a texel's value where the grass stands


def encode(lean_xz: np.ndarray) -> np.ndarray:
    """Texel values (..., 2) of tip displacements (..., 2), their length limited to MAX_LEAN."""
    lean_xz = np.asarray(lean_xz, np.float64)
    size = np.linalg.norm(lean_xz, axis=-1, keepdims=True)
    lean_xz = lean_xz * np.minimum(1.0, MAX_LEAN / np.maximum(size, 1e-12))
    return UPRIGHT + 0.5 * lean_xz / MAX_LEAN


def decode(texels: np.ndarray) -> np.ndarray:
    """Tip displacements (..., 2) of trample-map texels (..., ≥ 2)."""
    return (np.asarray(texels, np.float64)[..., :2] - UPRIGHT) * (2.0 * MAX_LEAN)


def brush_value(amount: float, direction: float) -> tuple[float, float]:
    """The texel value a brush paints: the blades laid over by `amount` (a fraction of their
    length, 0 … MAX_LEAN) towards `direction` (degrees, 0 = +x, 90 = +z)."""
    a = math.radians(direction)
    x, z = encode(np.array([math.cos(a), math.sin(a)]) * amount)
    return (float(x), float(z))


def trampled(texels: np.ndarray) -> bool:
    """Whether any texel lays the grass over (the renderers bend it only then)."""
    return bool(np.any(np.asarray(texels)[..., :2] != UPRIGHT))


def largest_lean(texels: np.ndarray) -> float:
    """The longest lean the texels hold (0: the grass stands everywhere)."""
    if not trampled(texels):
        return 0.0
    return float(np.linalg.norm(decode(texels), axis=-1).max())


def lean_at(texels: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The trampled lean (..., 2) at design-map uv, read as the GPU's linear filter reads the
    map (clamp to edge)."""
    return decode(np.stack([bilinear(texels[..., c], u, v) for c in range(2)], axis=-1))
