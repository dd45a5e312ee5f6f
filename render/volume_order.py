"""The order the volume passes of a frame are drawn in (render/frame.py).

The volume writes no depth: its fragments are blended over what is drawn before them, so the
order is the compositing. Each pass's cells go far to near (render/grass_type.py sorts them);
several passes (levels, grass types, parts) over the same places are drawn in bands of
distance, far to near, each band pass by pass, or a later pass's far cuboids would go over an
earlier pass's near ones.

Grass types that grow among each other are drawn in bands of height, low to high, each type's
part of a band in turn. A ray into the grass meets the upper blades of both types first and
their lower parts behind them; a type drawn whole over the other showed its own lower, darker
parts where the other's blades hide them, and the pair went dark. Which type goes first
alternates from band to band, the taller type's last, so that its part above the other lies on
top. A type's parts that come one right after the other in that order are drawn as one pass
over both bands: its ray marches them together, as it would have composited them, and the
pass's fragments (each a whole ray's fixed cost) are shaded once. Two bands so keep a pair of
types at three passes, the type beneath drawn whole between the other's lower and upper part."""

from __future__ import annotations

import itertools

import numpy as np

DEPTH_BANDS = 8  # bands of distance when there are several volume passes
HEIGHT_BANDS = 2  # bands of height where grass types grow among each other
INF = float("inf")
Band = tuple[float, float]  # heights over the ground from, to
Part = tuple[tuple[int, int], Band]  # (band of height, turn in it), band


def beneath_heights(tops: list[float | None], heights: list[float]) -> list[float | None]:
    """Per grass type, the slice height of the tallest type whose layer lies lower than its
    own (`tops`: each type's layer height, None without slices), or None. Of two types with
    their layers as high, the later stands over the earlier."""
    out: list[float | None] = []
    for index, own in enumerate(tops):
        lower = [
            h for other, (top, h) in enumerate(zip(tops, heights, strict=True))
            if own is not None and top is not None and (top, other) < (own, index)
        ]  # fmt: skip
        out.append(float(max(lower)) if lower else None)
    return out


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


def stacked_parts(beneath: list[float | None], bands: int = HEIGHT_BANDS) -> list[list[Part]]:
    """Per grass type (`beneath`: beneath_heights), its volume passes as (order, band): the
    passes of all types sorted by order are drawn in that order. Without one type standing
    over another, each type is one pass. Else the heights up to the tallest grass another
    stands over are cut into `bands` bands (the last reaches up to the sky), each type draws
    each band, and in each band the type standing over another goes first or second by turns,
    second in the top band; a type's parts that follow each other in the order are one."""
    among = [b for b in beneath if b is not None]
    if not among:
        return [[((0, 0), (0.0, INF))] for _ in beneath]
    edges = [max(among) * k / bands for k in range(bands)] + [INF]
    out = []
    for b in beneath:
        over = b is not None
        parts: list[Part] = []
        for k in range(bands):
            taller_first = (bands - 1 - k) % 2 == 1
            parts.append(((k, 0 if over == taller_first else 1), (edges[k], edges[k + 1])))
        out.append(parts)
    return _merged(out)


def _merged(parts: list[list[Part]]) -> list[list[Part]]:
    """The parts with each run of one type's parts at turns that follow each other in the
    drawing order made one part: the first's turn, the bands' union. (Types at the same turn
    are drawn one after the other; of those, only one has slices: the others stand over none.)"""
    turns = sorted({key for own in parts for key, _ in own})
    after = dict(itertools.pairwise(turns))
    out: list[list[Part]] = []
    for own in parts:
        kept: list[tuple[tuple[int, int], Band, tuple[int, int]]] = []
        for key, band in own:
            if kept and after.get(kept[-1][2]) == key:
                first, (low, _), _ = kept[-1]
                kept[-1] = (first, (low, band[1]), key)
            else:
                kept.append((key, band, key))
        out.append([(key, band) for key, band, _ in kept])
    return out
