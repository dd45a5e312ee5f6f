"""Picking the ground under the cursor (map painting in the viewport): a camera ray through a
pixel, its first hit with the terrain's height field, and the design-map texel at a world
point. Vectorised: the ray is sampled at once, then refined between the two samples that
bracket the hit."""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.heights import bilinear
from core.terrain import Terrain


def pixel_ray(
    camera: Camera, x: float, y: float, width: int, height: int
) -> tuple[np.ndarray, np.ndarray]:
    """(origin, unit direction) in world space of the ray through pixel (x, y), y downwards."""
    inverse = np.linalg.inv(
        camera.projection(width / max(height, 1)).astype(np.float64) @ camera.view()
    )
    ndc_x = 2.0 * x / max(width, 1) - 1.0
    ndc_y = 1.0 - 2.0 * y / max(height, 1)
    near = inverse @ np.array([ndc_x, ndc_y, -1.0, 1.0])
    far = inverse @ np.array([ndc_x, ndc_y, 1.0, 1.0])
    near, far = near[:3] / near[3], far[:3] / far[3]
    direction = far - near
    return camera.eye.astype(np.float64), direction / np.linalg.norm(direction)


def ground_height(terrain: Terrain, x, z, heights: np.ndarray | None = None) -> np.ndarray:
    """World height of the ground at world (x, z) (0 on a flat terrain). `heights`: a height
    map newer than the terrain's (one being painted), 0 … 1 like the terrain's."""
    x, z = np.asarray(x, np.float64), np.asarray(z, np.float64)
    heights = terrain.heights if heights is None else heights
    if heights is None or terrain.height_scale <= 0:
        return np.zeros(np.broadcast(x, z).shape)
    u = (x - terrain.origin[0]) / terrain.columns
    v = (z - terrain.origin[1]) / terrain.rows
    return bilinear(heights, u, v) * terrain.height_scale


def ground_hit(
    terrain: Terrain,
    origin: np.ndarray,
    direction: np.ndarray,
    samples: int = 2048,
    heights: np.ndarray | None = None,
) -> np.ndarray | None:
    """The first point where the ray meets the ground inside the terrain, or None; `heights`
    as in ground_height."""
    x0, z0, x1, z1 = terrain.rect
    bottom, top = terrain.ground_span
    if heights is not None and terrain.height_scale > 0:
        top = max(top, float(heights.max()) * terrain.height_scale)
        bottom = min(bottom, float(heights.min()) * terrain.height_scale)
    lo = np.array([x0, bottom - 1e-3, z0])
    hi = np.array([x1, top + 1e-3, z1])
    parallel = np.abs(direction) < 1e-12
    if np.any(parallel & ((origin < lo) | (origin > hi))):
        return None  # parallel to a slab of the terrain's box and outside it
    d = np.where(parallel, 1.0, direction)
    t0, t1 = (lo - origin) / d, (hi - origin) / d
    near = np.max(np.where(parallel, -np.inf, np.minimum(t0, t1)))
    far = np.min(np.where(parallel, np.inf, np.maximum(t0, t1)))
    near = max(float(near), 0.0)
    if not far >= near:
        return None
    t = np.linspace(near, far, samples)
    points = origin[None, :] + t[:, None] * direction[None, :]
    above = points[:, 1] - ground_height(terrain, points[:, 0], points[:, 2], heights)
    below = np.flatnonzero(above <= 0.0)
    if below.size == 0:
        return None
    k = int(below[0])
    if k == 0:
        return points[0]
    a, b = above[k - 1], above[k]  # linear between the bracketing samples
    f = a / (a - b) if a != b else 0.0
    return points[k - 1] + (points[k] - points[k - 1]) * f


def world_to_texel(terrain: Terrain, map_size: tuple[int, int], x: float, z: float):
    """Design-map position (column, row) in texels of world (x, z)."""
    w, h = map_size
    return (
        (x - terrain.origin[0]) / terrain.columns * w,
        (z - terrain.origin[1]) / terrain.rows * h,
    )


def ground_circle(terrain: Terrain, x: float, z: float, radius: float, points: int = 64):
    """(points, 3) world positions of a circle lying on the ground, lifted a little above it."""
    a = np.linspace(0.0, 2.0 * np.pi, points)
    cx = x + radius * np.cos(a)
    cz = z + radius * np.sin(a)
    y = ground_height(terrain, cx, cz) + 0.02
    return np.stack([cx, y, cz], axis=1).astype(np.float32)


def zone_rings(terrain: Terrain, eye, levels, points: int = 160) -> list[tuple[np.ndarray, str]]:
    """The LOD zone boundaries on the ground around the eye: a circle where each level begins
    and ends (the LOD distance is horizontal, core/lod.py), with the level's representation."""
    rings = []
    for level in levels:
        for d in (level.begin, level.end):
            if d is not None and d > 0:
                ring = ground_circle(terrain, float(eye[0]), float(eye[2]), float(d), points)
                rings.append((ring, level.representation))
    return rings
