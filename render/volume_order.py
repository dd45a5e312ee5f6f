"""The order the volume passes of a frame are drawn in (render/frame.py).

The volume writes no depth: its fragments are blended over what is drawn before them, so the
order is the compositing. Each pass's cells go far to near (render/grass_type.py sorts them);
several passes (levels, grass types, parts) over the same places are drawn in bands of
distance, far to near, each band pass by pass, or a later pass's far cuboids would go over an
earlier pass's near ones. A grass type that stands over another is drawn in parts: its blades
among the shorter grass half before and half after it, the mean of the two orders of two
interleaved veils, and its part above the shorter grass last, over it."""

from __future__ import annotations

import numpy as np

DEPTH_BANDS = 8  # bands of distance when there are several volume passes
INF = float("inf")
Band = tuple[float, float, float]  # heights over the ground from, to; the share of the blades


def beneath_heights(tops: list[float | None], heights: list[float]) -> list[float | None]:
    """Per grass type, the slice height of the tallest type whose layer lies lower than its
    own (`tops`: each type's layer height, None without slices), or None."""
    out: list[float | None] = []
    for own in tops:
        lower = [
            h for top, h in zip(tops, heights, strict=True)
            if own is not None and top is not None and top < own
        ]  # fmt: skip
        out.append(float(max(lower)) if lower else None)
    return out


def height_parts(beneath: float | None) -> list[tuple[int, Band]]:
    """A type's volume passes as (phase, band): phase 1 for a type that stands over none; the
    parts of one that stands over grass `beneath` tall in phases 0, 2 (among it) and 3 (above)."""
    if beneath is None:
        return [(1, (0.0, INF, 1.0))]
    return [(0, (0.0, beneath, 0.5)), (2, (0.0, beneath, 0.5)), (3, (beneath, INF, 1.0))]


def distance_bands(distances: list[np.ndarray], bands: int) -> list[list[slice]]:
    """For each band of distance, far to near, the slice of each array (distances sorted far
    to near) that falls in it: bands of equal counts over all of them, every entry in one."""
    every = np.concatenate(distances) if distances else np.zeros(0)
    if every.size == 0 or bands <= 1:
        return [[slice(0, d.size) for d in distances]]
    edges = np.quantile(every, np.linspace(1.0, 0.0, bands + 1))[1:-1]
    cuts = [np.searchsorted(-d, -edges, side="right") for d in distances]
    out = []
    for b in range(bands):
        row = []
        for d, cut in zip(distances, cuts, strict=True):
            start = int(cut[b - 1]) if b else 0
            stop = int(cut[b]) if b < bands - 1 else d.size
            row.append(slice(start, max(start, stop)))
        out.append(row)
    return out
