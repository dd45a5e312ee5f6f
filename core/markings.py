"""Football field markings and mowing stripes as a colour-modulation map (thesis 6.4.2: "on a
football field we provide the field marks in that fashion"), in metres after the laws of the
game, drawn with numpy distance fields."""

from __future__ import annotations

import numpy as np

LENGTH, WIDTH = 105.0, 68.0  # pitch, metres
LINE = 0.12  # line width, metres


def football_colour_map(width: int, height: int, margin: float = 4.0) -> np.ndarray:
    """(height, width, 4) RGBA: white lines with alpha 0.9, light mowing stripes elsewhere.
    The map spans the pitch plus `margin` metres on every side; u runs across the pitch (x),
    v along it (z)."""
    span_x, span_z = WIDTH + 2 * margin, LENGTH + 2 * margin
    x = (np.arange(width) + 0.5) / width * span_x - span_x / 2  # metres from the centre
    z = (np.arange(height) + 0.5) / height * span_z - span_z / 2
    X, Z = np.meshgrid(x, z)  # rows along z
    d = np.full(X.shape, np.inf)

    def rect(x0, z0, x1, z1):
        """Distance to the outline of an axis-aligned rectangle."""
        inside = (X >= x0) & (X <= x1) & (Z >= z0) & (Z <= z1)
        dx = np.minimum(np.abs(X - x0), np.abs(X - x1))
        dz = np.minimum(np.abs(Z - z0), np.abs(Z - z1))
        out_x = np.maximum(np.maximum(x0 - X, X - x1), 0)
        out_z = np.maximum(np.maximum(z0 - Z, Z - z1), 0)
        return np.where(inside, np.minimum(dx, dz), np.hypot(out_x, out_z))

    hw, hl = WIDTH / 2, LENGTH / 2
    d = np.minimum(d, rect(-hw, -hl, hw, hl))  # touch and goal lines
    d = np.minimum(d, np.where(np.abs(X) <= hw, np.abs(Z), np.inf))  # halfway line
    d = np.minimum(d, np.abs(np.hypot(X, Z) - 9.15))  # centre circle
    d = np.minimum(d, np.hypot(X, Z) - 0.15)  # centre spot
    for sign in (-1, 1):
        goal = sign * hl
        inner = goal - sign * 16.5
        d = np.minimum(d, rect(-20.16, min(goal, inner), 20.16, max(goal, inner)))  # penalty area
        inner = goal - sign * 5.5
        d = np.minimum(d, rect(-9.16, min(goal, inner), 9.16, max(goal, inner)))  # goal area
        d = np.minimum(d, np.hypot(X, Z - (goal - sign * 11.0)) - 0.15)  # penalty spot
    line = np.clip(1.0 - (d - LINE / 2) / (span_x / width), 0.0, 1.0)  # one texel of soft edge

    stripe = (np.floor((Z + hl) / (LENGTH / 18)) % 2).astype(np.float32)  # 18 mowing stripes
    rgba = np.empty((height, width, 4), np.float32)
    rgba[..., :3] = np.where(stripe[..., None] > 0, (0.30, 0.52, 0.16), (0.20, 0.40, 0.10))
    rgba[..., 3] = 0.18
    white = line[..., None] * 0.9
    rgba[..., :3] = (
        rgba[..., :3] * (1 - line[..., None]) + np.array([0.95, 0.95, 0.92]) * line[..., None]
    )
    rgba[..., 3] = np.maximum(rgba[..., 3], white[..., 0])
    return rgba


def touchlines(columns: int, rows: int, margin: float = 4.0, count: int = 4000) -> list[np.ndarray]:
    """The two touchlines of `football_colour_map` on a terrain of columns × rows cells centred
    on the world origin (core/terrain.py): per line, (count, 3) world points along it at the
    ground, from one goal line to the other."""
    sx = columns / (WIDTH + 2 * margin)  # world units a metre, across and along the pitch
    sz = rows / (LENGTH + 2 * margin)
    z = np.linspace(-LENGTH / 2, LENGTH / 2, count) * sz
    return [
        np.stack([np.full(count, side * WIDTH / 2 * sx), np.zeros(count), z], axis=-1)
        for side in (-1, 1)
    ]
