"""Image differences for checking that a change to the renderer kept its picture (and, later,
for comparing the LOD frame with all-geometry): NVIDIA's FLIP (flip-evaluator) at full and at
a reduced resolution, where blade-level detail that differs by a hair no longer counts.

Images are (h, w, 3) uint8 arrays or floats in 0 … 1, top row first."""

from __future__ import annotations

import numpy as np

QUARTER = 4  # "quarter resolution": 4 × 4 pixels averaged into one


def to_float(image: np.ndarray) -> np.ndarray:
    a = np.asarray(image)
    if a.ndim != 3 or a.shape[2] < 3:
        raise ValueError(f"expected an (h, w, 3) image, got shape {a.shape}")
    a = a[..., :3]
    return a.astype(np.float32) / 255.0 if a.dtype == np.uint8 else a.astype(np.float32)


def downsample(image: np.ndarray, factor: int) -> np.ndarray:
    """Mean of factor × factor blocks (the image is cropped to a multiple of factor)."""
    a = to_float(image)
    h, w = (a.shape[0] // factor) * factor, (a.shape[1] // factor) * factor
    if h == 0 or w == 0:
        raise ValueError(f"image of {a.shape[1]} × {a.shape[0]} is smaller than {factor} pixels")
    return a[:h, :w].reshape(h // factor, factor, w // factor, factor, 3).mean(axis=(1, 3))


def flip(reference: np.ndarray, test: np.ndarray, factor: int = 1) -> tuple[float, np.ndarray]:
    """Mean FLIP error of `test` against `reference` (0: identical; 1: as different as can be),
    and the per-pixel error map, after averaging factor × factor blocks."""
    import flip_evaluator

    ref, tst = to_float(reference), to_float(test)
    if ref.shape != tst.shape:
        raise ValueError(f"images differ in size: {ref.shape[:2]} and {tst.shape[:2]}")
    if factor > 1:
        ref, tst = downsample(ref, factor), downsample(tst, factor)
    error, mean, _ = flip_evaluator.evaluate(
        np.ascontiguousarray(ref), np.ascontiguousarray(tst), "LDR", applyMagma=False
    )
    return float(mean), np.asarray(error)
