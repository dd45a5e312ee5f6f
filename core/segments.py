"""Blade segments fewer with distance (Horlebein §4.1: 5 / 3 / 1 segments by distance;
Papavasiliou §2.3): a blade's strip is drawn through fewer of its rows the smaller it is on
screen, its curve sampled at fewer points and its shape kept.

Level k keeps the rows that are multiples of 2^k, and the tip; the last level keeps the root and
the tip alone (one segment). Each level's rows hold the next level's, so a vertex leaves at one
level only: while a blade is drawn at level k it slides its leaving vertices onto the chord
between the rows of level k + 1 as the continuous level f rises from k to k + 1, and at f = k + 1
the strip has level k + 1's shape; no step shows (geomorphing). They slide (4^(f − k) − 1) / 3 of
the way: level k + 1's chord strays TOLERANCE_PX · 4^(k + 1 − f) from the curve, so the drawn
shape stays within the tolerance throughout.

The level follows from the patch: sampling a quadratic curve p(t) = b t + g t² (eq. 4.1) at steps
Δt leaves at most |g| Δt² / 4 between the chord and the curve. Level k's steps are 2^k / s for a
patch of s subdivisions, so its error is e₀ 4^k with e₀ = |g| / (4 s²); a blade takes the
coarsest level whose error on screen stays within TOLERANCE_PX, continuously:

    f = ½ log₂(TOLERANCE_PX · pixel · distance / (e₀ · cell size)),  clamped to 0 … last level

with `pixel` the view's radians per pixel and `distance` the eye's to the instance's nearest
point. The wind bends the curve further (core/wind.py): its largest lean adds to |g| while it
blows. The renderer bins instances by the floor of f and hands each its f (render/geometry.py,
shaders/_segments.glsl)."""

from __future__ import annotations

import numpy as np

from core.wind import MAX_LEAN, MIDDLE_SHARE, curve_length

# by default the chord may stray this far from the curve on screen: an eighth of a pixel, a
# quarter of the spacing of the samples a 4× multisampled pixel holds, so a thin blade covers
# nearly the samples it covers whole (a grass type's LOD settings may set another,
# core/lod.py LodConfig.segment_tolerance)
TOLERANCE_PX = 0.125


def level_count(subdivisions: int) -> int:
    """Levels 0 … count − 1; the last draws one segment."""
    return 1 + int(np.ceil(np.log2(subdivisions))) if subdivisions > 1 else 1


def level_rows(subdivisions: int, level: int) -> np.ndarray:
    """The rows of a blade's strip that level `level` keeps: multiples of 2^level, and the tip."""
    rows = list(range(0, subdivisions + 1, 2**level))
    if rows[-1] != subdivisions:
        rows.append(subdivisions)
    return np.array(rows)


def level_indices(
    blades: int, subdivisions: int, level: int, order: np.ndarray | None = None
) -> np.ndarray:
    """Two triangles per kept segment of each blade's strip, over the same vertices as the full
    strip ((segment, side) ordered, as core/patch.py lays them out); the blades in `order`
    (their indices) where given, else as the patch holds them."""
    rows = level_rows(subdivisions, level) * 2
    lo, hi = rows[:-1], rows[1:]
    quad = np.stack([lo, lo + 1, hi, hi, lo + 1, hi + 1], axis=1).reshape(-1)
    blade = np.arange(blades) if order is None else np.asarray(order, np.int64)
    base = (blade * (subdivisions + 1) * 2)[:, None]
    return (base + quad[None, :]).astype(np.uint32).reshape(-1)


def leaving(subdivisions: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For each row 0 … s: the rows below and above it on the chord it slides onto when it
    leaves (itself where it never leaves: the root and the tip), and its share of the way from
    the one below to the one above."""
    rows = np.arange(subdivisions + 1)
    lo, hi = rows.copy(), rows.copy()
    for level in range(level_count(subdivisions) - 1):
        kept = set(level_rows(subdivisions, level + 1).tolist())
        for row in level_rows(subdivisions, level):
            if row not in kept:
                step = 2 ** (level + 1)
                lo[row] = row - row % step
                hi[row] = min(lo[row] + step, subdivisions)
    share = np.where(hi > lo, (rows - lo) / np.maximum(hi - lo, 1), 0.0)
    return lo, hi, share


def chord_colors(colors: np.ndarray) -> np.ndarray:
    """(blades, s + 1, 3) vertex colours as each row's colour on the chord it slides onto: the
    colour it takes on when it leaves (the coarser strip interpolates its neighbours')."""
    lo, hi, share = leaving(colors.shape[1] - 1)
    return colors[:, lo] * (1.0 - share[None, :, None]) + colors[:, hi] * share[None, :, None]


def level_widths(centres: np.ndarray) -> np.ndarray:
    """(blades, 4): each blade's width at levels 1 … 4 over its full strip's, given its rows'
    centre points (blades, s + 1, 3). A level's chords cut the curve's corners, so its strip is
    shorter than the full one: as much wider, it covers as much (1 past the last level)."""
    centres = np.asarray(centres, np.float64)
    s = centres.shape[1] - 1
    out = np.ones((centres.shape[0], 4), np.float32)

    def length(rows: np.ndarray) -> np.ndarray:
        return np.linalg.norm(np.diff(centres[:, rows], axis=1), axis=-1).sum(axis=1)

    full = length(level_rows(s, 0))
    for level in range(1, level_count(s)):
        out[:, level - 1] = full / np.maximum(length(level_rows(s, level)), 1e-12)
    return out


def curvature(ctrl1: np.ndarray, ctrl2: np.ndarray, lean: float = 0.0) -> float:
    """The largest |g| of a patch's blades (patch units), given their Bézier control points
    (B(t) = 2t(1 − t) c1 + t² c2, so g = c2 − 2 c1); bent by the wind or trampled, the largest
    bend added: the tip moves by up to `lean` of the blade's length (at most MAX_LEAN) and the
    middle control point by MIDDLE_SHARE of that, and the curve shrinks back to its length
    (core/wind.py bend), which does not make |g| larger."""
    c1, c2 = np.asarray(ctrl1, np.float64), np.asarray(ctrl2, np.float64)
    if not len(c1):
        return 0.0
    g = np.linalg.norm(c2 - 2.0 * c1, axis=-1)
    if lean > 0.0:
        g = g + abs(1.0 - 2.0 * MIDDLE_SHARE) * min(lean, MAX_LEAN) * curve_length(c1, c2)
    return float(g.max())


def error_scale(
    g: float, subdivisions: int, cell_size: float, pixel: float, tolerance: float = TOLERANCE_PX
) -> float:
    """C of f = ½ log₂(C · distance): tolerance · pixel / (e₀ · cell size); infinite for a
    patch of straight blades (every level is exact: the last is drawn)."""
    e0 = g / (4.0 * subdivisions**2) * cell_size
    return tolerance * pixel / e0 if e0 > 0 else float("inf")


def cell_distance(eye: np.ndarray, instances: np.ndarray, cell_size: float, height: float):
    """Distance from the eye to each instance's nearest point: its cells (x, z), its ground's
    height range (lowest, and unplanarity above it) and the patch's height above that (world
    units)."""
    lo = np.stack(
        [instances["origin"][:, 0], instances["ground"][:, 0], instances["origin"][:, 1]], axis=1
    ).astype(np.float64)
    size = instances["size"].astype(np.float64)
    hi = np.stack(
        [
            lo[:, 0] + size[:, 0],
            lo[:, 1] + instances["ground"][:, 1] + height,
            lo[:, 2] + size[:, 1],
        ],
        axis=1,
    )
    lo[:, [0, 2]] *= cell_size
    hi[:, [0, 2]] *= cell_size
    nearest = np.clip(np.asarray(eye, np.float64)[None, :], lo, hi)
    return np.linalg.norm(nearest - np.asarray(eye, np.float64)[None, :], axis=1)


def segment_level(distance: np.ndarray, scale: float, levels: int, bias: int = 0) -> np.ndarray:
    """The continuous level f at each distance; `bias` levels coarser (a draft's)."""
    d = np.maximum(np.asarray(distance, np.float64), 1e-9)
    with np.errstate(divide="ignore"):
        f = np.clip(0.5 * np.log2(scale * d), 0.0, levels - 1)
    return np.minimum(f + bias, levels - 1)
