"""Procedural geometry-based grass patch (thesis 4.1-4.1.2), on arrays.

Every blade is a quad strip sampled along the trajectory p = b·t + g·t² (eq. 4.1) at equal steps
of t; its normals are orthogonal to the derivative v = b + 2·g·t (eq. 4.2). The patch is the unit
square of ground in x and z, y up. Roots lie inside the square, tips may reach outside.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.density import clustered_thresholds, uniform_thresholds
from core.params import PatchParams
from core.segments import chord_colors, level_widths

# Vertex layout shared with render/geometry.py and shaders/geometry.glsl.
VERTEX_DTYPE = np.dtype(
    [
        ("position", np.float32, 3),
        ("normal", np.float32, 3),
        ("uv", np.float32, 2),
        ("color", np.float32, 3),
        ("root", np.float32, 2),
        ("threshold", np.float32),
        # the blade's trajectory as a quadratic Bézier curve from its root: the control points
        # b / 2 and b + g of eq. 4.1 (in the patch's units, fitted in height like the vertices);
        # the wind bends the curve (core/wind.py, shaders/_wind.glsl)
        ("ctrl1", np.float32, 3),
        ("ctrl2", np.float32, 3),
        # the colour on the chord this vertex slides onto where fewer segments draw its blade
        # (core/segments.py): the colour it takes on as it leaves
        ("chord_color", np.float32, 3),
        # its blade's width at segment levels 1 … 4 over the full strip's (core/segments.py)
        ("level_width", np.float32, 4),
    ]
)


@dataclass(frozen=True, eq=False)
class GrassPatch:
    """The generated geometry of one patch: interleaved vertices and triangle indices. Patches
    compare by identity (they hold arrays)."""

    params: PatchParams
    vertices: np.ndarray  # VERTEX_DTYPE, (blades * (subdivisions + 1) * 2,)
    indices: np.ndarray  # uint32, (blades * subdivisions * 6,)
    roots: np.ndarray  # (blades, 2) float32, x and z of each blade root
    thresholds: np.ndarray  # (blades,) float32 on (0, 1]
    height: float  # tallest tip above the ground

    @property
    def blade_count(self) -> int:
        return int(self.roots.shape[0])


def generate_patch(params: PatchParams) -> GrassPatch:
    """Generate the patch for `params`; the same parameters always give the same patch."""
    rng = np.random.default_rng(params.seed)
    n = params.blade_count
    s = params.subdivisions

    roots = rng.random((n, 2))
    length = rng.uniform(params.length_min, params.length_max, n)
    width = rng.uniform(params.width_min, params.width_max, n)
    tilt = np.radians(rng.uniform(params.tilt_min, params.tilt_max, n))
    rotation = rng.uniform(0.0, 2.0 * np.pi, n)
    blade_mod = rng.random(n)
    vertex_mod = rng.random((n, s + 1))

    if params.clustered:
        thresholds = clustered_thresholds(roots, params.cluster_sigma, rng, params.seed)
    else:
        thresholds = uniform_thresholds(n, rng)

    # Trajectory (eq. 4.1): b carries length, tilt and rotation; g is gravity along -y.
    facing = np.stack([np.cos(rotation), np.zeros(n), np.sin(rotation)], axis=1)
    up = np.array([0.0, 1.0, 0.0])
    b = length[:, None] * (np.sin(tilt)[:, None] * facing + np.cos(tilt)[:, None] * up)
    g = -params.bending * length[:, None] * up
    t = np.linspace(0.0, 1.0, s + 1)
    p = b[:, None, :] * t[None, :, None] + g[:, None, :] * (t * t)[None, :, None]
    v = b[:, None, :] + 2.0 * g[:, None, :] * t[None, :, None]  # eq. 4.2

    # Fit into the patch's bounding box: a tip above patch_height is scaled down in y only.
    p[..., 1] = np.maximum(p[..., 1], 0.0)
    ctrl1, ctrl2 = 0.5 * b, b + g  # B(t) = 2t(1 - t) ctrl1 + t² ctrl2 = b t + g t²
    tallest = float(p[..., 1].max()) if n else 0.0
    if tallest > params.patch_height:
        fit = params.patch_height / tallest
        p[..., 1] *= fit
        v[..., 1] *= fit
        ctrl1[:, 1] *= fit
        ctrl2[:, 1] *= fit
        tallest = params.patch_height

    # Side vector is horizontal and perpendicular to the blade's facing; the normal is
    # side × v, hence orthogonal to the derivative v and to the strip.
    side = np.stack([-np.sin(rotation), np.zeros(n), np.cos(rotation)], axis=1)
    side_b = np.broadcast_to(side[:, None, :], v.shape)
    normal = np.cross(side_b, v)
    norm = np.linalg.norm(normal, axis=-1, keepdims=True)
    # A vertical blade bent straight down has v = 0 at one sample: take the facing there.
    fallback = np.broadcast_to(facing[:, None, :], v.shape)
    normal = np.where(norm > 1e-9, normal / np.maximum(norm, 1e-9), fallback)

    half = 0.5 * width[:, None, None] * side[:, None, :]
    root3 = np.stack([roots[:, 0], np.zeros(n), roots[:, 1]], axis=1)[:, None, :]
    centre = root3 + p  # (n, s+1, 3)

    verts = np.empty((n, s + 1, 2), dtype=VERTEX_DTYPE)
    verts["position"][:, :, 0] = centre - half
    verts["position"][:, :, 1] = centre + half
    verts["normal"] = normal[:, :, None, :]
    verts["uv"][..., 0] = np.array([0.0, 1.0])[None, None, :]
    verts["uv"][..., 1] = t[None, :, None]
    colors = _vertex_colors(params, blade_mod, vertex_mod, t)
    verts["color"] = colors[:, :, None, :]
    verts["chord_color"] = chord_colors(colors)[:, :, None, :]
    verts["level_width"] = level_widths(centre)[:, None, None, :]
    verts["root"] = roots[:, None, None, :]
    verts["threshold"] = thresholds[:, None, None]
    verts["ctrl1"] = ctrl1[:, None, None, :]
    verts["ctrl2"] = ctrl2[:, None, None, :]

    return GrassPatch(
        params=params,
        vertices=verts.reshape(-1),
        indices=_strip_indices(n, s),
        roots=roots.astype(np.float32),
        thresholds=thresholds,
        height=max(tallest, 1e-3),
    )


def _vertex_colors(
    params: PatchParams, blade_mod: np.ndarray, vertex_mod: np.ndarray, t: np.ndarray
) -> np.ndarray:
    """Per-vertex colour: root→tip gradient, per-blade modulation toward a dry colour and in
    brightness (thesis 4.1.2), and a per-vertex light modulation interpolated along the blade."""
    root = np.asarray(params.root_color)
    tip = np.asarray(params.tip_color)
    dry = np.asarray(params.dry_color)
    base = root[None, :] + (tip - root)[None, :] * np.sqrt(t)[:, None]  # (s+1, 3)
    dryness = params.blade_color_variation * blade_mod**2  # most blades fresh, a few dry
    tinted = base[None, :, :] * (1 - dryness)[:, None, None] + dry * dryness[:, None, None]
    brightness = 1.0 + params.blade_color_variation * 0.5 * (blade_mod - 0.5)
    light = 1.0 + params.vertex_light_variation * (vertex_mod - 0.5)  # (n, s+1)
    rgb = tinted * (brightness[:, None] * light)[:, :, None]
    return np.clip(rgb, 0.0, 1.0).astype(np.float32)


def _strip_indices(blades: int, subdivisions: int) -> np.ndarray:
    """Two triangles per quad of each blade's strip; vertices are (segment, side) ordered."""
    per_blade = (subdivisions + 1) * 2
    k = np.arange(subdivisions) * 2
    quad = np.stack([k, k + 1, k + 2, k + 2, k + 1, k + 3], axis=1).reshape(-1)
    base = (np.arange(blades) * per_blade)[:, None]
    return (base + quad[None, :]).astype(np.uint32).reshape(-1)


def blade_fill(v) -> np.ndarray:
    """The share of a blade's width its texture's mask keeps at v (0 at the root, 1 at the
    tip): the blade narrows to a pointed tip (blade_texture)."""
    return np.clip(1.0 - np.asarray(v, np.float64) ** 3, 0.0, 1.0) ** 0.6


def blade_texture(size: tuple[int, int] = (32, 256), seed: int = 0) -> np.ndarray:
    """A procedural blade texture, RGBA uint8 of shape (height, width, 4).

    u runs across the blade, v from root (row 0) to tip. RGB is a light modulation around white
    with fibres along the blade; alpha is a mask that narrows the blade to a pointed tip.
    """
    w, h = size
    rng = np.random.default_rng(seed)
    u = (np.arange(w) + 0.5) / w
    v = (np.arange(h) + 0.5) / h
    uu, vv = np.meshgrid(u, v)
    half_width = 0.5 * blade_fill(vv)  # pointed tip
    edge = half_width - np.abs(uu - 0.5)
    alpha = np.clip(edge * w * 0.75 + 0.5, 0.0, 1.0)
    fibres = 0.85 + 0.15 * np.cos(uu * np.pi * 2.0 * 3.0 + rng.uniform(0, 6.28)) ** 2
    midrib = 1.0 + 0.12 * np.exp(-(((uu - 0.5) / 0.06) ** 2))
    shade = np.clip(fibres * midrib, 0.0, 1.0)
    rgba = np.empty((h, w, 4), dtype=np.uint8)
    rgba[..., 0:3] = (shade[..., None] * 255).astype(np.uint8)
    rgba[..., 3] = (alpha * 255).astype(np.uint8)
    return rgba
