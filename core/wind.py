"""One wind field for the whole terrain, and the bend it gives a blade (issue: wind).

The field follows Habel 2007 (seeds/001, "texture-based animation"): a noise map that covers the
whole terrain, translated each frame in the wind's direction, of two Perlin functions — a low
frequency of high amplitude for gusts and a high frequency of low amplitude for turbulence. Its
value at a point is the horizontal displacement of a blade's tip there, as a fraction of the
blade's length (dimensionless), so that short grass moves less than tall grass.

A blade is the quadratic Bézier curve of its trajectory (thesis eq. 4.1: p(t) = b·t + g·t² has
the control points 0, b / 2 and b + g). The wind moves its tip, and its middle control point a
quarter as far, and the curve is then scaled about its root back to its length at rest (after
Jahrmann & Wimmer's length correction): the root stays, the blade bends and does not stretch,
and its tip sinks as it leans.

shaders/_wind.glsl computes the same field and bend on the GPU; the numpy here is what the
tests check (and what a test compares the GPU's frames against).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from functools import lru_cache
from typing import Any

import numpy as np

from core.noise import perlin2d

NOISE_RESOLUTION = 64  # texels per side of the tileable noise map
NOISE_FEATURES = 4  # Perlin lattice cells across the map: a feature is a quarter of a tile
MAX_LEAN = 0.9  # the largest tip displacement, as a fraction of the blade's length
MIDDLE_SHARE = 0.25  # how far the middle control point moves with the tip
TURBULENCE_DRIFT = 0.6  # turbulence travels at this share of the gusts' speed, turned 30°

# (field, low, high, label): the ranges a project file and the Wind dock accept
RANGES = {
    "direction": (-360.0, 360.0),
    "speed": (0.0, 30.0),
    "gust_strength": (0.0, 0.9),
    "gust_scale": (0.5, 200.0),
    "turbulence_strength": (0.0, 0.5),
    "turbulence_scale": (0.1, 50.0),
    "blade_reach": (1.0, 2.0),
}


@dataclass(frozen=True)
class Wind:
    """The wind over the terrain. direction: degrees, the way the wind blows, 0 = +x, 90 = +z;
    speed: world units a second the gusts travel; gust_strength / turbulence_strength: the tip
    displacement they give, as a fraction of a blade's length; gust_scale / turbulence_scale:
    the size of a gust and of a turbulence eddy in world units; blade_reach: while the wind
    blows, the representation after the blades begins this many times as far out as the LOD
    levels say, and the blades run on a little past it (core/lod.py
    LodConfig.with_blade_reach): the slices hold the grass at rest and miss the bent blades'
    light most where they begin, nearest the eye."""

    enabled: bool = False
    direction: float = 30.0
    speed: float = 2.0
    gust_strength: float = 0.35
    gust_scale: float = 8.0
    turbulence_strength: float = 0.08
    turbulence_scale: float = 1.5
    blade_reach: float = 1.4

    def __post_init__(self) -> None:
        if not isinstance(self.enabled, bool):
            raise ValueError("wind: enabled must be true or false")
        for name, (low, high) in RANGES.items():
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValueError(f"wind: {name} must be a number")
            if not math.isfinite(value) or not low <= value <= high:
                raise ValueError(f"wind: {name} must lie in {low:g} … {high:g}, not {value!r}")

    def replace(self, **changes: Any) -> Wind:
        return replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Wind:
        unknown = set(data) - set(cls.__dataclass_fields__)
        if unknown:
            raise ValueError(f"wind: unknown field {sorted(unknown)[0]!r}")
        return cls(**data)

    @property
    def largest_lean(self) -> float:
        """The most the wind displaces a tip (a fraction of the blade's length; 0 when it is
        off): the gusts' full strength and the turbulence's two components at their largest
        together (lean's noise channels lie in -1 … 1)."""
        if not self.enabled:
            return 0.0
        return min(MAX_LEAN, self.gust_strength + math.sqrt(2.0) * self.turbulence_strength)

    @property
    def reach(self) -> float:
        """The blade reach the frames draw with: blade_reach while the wind blows, else 1."""
        return self.blade_reach if self.enabled else 1.0

    @property
    def heading(self) -> np.ndarray:
        """Unit vector (x, z) the wind blows towards."""
        a = math.radians(self.direction)
        return np.array([math.cos(a), math.sin(a)])

    def offsets(self, time: float) -> tuple[np.ndarray, np.ndarray]:
        """How far the gust and turbulence patterns have travelled at `time` (x, z)."""
        h = self.heading
        turned = np.array([h[0] * 0.8660254 - h[1] * 0.5, h[0] * 0.5 + h[1] * 0.8660254])
        return h * self.speed * time, turned * self.speed * TURBULENCE_DRIFT * time


# The Wind dock's presets: how the gusts and the turbulence move (their speed, strength and
# size); the direction, the on/off and the blade reach stay as they are. "gusty" is the
# default wind.
MOTION = ("speed", "gust_strength", "gust_scale", "turbulence_strength", "turbulence_scale")
PRESETS = {
    "light breeze": dict(zip(MOTION, (1.0, 0.15, 10.0, 0.04, 2.0), strict=True)),
    "gusty": {name: getattr(Wind(), name) for name in MOTION},
    "storm": dict(zip(MOTION, (6.0, 0.7, 12.0, 0.2, 1.0), strict=True)),
}


def preset_of(wind: Wind) -> str | None:
    """The name of the preset whose values `wind` has, or None."""
    for name, values in PRESETS.items():
        if all(getattr(wind, field) == value for field, value in values.items()):
            return name
    return None


@lru_cache(maxsize=1)
def noise_map() -> np.ndarray:
    """(NOISE_RESOLUTION, NOISE_RESOLUTION, 3) float32, indexed [row = z, column = x]: channel 0
    the gusts' noise, 1 and 2 the turbulence's two components, each in -1 … 1, tiling."""
    c = (np.arange(NOISE_RESOLUTION) + 0.5) / NOISE_RESOLUTION
    x, z = np.meshgrid(c, c, indexing="xy")
    out = np.empty((NOISE_RESOLUTION, NOISE_RESOLUTION, 3), np.float32)
    for channel, seed in enumerate((101, 202, 303)):
        n = perlin2d(x, z, NOISE_FEATURES, seed)
        out[..., channel] = n / max(float(np.abs(n).max()), 1e-9)
    out.flags.writeable = False
    return out


def sample_noise(uv: np.ndarray) -> np.ndarray:
    """The noise map at texture coordinates uv (..., 2) as GL samples it: bilinear, repeating,
    texel centres at (i + ½) / resolution. Returns (..., 3)."""
    tex = noise_map()
    n = NOISE_RESOLUTION
    p = np.asarray(uv, np.float64) * n - 0.5
    i0 = np.floor(p).astype(np.int64)
    f = p - i0
    x0, z0 = i0[..., 0] % n, i0[..., 1] % n
    x1, z1 = (x0 + 1) % n, (z0 + 1) % n
    fx, fz = f[..., 0:1], f[..., 1:2]
    top = tex[z0, x0] * (1 - fx) + tex[z0, x1] * fx
    bottom = tex[z1, x0] * (1 - fx) + tex[z1, x1] * fx
    return top * (1 - fz) + bottom * fz


def lean(wind: Wind, xz: np.ndarray, time: float) -> np.ndarray:
    """The tip displacement (x, z) at world points xz (..., 2) and `time` seconds, as a
    fraction of a blade's length: gusts along the wind's heading, turbulence in any direction.
    Zero everywhere when the wind is off."""
    return limit(_gusts(wind, xz, time))


def grass_lean(wind: Wind, xz: np.ndarray, time: float, trampled: np.ndarray) -> np.ndarray:
    """What the grass leans by at world points xz: the wind's lean and the trampled one
    (core/trample.py) added, no further than MAX_LEAN (shaders/_wind.glsl grass_lean)."""
    return limit(_gusts(wind, xz, time) + np.asarray(trampled, np.float64))


def limit(lean_xz: np.ndarray) -> np.ndarray:
    """Tip displacements no longer than MAX_LEAN."""
    size = np.linalg.norm(lean_xz, axis=-1, keepdims=True)
    return lean_xz * np.minimum(1.0, MAX_LEAN / np.maximum(size, 1e-9))


def _gusts(wind: Wind, xz: np.ndarray, time: float) -> np.ndarray:
    xz = np.asarray(xz, np.float64)
    if not wind.enabled:
        return np.zeros(xz.shape)
    gust_shift, turbulence_shift = wind.offsets(time)
    tile = float(NOISE_FEATURES)
    gust = sample_noise((xz - gust_shift) / (wind.gust_scale * tile))[..., 0]
    eddy = sample_noise((xz - turbulence_shift) / (wind.turbulence_scale * tile))[..., 1:3]
    envelope = 0.5 * (1.0 + gust)  # 0 … 1: calm between gusts, full strength in one
    out = wind.heading * (wind.gust_strength * envelope)[..., None]
    return out + wind.turbulence_strength * eddy


# Gauss-Legendre nodes and weights on 0 … 1: the length of a quadratic Bézier curve
_GL_T = np.array([0.5 - 0.4305681558, 0.5 - 0.1699905218, 0.5 + 0.1699905218, 0.5 + 0.4305681558])
_GL_W = np.array([0.1739274226, 0.3260725774, 0.3260725774, 0.1739274226])


def curve_length(c1: np.ndarray, c2: np.ndarray) -> np.ndarray:
    """Length of the quadratic Bézier curves from the origin through control points c1 and c2
    (..., 3): the integral of |B'(t)| = |2 c1 (1 - 2t) + 2 c2 t| (four-point Gauss-Legendre)."""
    c1 = np.asarray(c1, np.float64)[..., None, :]
    c2 = np.asarray(c2, np.float64)[..., None, :]
    t = _GL_T[:, None]
    speed = np.linalg.norm(2.0 * c1 * (1.0 - 2.0 * t) + 2.0 * c2 * t, axis=-1)
    return (speed * _GL_W).sum(axis=-1)


def curve_point(c1: np.ndarray, c2: np.ndarray, t: np.ndarray) -> np.ndarray:
    """B(t) = 2 t (1 - t) c1 + t² c2 (the root at the origin)."""
    t = np.asarray(t, np.float64)[..., None]
    return 2.0 * t * (1.0 - t) * np.asarray(c1) + t * t * np.asarray(c2)


def bend(c1: np.ndarray, c2: np.ndarray, lean_xz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The control points of blades bent by a tip displacement `lean_xz` (..., 2), a fraction
    of each blade's length: the tip moves by it, the middle control point by MIDDLE_SHARE of
    it, and the curve is scaled about its root back to its length at rest."""
    c1 = np.asarray(c1, np.float64)
    c2 = np.asarray(c2, np.float64)
    rest = curve_length(c1, c2)
    move = np.zeros(c2.shape)
    move[..., 0] = lean_xz[..., 0]
    move[..., 2] = lean_xz[..., 1]
    move = move * rest[..., None]
    b1 = c1 + MIDDLE_SHARE * move
    b2 = c2 + move
    scale = rest / np.maximum(curve_length(b1, b2), 1e-12)
    return b1 * scale[..., None], b2 * scale[..., None]


def curve_tangent(c1: np.ndarray, c2: np.ndarray, t: np.ndarray) -> np.ndarray:
    """B'(t) = 2 (1 - 2t) c1 + 2t c2."""
    t = np.asarray(t, np.float64)[..., None]
    return 2.0 * (1.0 - 2.0 * t) * np.asarray(c1) + 2.0 * t * np.asarray(c2)


def turn(v: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """v (..., 3) turned by the rotation that takes unit a to unit b (Rodrigues), as
    shaders/_wind.glsl's turn."""
    k = np.cross(a, b)
    s = np.linalg.norm(k, axis=-1, keepdims=True)
    c = (a * b).sum(axis=-1, keepdims=True)
    k = k / np.maximum(s, 1e-12)
    out = v * c + np.cross(k, v) * s + k * (k * v).sum(axis=-1, keepdims=True) * (1.0 - c)
    return np.where(s < 1e-6, v, out)


def bend_vertices(vertices: np.ndarray, lean_xz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Positions and normals of a patch's vertices (core/patch.py VERTEX_DTYPE) with every
    blade bent by the tip displacement `lean_xz` ((2,) or one per vertex), as the geometry
    shader bends them: each vertex keeps its offset across the blade from the curve, its
    normal turns with the curve's tangent."""
    c1 = vertices["ctrl1"].astype(np.float64)
    c2 = vertices["ctrl2"].astype(np.float64)
    t = vertices["uv"][:, 1].astype(np.float64)
    root = np.zeros((len(vertices), 3))
    root[:, [0, 2]] = vertices["root"]
    across = vertices["position"] - root - curve_point(c1, c2, t)
    before = curve_tangent(c1, c2, t)
    b1, b2 = bend(c1, c2, np.broadcast_to(np.asarray(lean_xz, np.float64), (len(vertices), 2)))
    positions = root + curve_point(b1, b2, t) + across
    after = curve_tangent(b1, b2, t)

    def unit(v: np.ndarray) -> np.ndarray:
        return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-12)

    normals = turn(vertices["normal"].astype(np.float64), unit(before), unit(after))
    return positions, normals
