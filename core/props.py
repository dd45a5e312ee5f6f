"""Props: boxes and rocks standing on the terrain, for occlusion checks and for t_m (the rest of
the scenery). One row a prop; the renderer draws each shape in one instanced call."""

from __future__ import annotations

import numpy as np

PROP_DTYPE = np.dtype(
    [
        ("centre", np.float32, 3),
        ("size", np.float32, 3),
        ("color", np.float32, 3),
        ("shape", np.float32),  # index into SHAPES
    ]
)
SHAPES = ("box", "rock")


def boxes(rows) -> np.ndarray:
    """Props from (centre x, z), (width, height, depth), (r, g, b)[, lift[, shape]] rows; a prop
    stands on y = 0, or `lift` above it (a crossbar), in the box (w, h, d) around its centre."""
    rows = list(rows)
    out = np.zeros(len(rows), PROP_DTYPE)
    for i, row in enumerate(rows):
        (x, z), (w, h, d), color = row[:3]
        lift = row[3] if len(row) > 3 else 0.0
        shape = row[4] if len(row) > 4 else "box"
        if min(w, h, d) <= 0:
            raise ValueError(f"prop {i}: size {w} × {h} × {d} must be positive")
        if shape not in SHAPES:
            raise ValueError(f"prop {i}: shape {shape!r} is not one of {', '.join(SHAPES)}")
        out[i] = ((x, lift + h / 2.0, z), (w, h, d), color, SHAPES.index(shape))
    return out
