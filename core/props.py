"""Props: simple boxes standing on the terrain, for occlusion checks and for t_m (the rest of the
scenery). One row a box; the renderer draws them all in one instanced call."""

from __future__ import annotations

import numpy as np

PROP_DTYPE = np.dtype(
    [("centre", np.float32, 3), ("size", np.float32, 3), ("color", np.float32, 3)]
)


def boxes(rows) -> np.ndarray:
    """Props from (centre x, z), (width, height, depth), (r, g, b)[, lift] rows; a box stands
    on y = 0, or `lift` above it (a crossbar)."""
    rows = list(rows)
    out = np.zeros(len(rows), PROP_DTYPE)
    for i, row in enumerate(rows):
        (x, z), (w, h, d), color = row[:3]
        lift = row[3] if len(row) > 3 else 0.0
        if min(w, h, d) <= 0:
            raise ValueError(f"prop {i}: size {w} × {h} × {d} must be positive")
        out[i] = ((x, lift + h / 2.0, z), (w, h, d), color)
    return out
