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
from core.light_moments import LightMoments, powers

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


def _facing_weights(
    normals: np.ndarray,
    azimuths: int,
    elevations: int,
    seen: tuple[np.ndarray, Canopy] | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The unit normals (k, 3) a table takes (at most SAMPLE), each one's weight from each
    table direction (k, m): |n · e|, times what reaches it with `seen`; and sign(n · e)."""
    n = np.asarray(normals, np.float64).reshape(-1, 3)
    length = np.linalg.norm(n, axis=1)
    keep = length > 1e-6
    n = n[keep] / length[keep, None]
    pick = np.linspace(0, len(n) - 1, min(len(n), SAMPLE)).astype(np.int64)
    n = n[pick]
    ne = n @ directions(azimuths, elevations).reshape(-1, 3).T  # (normals, directions)
    w = np.abs(ne)
    if seen is not None and len(n):
        heights, canopy = seen
        y = np.asarray(heights, np.float64).reshape(-1)[keep][pick]
        theta = np.arcsin(directions(1, elevations)[:, 0, 1])  # the rows' elevations
        w = w * np.repeat(canopy.transmittance(y, theta), azimuths, axis=1)
    return n, w, np.sign(ne)


def facing_lambert(
    normals: np.ndarray,
    light_dir: np.ndarray,
    translucency: float,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    seen: tuple[np.ndarray, Canopy] | None = None,
) -> np.ndarray:
    """(elevations, azimuths) float32: L(e) at each table direction (see the module), summed
    over the normals for this light. `seen`: the vertices' heights and the patch's canopy; each
    vertex then counts as far as a view from e reaches its height through the blades above it
    (Canopy.transmittance)."""
    n, w, facing = _facing_weights(normals, azimuths, elevations, seen)
    if len(n) == 0:
        return np.zeros((elevations, azimuths), np.float32)
    facing_l = facing * (n @ np.asarray(light_dir, np.float64))[:, None]  # n_f · L
    lit = np.maximum(facing_l, 0.0) + translucency * np.maximum(-facing_l, 0.0)
    table = (w * lit).sum(axis=0) / np.maximum(w.sum(axis=0), 1e-12)
    return table.reshape(elevations, azimuths).astype(np.float32)


def facing_moments(
    normals: np.ndarray,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    seen: tuple[np.ndarray, Canopy] | None = None,
) -> LightMoments:
    """facing_lambert's table for any light: LightMoments of shape (elevations, azimuths)
    (core/light_moments.py), `.lit(light, translucency)` the table."""
    n = np.asarray(normals, np.float64).reshape(-1, 3)
    length = np.linalg.norm(n, axis=1)
    keep = length > 1e-6
    pick = np.linspace(0, keep.sum() - 1, min(int(keep.sum()), SAMPLE)).astype(np.int64)
    n = (n[keep] / length[keep, None])[pick]
    e = directions(azimuths, elevations).reshape(-1, 3)
    # the (k, m) weights and their products in single precision (the sums' tables agree with
    # double precision's to under 1e-6: tests/core/test_light_moments.py); the light's side is
    # a product with these sums (core/light_moments.py)
    w = np.abs(n.astype(np.float32) @ e.T.astype(np.float32))  # |n · e|
    through = np.ones((len(n), 1))  # what reaches each vertex, by table row
    if seen is not None and len(n):
        heights, canopy = seen
        y = np.asarray(heights, np.float64).reshape(-1)[keep][pick]
        theta = np.arcsin(directions(1, elevations)[:, 0, 1])  # the rows' elevations
        through = canopy.transmittance(y, theta)
        w *= np.repeat(through.astype(np.float32), azimuths, axis=1)
    basis = np.hstack([powers(n, np.float32), np.ones((len(n), 1), np.float32)])
    sums = (w.T @ basis).astype(np.float64)
    # Σ w s n, s = sign(n · e): w s = (n · e) times what reaches the vertex, which depends on
    # the row alone, so the sum is (Σ through n nᵀ) e per row, with no second (k, m) product
    second = (through.T @ (n[:, :, None] * n[:, None, :]).reshape(-1, 9)).reshape(-1, 3, 3)
    row = np.arange(len(e)) // azimuths if through.shape[1] > 1 else np.zeros(len(e), np.int64)
    signed = np.einsum("mij,mj->mi", second[row], e)
    return LightMoments(sums[:, :-1], signed, sums[:, -1]).reshaped((elevations, azimuths))


# -- the wind's bend ---------------------------------------------------------------------------
# The wind bends the blades and their normals turn with their curves (core/wind.py
# bend_vertices, shaders/_blade_vertex.glsl): a gust changes the blades' light, and a far
# representation shows it through these coefficients of L as a function of the lean λ (the tip
# displacement, a fraction of a blade's length): L(e, λ) ≈ L + G · λ + ½ λᵀ H λ, from central
# differences of the table of the patch bent by ±LEAN_STEP along x, z and the diagonals. The
# second order matters: a lean tilts further the blades that lean another way at rest, whichever
# way it blows, and the light's change is as much quadratic in λ as linear.
LEAN_STEP = 0.3  # the shaders keep λ within ±LEAN_STEP per component: interpolation
BEND_SAMPLE = 6000  # the bent tables' normals (nine tables on every patch or light change)


BENDS = ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1))


def bend_moments(
    vertices: np.ndarray,
    canopy: Canopy | None = None,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    step: float = LEAN_STEP,
) -> LightMoments:
    """The tables of the patch bent by each of BENDS times `step` for any light: LightMoments
    of shape (len(BENDS), elevations, azimuths); with `canopy`, each vertex seen through the
    blades above its bent height (facing_lambert's `seen`)."""
    from core.wind import bend_vertices

    pick = np.linspace(0, len(vertices) - 1, min(len(vertices), BEND_SAMPLE)).astype(np.int64)
    v = vertices[pick]
    tables = []
    for x, z in BENDS:
        positions, normals = bend_vertices(v, np.array([x, z]) * step)
        seen = None if canopy is None else (positions[:, 1], canopy)
        tables.append(facing_moments(normals, azimuths, elevations, seen))
    return LightMoments.stack(tables)


def bend_coefficients(
    vertices: np.ndarray | None,
    light_dir: np.ndarray,
    translucency: float,
    canopy: Canopy | None = None,
    azimuths: int = AZIMUTHS,
    elevations: int = ELEVATIONS,
    step: float = LEAN_STEP,
    moments: LightMoments | None = None,
) -> np.ndarray:
    """(elevations, azimuths, 5) float32: G_x, G_z, H_xx, H_xz, H_zz (see above) of the
    patch's vertices (core/patch.py VERTEX_DTYPE); with `canopy`, each vertex seen through the
    blades above its bent height (facing_lambert's `seen`). `moments`: bend_moments of the
    same, kept from an earlier light."""
    if moments is None:
        assert vertices is not None, "the vertices or their bend_moments"
        moments = bend_moments(vertices, canopy, azimuths, elevations, step)
    rest, xp, xm, zp, zm, pp, pm, mp, mm = moments.lit(light_dir, translucency)
    diagonal = pp - pm - mp + mm
    h2 = step * step
    out = [
        (xp - xm) / (2.0 * step),
        (zp - zm) / (2.0 * step),
        (xp - 2.0 * rest + xm) / h2,
        diagonal / (4.0 * h2),
        (zp - 2.0 * rest + zm) / h2,
    ]
    return np.stack(out, axis=-1).astype(np.float32)
