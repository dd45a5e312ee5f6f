"""How bright grass blades are on average, seen from a direction: the diffuse factor a far
representation must show to light like the blades it stands for (issue: the LOD image matches
all-geometry).

A blade is two-sided: seen from `e`, each of its fragments shows the face whose normal turns to
the viewer, n_f = n · sign(n · e), and covers the screen in proportion to |n · e|. The mean
diffuse factor of the blades seen from `e` is then

    L(e) = Σ_k |n_k · e| · l(n_k · sign(n_k · e)) / Σ_k |n_k · e|,
    l(n) = max(n · L, 0) + translucency · max(−n · L, 0)       (shaders/_lighting.glsl)

over the patch's vertex normals n_k. A slice's averaged normal cannot give this: averaging
turns the facing normals of many blades, which point to the viewer, into one short vector that
points wherever the capture put it, and max(·, 0) of an average is not the average of max(·, 0).
The image-based grass lights with this table, varied texel by texel by its normal about the
patch's mean (shaders/image.glsl). The volume lights its horizontal slice with it, and its
vertical slices' samples with their own normals, blended towards the table as far as averaging
has shortened them (shaders/volume.glsl; the table alone lost the near blades' light and shade).
The table is small (azimuth × elevation of e
over the upper hemisphere), depends on the light and the patch, and is cheap to rebuild when
either changes."""

from __future__ import annotations

import numpy as np

from core.canopy import Canopy

AZIMUTHS = 32  # table columns: azimuth of e, 0 = +z turning towards +x (as the sun's)
ELEVATIONS = 8  # table rows: elevation of e, 0 … 90 degrees, texel centres
SAMPLE = 20000  # at most this many normals are used (a patch has tens of thousands)


def directions(azimuths: int = AZIMUTHS, elevations: int = ELEVATIONS) -> np.ndarray:
    """(elevations, azimuths, 3) unit vectors at the table's texel centres."""
    az = 2.0 * np.pi * (np.arange(azimuths) + 0.5) / azimuths
    el = 0.5 * np.pi * (np.arange(elevations) + 0.5) / elevations
    ce = np.cos(el)[:, None]
    return np.stack(
        [
            ce * np.sin(az)[None, :],
            np.sin(el)[:, None].repeat(azimuths, 1),
            ce * np.cos(az)[None, :],
        ],
        axis=-1,
    )


def facing_lambert(
    normals: np.ndarray,
    light_dir: np.ndarray,
    translucency: float,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    seen: tuple[np.ndarray, Canopy] | None = None,
) -> np.ndarray:
    """(elevations, azimuths) float32: L(e) at each table direction (see the module).
    `seen`: the vertices' heights and the patch's canopy; each vertex then counts as far as a
    view from e reaches its height through the blades above it (Canopy.transmittance)."""
    n = np.asarray(normals, np.float64).reshape(-1, 3)
    length = np.linalg.norm(n, axis=1)
    keep = length > 1e-6
    n = n[keep] / length[keep, None]
    if len(n) == 0:
        return np.zeros((elevations, azimuths), np.float32)
    pick = np.linspace(0, len(n) - 1, min(len(n), SAMPLE)).astype(np.int64)
    n = n[pick]
    e = directions(azimuths, elevations).reshape(-1, 3)
    ne = n @ e.T  # (normals, directions)
    nl = n @ np.asarray(light_dir, np.float64)  # (normals,)
    facing_l = np.sign(ne) * nl[:, None]  # n_f · L
    lit = np.maximum(facing_l, 0.0) + translucency * np.maximum(-facing_l, 0.0)
    w = np.abs(ne)
    if seen is not None:
        heights, canopy = seen
        y = np.asarray(heights, np.float64).reshape(-1)[keep][pick]
        theta = np.arcsin(directions(1, elevations)[:, 0, 1])  # the rows' elevations
        w = w * np.repeat(canopy.transmittance(y, theta), azimuths, axis=1)
    table = (w * lit).sum(axis=0) / np.maximum(w.sum(axis=0), 1e-12)
    return table.reshape(elevations, azimuths).astype(np.float32)
