"""What `sward export` writes, as arrays (no file formats here: app/export.py writes them).

- A grass type's patch as a mesh: the blades' vertices in the unit cell (x, z in 0 … 1, y up,
  thesis 4.1), normals, per-vertex colour, UV over the blade texture (across, and from root
  to tip), and on every vertex its blade's root (x, z) and density threshold (4.1.3), so an
  engine can thin the patch by the density map as Sward does (a blade shows where its
  threshold ≤ the local density at its root).
- Its instances: one per cell that can show grass of the type (the density map's channel is
  not zero there, core/occupancy.py, as the renderer skips bare cells), in blocks of cells so
  an engine can cull them. Each instance is a translation, a rotation and a scale: the
  aperiodic tiling's mirror bits (thesis 6.3) are a scale of −1 about the cell's centre in x
  and/or z, and the instance stands on the ground at the cell's centre, tilted to the
  ground's slope there, so neighbouring cells meet without steps (the renderer displaces every
  vertex by the height map instead, 6.4.4, and keeps the blades upright).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from core.heights import bilinear
from core.occupancy import DensityOccupancy
from core.patch import GrassPatch
from core.tiling import mirror_bits

BLOCK = 64  # cells per side of one block of instances


def patch_mesh(patch: GrassPatch) -> dict[str, np.ndarray]:
    """The patch's vertex attributes (float32) and triangle indices (uint32)."""
    v = patch.vertices
    normals = v["normal"].astype(np.float64)
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    return {
        "position": np.ascontiguousarray(v["position"], np.float32),
        "normal": np.ascontiguousarray(normals, np.float32),
        # Sward shades and stores colours as the display shows them (no sRGB framebuffer);
        # glTF's COLOR_0 and USD's displayColor are linear, which an engine encodes for the
        # display again
        "color": np.ascontiguousarray(srgb_to_linear(v["color"]), np.float32),
        "uv": np.ascontiguousarray(v["uv"], np.float32),
        "threshold": np.ascontiguousarray(v["threshold"], np.float32),
        "root": np.ascontiguousarray(v["root"], np.float32),
        "ctrl1": np.ascontiguousarray(v["ctrl1"], np.float32),
        "ctrl2": np.ascontiguousarray(v["ctrl2"], np.float32),
        "indices": np.ascontiguousarray(patch.indices, np.uint32),
    }


def srgb_to_linear(values) -> np.ndarray:
    """Display (sRGB-encoded) values 0 … 1 as linear light (IEC 61966-2-1)."""
    v = np.clip(np.asarray(values, np.float64), 0.0, 1.0)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def grass_cells(document) -> list[np.ndarray]:
    """Per grass type, (columns, rows) bool: the cells that can show its grass."""
    t = document.terrain_spec
    density = document.maps.layer("density")
    if document.density <= 0:
        return [np.zeros((t.columns, t.rows), bool) for _ in document.grass_types]
    occupancy = DensityOccupancy(t.columns, t.rows, density)
    return [occupancy.grows(kind.channel) for kind in document.grass_types]


def blocks(columns: int, rows: int, size: int = BLOCK) -> Iterator[tuple[int, int, int, int]]:
    """(x0, z0, x1, z1) in cells: the terrain in blocks of `size` × `size` cells."""
    for z0 in range(0, rows, size):
        for x0 in range(0, columns, size):
            yield x0, z0, min(x0 + size, columns), min(z0 + size, rows)


def block_instances(
    document, grows: np.ndarray, block: tuple[int, int, int, int], heights: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The instances of one block: translations (n, 3), rotations (n, 4: unit quaternions
    x, y, z, w) and scales (n, 3), float32, world units, column by column. `heights` is
    document.heights(), taken once for all blocks."""
    x0, z0, x1, z1 = block
    ix, iz = np.nonzero(grows[x0:x1, z0:z1])
    ix, iz = ix + x0, iz + z0
    spec = document.terrain_spec
    # the cells' corners as the terrain places them (centred on the origin, core/terrain.py),
    # without building the terrain's quadtree and height ranges: memory for this block only
    origin = np.column_stack([ix - spec.columns / 2.0, iz - spec.rows / 2.0]).astype(np.float32)
    if spec.mirror_seed is None:
        mirror = np.ones((ix.size, 2))
    else:
        mirror = mirror_bits(origin.astype(np.float64), spec.mirror_seed).astype(np.float64)
    origin = origin.astype(np.float64)
    y, normal = _ground(heights, spec, ix, iz)
    rotation = _tilt(normal)
    # the cell's centre (0.5, 0, 0.5) of the patch, mirrored (s = ±1 per axis) and tilted,
    # lands on the ground at the centre: x' = t + R·(s·x) maps the unit cell onto its cell
    centre = np.column_stack([origin[:, 0] + 0.5, y, origin[:, 1] + 0.5])
    local = np.column_stack([0.5 * mirror[:, 0], np.zeros(ix.size), 0.5 * mirror[:, 1]])
    translation = centre - _rotate(rotation, local)
    scale = np.column_stack([mirror[:, 0], np.ones(ix.size), mirror[:, 1]])
    return translation.astype(np.float32), rotation.astype(np.float32), scale.astype(np.float32)


def _ground(heights, spec, ix: np.ndarray, iz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ground's height and unit normal at the cells' centres (the height map sampled as
    the renderer samples it, its slope over one cell)."""
    if heights is None or ix.size == 0:
        up = np.zeros((ix.size, 3))
        up[:, 1] = 1.0
        return np.zeros(ix.size), up

    def h(dx: float, dz: float) -> np.ndarray:
        u = (ix + 0.5 + dx) / spec.columns
        v = (iz + 0.5 + dz) / spec.rows
        return bilinear(heights, u, v) * spec.height_scale

    gx = h(0.5, 0.0) - h(-0.5, 0.0)
    gz = h(0.0, 0.5) - h(0.0, -0.5)
    normal = np.column_stack([-gx, np.ones(ix.size), -gz])
    return h(0.0, 0.0), normal / np.linalg.norm(normal, axis=1, keepdims=True)


def _tilt(normal: np.ndarray) -> np.ndarray:
    """Unit quaternions (x, y, z, w) turning +y onto each normal (the shortest turn)."""
    q = np.column_stack([normal[:, 2], np.zeros(len(normal)), -normal[:, 0], 1.0 + normal[:, 1]])
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def _rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Each vector of v (n, 3) turned by its quaternion of q (n, 4: x, y, z, w)."""
    u, w = q[:, :3], q[:, 3:]
    t = 2.0 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def ground_mesh(document, step: int = 1) -> dict[str, np.ndarray]:
    """The terrain as a grid mesh over its cells, a vertex every `step` cells (and at the far
    edges): positions, normals, UV over the design maps (u along x, v along z) and indices."""
    spec = document.terrain_spec
    ox, oz = -spec.columns / 2.0, -spec.rows / 2.0
    xs = np.unique(np.append(np.arange(0, spec.columns, step), spec.columns)).astype(np.float64)
    zs = np.unique(np.append(np.arange(0, spec.rows, step), spec.rows)).astype(np.float64)
    u, v = xs / spec.columns, zs / spec.rows
    uu, vv = np.meshgrid(u, v)  # (len(zs), len(xs))
    heights = document.heights()
    if heights is None:
        y = np.zeros(uu.shape)
    else:
        y = bilinear(heights, uu.ravel(), vv.ravel()).reshape(uu.shape) * spec.height_scale
    xx, zz = np.meshgrid(xs + ox, zs + oz)
    position = np.stack([xx, y, zz], axis=-1)
    # normals from the heights' central differences over the grid
    gx = np.gradient(y, xs, axis=1) if xs.size > 1 else np.zeros_like(y)
    gz = np.gradient(y, zs, axis=0) if zs.size > 1 else np.zeros_like(y)
    normal = np.stack([-gx, np.ones_like(y), -gz], axis=-1)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    nx, nz = xs.size, zs.size
    k = np.arange(nx * nz).reshape(nz, nx)
    a, b, c, d = k[:-1, :-1], k[:-1, 1:], k[1:, :-1], k[1:, 1:]
    # counter-clockwise seen from above (+y): a, c, b and b, c, d
    indices = np.stack([a, c, b, b, c, d], axis=-1).reshape(-1)
    return {
        "position": position.reshape(-1, 3).astype(np.float32),
        "normal": normal.reshape(-1, 3).astype(np.float32),
        "uv": np.stack([uu, vv], axis=-1).reshape(-1, 2).astype(np.float32),
        "indices": indices.astype(np.uint32),
    }
