"""Blade shadows on the ground (Papavasiliou 2015, seeds/002 §3.6).

Near the eye the blades cast their shadows as geometry (shaders/geometry.glsl, SHADOW): each
blade is drawn a second time with every vertex moved along the sun onto the ground's plane at
its root, in the colour of the ground without the sun. A shadow covers as much of a pixel as
its blade does (the blade texture's alpha), within a `shadow_strength` share of the pixel's
samples that every shadow shares (screen-door transparency through the coverage mask): shadows
side by side within a pixel add up as their blades do, overlapping shadows darken once, and
nothing needs sorting. A point of the ground loses `strength` of its sun wherever any blade's
shadow falls on it.

The representations farther out cast none; there the ground loses what the blades' shadows
would take (shaders/ground.glsl), from the patch's `field`: where in a cell the union of its
blades' shadows falls — their outlines (the strip narrowed as the blade texture's mask narrows
it) moved along the sun onto the ground, the patch tiled so that its neighbours' shadows fall
in too — per mirror state of the aperiodic tiling and for every density at once (a point is
shadowed at density x when a blade with a threshold below x covers it: the blades the geometry
keeps). A slope maps each shadow onto its plane stretched along the sun; on uneven terrain the
field is drawn at a few such stretches (STRETCHES). `cover` is its mean over the cell.
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np

from core.patch import GrassPatch, blade_fill

SAMPLES = 17  # densities 0, 1/16 … 1 at which cover is given
RASTER = 384  # texels across a cell where the shadows are drawn
# the points along a blade's outline, at least (`_outlines`: the strip's rows and as many
# steps between them as make up this many)
OUTLINE_POINTS = 16
FIELD = 32  # texels across a cell of the field of where they fall (RASTER / 12 each)
# the shadows' lengths over level ground's at which the field is drawn on uneven terrain; a
# slope facing the sun shortens them, one facing away lengthens them (shaders/ground.glsl)
STRETCHES = (0.5, 1.0, 2.0)
LOWEST_SUN = math.sin(math.radians(5.0))  # a lower sun casts shadows as if it stood at 5°
MIRRORS = ((1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0))


def cover(
    patch: GrassPatch,
    sun: np.ndarray,
    mirrored: bool = True,
    samples: int = SAMPLES,
    raster: int = RASTER,
) -> np.ndarray:
    """(samples,) the share of a cell's ground in the shadow of the blades whose thresholds
    lie below x, for x = 0, 1 / (samples − 1) … 1; `sun` the unit vector towards the sun;
    `mirrored`: the cells are mirrored by the aperiodic tiling (the mean of its four states)."""
    return field(patch, sun, mirrored, (1.0,), samples, raster, 1)[:, 0, :, 0, 0].mean(axis=0)


def field(
    patch: GrassPatch,
    sun: np.ndarray,
    mirrored: bool = True,
    stretches: tuple[float, ...] = (1.0,),
    samples: int = SAMPLES,
    raster: int = RASTER,
    texels: int = FIELD,
) -> np.ndarray:
    """Where in a cell the shadows fall: (states, stretches, samples, texels, texels) float32,
    per mirror state of the aperiodic tiling (MIRRORS; the first alone if not `mirrored`), per
    length of the shadows over level ground's (`stretches`: a slope changes it), per
    density x = 0 … 1 as in `cover`, the share of each texel of the cell (rows along z, columns
    along x) in the shadow of the blades below x. Its mean over the texels is `cover`."""
    outlines, thresholds = _outlines(patch)
    states = MIRRORS if mirrored else MIRRORS[:1]
    out = np.zeros((len(states), len(stretches), samples, texels, texels), np.float32)
    if not len(thresholds):
        return out
    sun = np.asarray(sun, np.float64)
    shift = -sun[[0, 2]] / max(float(sun[1]), LOWEST_SUN)  # ground offset per unit of height
    length = float(np.linalg.norm(shift))
    way = shift / length if length > 0 else np.zeros(2)  # along the shadows, across the plan

    # each outline point from its blade's root, the same in every mirror state but for signs
    patch_roots = patch.roots.astype(np.float64)
    rel = outlines[..., [0, 2]] - patch_roots[:, None, :]
    heights = outlines[..., 1:2]

    def state(i: int) -> None:
        mirror = np.array(states[i])
        roots = 0.5 + mirror * (patch_roots - 0.5)
        # each shadow from its blade's root on level ground
        level = rel * mirror + heights * shift
        along = (level @ way)[..., None] * way
        for j, k in enumerate(stretches):
            # a slope scales the whole shadow along the sun by k: the ground's plane maps
            # the plan by I − sun_xz n_xzᵀ / (sun · n), of determinant k, taken as that stretch
            ground = level + (k - 1.0) * along
            ground += roots[:, None, :]
            ground *= raster
            image = np.full((raster, raster), 2.0)
            _shadows(ground, thresholds, image)
            out[i, j] = _below(image, texels, samples)

    # the mirror states on threads of their own: the rasterising holds no GIL (numba nogil)
    with ThreadPoolExecutor(min(len(states), os.cpu_count() or 1)) as pool:
        list(pool.map(state, range(len(states))))
    return out


@numba.njit(cache=True, nogil=True)
def _shadows(ground, thresholds, image):  # pragma: no cover - compiled
    """Each blade's shadow (its quads, two triangles each) into `image`, the lowest threshold
    kept per texel; the cell repeats, so what falls past an edge comes in at the other."""
    n, m = image.shape
    rows = ground.shape[1] // 2
    for b in range(ground.shape[0]):
        t = thresholds[b]
        for r in range(rows - 1):
            a = ground[b, r]
            c = ground[b, r + 1]
            d = ground[b, 2 * rows - 2 - r]
            e = ground[b, 2 * rows - 1 - r]
            _triangle(a, c, d, t, image, n, m)
            _triangle(a, d, e, t, image, n, m)


@numba.njit(cache=True, inline="always")
def _cross(ax, ay, bx, by, cy, lo, hi):  # pragma: no cover - compiled
    """The span [lo, hi] widened to where edge a–b crosses the row at height cy."""
    if (ay <= cy < by) or (by <= cy < ay):
        x = ax + (cy - ay) * (bx - ax) / (by - ay)
        return min(lo, x), max(hi, x)
    return lo, hi


@numba.njit(cache=True, nogil=True)
def _triangle(p0, p1, p2, value, image, n, m):  # pragma: no cover - compiled
    """The texels whose centres lie in the triangle, row by row (shadows are long and thin
    and cross the texels' rows and columns at any angle: a row's span, not the bounding box)."""
    x0, y0, x1, y1, x2, y2 = p0[0], p0[1], p1[0], p1[1], p2[0], p2[1]
    for py in range(math.floor(min(y0, y1, y2)), math.ceil(max(y0, y1, y2))):
        cy = py + 0.5
        lo, hi = math.inf, -math.inf
        lo, hi = _cross(x0, y0, x1, y1, cy, lo, hi)
        lo, hi = _cross(x1, y1, x2, y2, cy, lo, hi)
        lo, hi = _cross(x2, y2, x0, y0, cy, lo, hi)
        if lo > hi:
            continue
        i = py % n
        for px in range(math.ceil(lo - 0.5), math.floor(hi - 0.5) + 1):
            j = px % m
            if value < image[i, j]:
                image[i, j] = value


@numba.njit(cache=True, nogil=True)
def _below(image, texels, samples):  # pragma: no cover - compiled
    """(samples, texels, texels): per density x = k / (samples − 1) the share of each block of
    the image's texels (texels × texels blocks) whose value lies below x."""
    steps = samples - 1
    block = image.shape[0] // texels
    counts = np.zeros((samples + 1, texels, texels))
    for y in range(texels * block):
        for x in range(texels * block):
            # below k / steps from bin k on (a value of 2, no shadow, from none)
            counts[min(int(image[y, x] * steps) + 1, samples), y // block, x // block] += 1.0
    out = np.empty((samples, texels, texels), np.float32)
    total = np.zeros((texels, texels))
    for k in range(samples):
        total += counts[k]
        out[k] = total / (block * block)
    return out


def reach(patch: GrassPatch) -> float:
    """How high up its blades a patch's shadows come from on average: the height of the
    centroid of its blades' outlines (narrowed as in `cover`), in the patch's units. A point of
    the ground lies in the shadows of blades rooted up to a blade's height times the shadow's
    length per unit of height towards the sun, this far on average."""
    outlines, _ = _outlines(patch)
    if not len(outlines):
        return 0.0
    rows = outlines.shape[1] // 2
    left, right = outlines[:, :rows], outlines[:, rows:][:, ::-1]
    width = np.linalg.norm(right - left, axis=-1)
    y = 0.5 * (left[..., 1] + right[..., 1])
    area = 0.5 * (width[:, 1:] + width[:, :-1]) * np.abs(np.diff(y, axis=1))
    middle = 0.5 * (y[:, 1:] + y[:, :-1])
    return float((area * middle).sum() / max(area.sum(), 1e-12))


def _outlines(patch: GrassPatch, between: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Each blade's outline (blades, 2 · rows, 3) — up its left edge, down its right — as its
    strip is drawn (straight between the patch's rows) and the blade texture's mask narrows it
    (blade_fill, which is not straight between rows: `between` steps per row, by default as
    many as make OUTLINE_POINTS along the blade), and its threshold."""
    rows = patch.params.subdivisions + 1
    if between is None:
        between = max(1, -(-OUTLINE_POINTS // max(rows - 1, 1)))
    v = patch.vertices.reshape(-1, rows, 2)
    if not len(v):
        return np.zeros((0, 2 * ((rows - 1) * between + 1), 3)), np.zeros(0)
    t = np.linspace(0.0, rows - 1.0, (rows - 1) * between + 1)
    lo = np.minimum(t.astype(np.int64), rows - 2) if rows > 1 else np.zeros(t.size, np.int64)
    share = (t - lo)[None, :, None]
    hi = np.minimum(lo + 1, rows - 1)

    def along(values: np.ndarray) -> np.ndarray:  # (blades, rows, ...) at the steps
        values = values.astype(np.float64)
        if values.ndim == 2:
            return values[:, lo] + (values[:, hi] - values[:, lo]) * share[..., 0]
        return values[:, lo] + (values[:, hi] - values[:, lo]) * share

    left = along(v["position"][:, :, 0])
    right = along(v["position"][:, :, 1])
    centre = 0.5 * (left + right)
    fill = blade_fill(along(v["uv"][:, :, 0, 1]))[..., None]
    left = centre + (left - centre) * fill
    right = centre + (right - centre) * fill
    outline = np.concatenate([left, right[:, ::-1]], axis=1)
    return outline, v["threshold"][:, 0, 0].astype(np.float64)
