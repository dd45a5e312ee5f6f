"""Camera paths: key positions the camera moves through at constant speed (for profiling)."""

from __future__ import annotations

import numpy as np


def sample_path(
    keys: list[tuple[tuple, tuple]], frames: int
) -> list[tuple[np.ndarray, np.ndarray]]:
    """`frames` (eye, target) pairs spread evenly by distance along the polyline of the key
    eyes; targets are interpolated alongside."""
    if len(keys) < 2:
        raise ValueError("a camera path needs at least two key positions")
    if frames < 1:
        raise ValueError("a camera path needs at least one frame")
    eyes = np.array([k[0] for k in keys], np.float64)
    targets = np.array([k[1] for k in keys], np.float64)
    seg = np.linalg.norm(np.diff(eyes, axis=0), axis=1)
    along = np.concatenate([[0.0], np.cumsum(seg)])
    if along[-1] <= 0:
        raise ValueError("a camera path's key positions must not all coincide")
    at = np.linspace(0.0, along[-1], frames) if frames > 1 else np.array([0.0])
    out = []
    for s in at:
        i = min(int(np.searchsorted(along, s, side="right")) - 1, len(seg) - 1)
        f = (s - along[i]) / seg[i] if seg[i] > 0 else 0.0
        out.append(
            (eyes[i] + f * (eyes[i + 1] - eyes[i]), targets[i] + f * (targets[i + 1] - targets[i]))
        )
    return out
