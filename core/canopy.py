"""What a view at a low elevation meets of a grass patch (issue: the LOD image matches
all-geometry). The image-based grass is one slice seen from above; far away it is seen nearly
level, where the blades hide one another's lower parts, and how deep a view reaches depends on
its elevation and on how densely the blades stand at each height.

From the vertical slices (rows run upward, row 0 at the ground), per row y of the patch:
- the share of a level ray stopped crossing one patch, α(y) = 1 − Π_k (1 − ā_k(y)) over the
  slices k of a family (ā: a slice's mean alpha along the row), so the extinction per patch
  length is σ(y) = −ln(1 − α(y));
- the blades' colour there, c(y), alpha-weighted over the slices.
A ray that enters the grass from above at elevation θ descends Δy while it travels Δy / tan θ,
so the share it gives row y is w(y) = T(y) · (1 − exp(−σ(y) Δy / tan θ)), T the transmittance
of the rows above. The table holds, per elevation, Σ w c / Σ w: the colour met."""

from __future__ import annotations

import numpy as np

ELEVATIONS = 8  # table entries: θ_j = 90° · ((j + 0.5) / 8)², dense near the horizon


def elevations(count: int = ELEVATIONS) -> np.ndarray:
    """The table's elevations in radians (the shaders invert this: shaders/image.glsl)."""
    return 0.5 * np.pi * ((np.arange(count) + 0.5) / count) ** 2


def level_view(families: list[np.ndarray], height: float, count: int = ELEVATIONS) -> np.ndarray:
    """(count, 3) colours met at each table elevation, averaged over the families of vertical
    slices ((n, rows, w, 4) colour + alpha arrays, 0 … 1, rows running upward)."""
    colours = []
    for color in families:
        a = color[..., 3]
        alpha = np.clip(a.mean(axis=2), 0.0, 1.0)  # (n, rows)
        through = 1.0 - np.prod(1.0 - alpha, axis=0)  # (rows,)
        sigma = -np.log(np.maximum(1.0 - through, 1e-6))  # per patch length
        n, rows, w = a.shape
        # per row, the colour weighted by alpha (one batched product over the columns)
        sums = np.matmul(a.reshape(n * rows, 1, w), color[..., :3].reshape(n * rows, w, 3))
        c = sums.reshape(n, rows, 3).sum(axis=0) / np.maximum(a.sum(axis=(0, 2)), 1e-9)[:, None]
        dy = height / rows
        met = []
        for theta in elevations(count):
            tau = sigma[::-1] * dy / max(np.tan(theta), 1e-3)  # the rows from the top down
            w = np.exp(-np.concatenate([[0.0], np.cumsum(tau)[:-1]])) * (1.0 - np.exp(-tau))
            met.append((w[:, None] * c[::-1]).sum(axis=0) / max(float(w.sum()), 1e-9))
        colours.append(met)
    return np.mean(colours, axis=0).astype(np.float32)
