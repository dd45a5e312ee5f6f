"""Blade shadows on the ground (Papavasiliou 2015, seeds/002 §3.6).

Near the eye the blades cast their shadows as geometry (shaders/geometry.glsl, SHADOW): each
blade is drawn a second time with every vertex moved along the sun onto the ground's plane at
its root, in the colour of the ground without the sun, covering `shadow_strength` of a pixel's
samples (screen-door transparency through the coverage mask). All shadows pick the same
samples of a pixel, so overlapping shadows do not darken twice and need no sorting: a point of
the ground loses `strength` of its sun wherever any blade's shadow falls on it.

The representations farther out cast none; there the ground loses what the blades' shadows take
on average (shaders/ground.glsl): `strength` times the share of a cell's ground that the union
of its blades' shadows covers. `cover` measures that share from the patch itself — its blades'
outlines (the strip narrowed as the blade texture's mask narrows it) moved along the sun onto
the ground, the patch tiled so that its neighbours' shadows fall in too, averaged over the
aperiodic tiling's four mirror states — for every density at once: a point is shadowed at
density x when a blade with a threshold below x covers it (the blades the geometry keeps).
On level ground; the ground's shader lengthens the shadows on a slope (shaders/ground.glsl).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from core.patch import GrassPatch, blade_fill

SAMPLES = 17  # densities 0, 1/16 … 1 at which cover is given
RASTER = 384  # texels across a cell where the shadows are drawn
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
    outlines, thresholds = _outlines(patch)
    if not len(thresholds):
        return np.zeros(samples)
    sun = np.asarray(sun, np.float64)
    shift = -sun[[0, 2]] / max(float(sun[1]), LOWEST_SUN)  # ground offset per unit of height
    levels = np.linspace(0.0, 1.0, samples)
    states = MIRRORS if mirrored else MIRRORS[:1]
    out = np.zeros(samples)
    for sx, sz in states:
        points = outlines.copy()
        points[..., 0] = 0.5 + sx * (points[..., 0] - 0.5)
        points[..., 2] = 0.5 + sz * (points[..., 2] - 0.5)
        ground = (points[..., [0, 2]] + points[..., 1:2] * shift) * raster  # along the sun
        image = np.full((raster, raster), 2.0)
        _shadows(ground, thresholds, image)
        lowest = np.sort(image.ravel())
        out += np.searchsorted(lowest, levels, side="left") / lowest.size
    return out / len(states)


@numba.njit(cache=True)
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


@numba.njit(cache=True)
def _triangle(p0, p1, p2, value, image, n, m):  # pragma: no cover - compiled
    area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])
    if area == 0.0:
        return
    x0 = math.floor(min(p0[0], p1[0], p2[0]))
    x1 = math.ceil(max(p0[0], p1[0], p2[0]))
    y0 = math.floor(min(p0[1], p1[1], p2[1]))
    y1 = math.ceil(max(p0[1], p1[1], p2[1]))
    for py in range(y0, y1):
        cy = py + 0.5
        for px in range(x0, x1):
            cx = px + 0.5
            w0 = (p1[0] - cx) * (p2[1] - cy) - (p2[0] - cx) * (p1[1] - cy)
            w1 = (p2[0] - cx) * (p0[1] - cy) - (p0[0] - cx) * (p2[1] - cy)
            w2 = (p0[0] - cx) * (p1[1] - cy) - (p1[0] - cx) * (p0[1] - cy)
            if area > 0.0:
                inside = w0 >= 0.0 and w1 >= 0.0 and w2 >= 0.0
            else:
                inside = w0 <= 0.0 and w1 <= 0.0 and w2 <= 0.0
            if inside:
                i = py % n
                j = px % m
                if value < image[i, j]:
                    image[i, j] = value


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


def _outlines(patch: GrassPatch) -> tuple[np.ndarray, np.ndarray]:
    """Each blade's outline (blades, 2 · rows, 3) — up its left edge, down its right — as the
    blade texture's mask narrows its strip, and its threshold."""
    rows = patch.params.subdivisions + 1
    v = patch.vertices.reshape(-1, rows, 2)
    if not len(v):
        return np.zeros((0, 2 * rows, 3)), np.zeros(0)
    left = v["position"][:, :, 0].astype(np.float64)
    right = v["position"][:, :, 1].astype(np.float64)
    centre = 0.5 * (left + right)
    fill = blade_fill(v["uv"][:, :, 0, 1].astype(np.float64))[..., None]
    left = centre + (left - centre) * fill
    right = centre + (right - centre) * fill
    outline = np.concatenate([left, right[:, ::-1]], axis=1)
    return outline, v["threshold"][:, 0, 0].astype(np.float64)
