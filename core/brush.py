"""Painting the design maps (issue: map painting): a round brush with a falloff curve, stamped
along a stroke at a spacing, in four modes. Pure numpy on the rectangle under each dab; every
dab writes only that rectangle (DesignMaps announces it, so the GL mirror uploads only it). A
stroke keeps the original texels of the tiles it touched, so undoing it restores them exactly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from core.design_maps import LAYER_INDEX, LAYERS, DesignMaps
from core.trample import decode, encode

FALLOFFS = ("smooth", "linear", "constant", "sharp")
MODES = ("paint", "erase", "smooth", "fill")
TILE = 64  # texels per side of the tiles a stroke saves for undo
ALL_TYPES = -1  # density channel: every grass type's at once (a bare path clears them all)


@dataclass(frozen=True)
class Brush:
    size: float = 32.0  # diameter in texels
    strength: float = 0.5  # 0 … 1: how far one dab moves a texel towards the target
    value: tuple[float, ...] = (1.0,)  # the target, one value per channel painted
    falloff: str = "smooth"
    spacing: float = 0.25  # distance between dabs as a fraction of the size
    mode: str = "paint"

    def __post_init__(self) -> None:
        if not 1.0 <= self.size <= 4096.0:
            raise ValueError(f"brush size {self.size:g} is out of range; allowed 1 … 4096")
        if not 0.0 <= self.strength <= 1.0:
            raise ValueError(f"brush strength {self.strength:g} is out of range; allowed 0 … 1")
        if not 0.01 <= self.spacing <= 4.0:
            raise ValueError(f"brush spacing {self.spacing:g} is out of range; allowed 0.01 … 4")
        if self.falloff not in FALLOFFS:
            raise ValueError(f"unknown falloff {self.falloff!r}; use {', '.join(FALLOFFS)}")
        if self.mode not in MODES:
            raise ValueError(f"unknown brush mode {self.mode!r}; use {', '.join(MODES)}")


def falloff(kind: str, r: np.ndarray) -> np.ndarray:
    """Weight 1 at the centre (r = 0) down to 0 at the rim (r = 1), 0 outside."""
    r = np.clip(r, 0.0, None)
    inside = r < 1.0
    if kind == "smooth":
        w = 1.0 - r * r * (3.0 - 2.0 * r)
    elif kind == "linear":
        w = 1.0 - r
    elif kind == "constant":
        w = np.ones_like(r)
    elif kind == "sharp":
        w = (1.0 - r) ** 3
    else:
        raise ValueError(f"unknown falloff {kind!r}")
    return np.where(inside, w, 0.0).astype(np.float32)


def _dab(diameter: float, kind: str, fx: float, fy: float) -> np.ndarray:
    """Weights of one dab whose centre lies at (fx, fy) inside its first texel."""
    radius = diameter / 2.0
    n = math.ceil(diameter) + 1
    c = np.arange(n, dtype=np.float32) + 0.5
    dx = (c - (radius + fx))[None, :]
    dy = (c - (radius + fy))[:, None]
    return falloff(kind, np.sqrt(dx * dx + dy * dy) / max(radius, 1e-6))


@dataclass
class Stroke:
    """One stroke on one map (one channel of the density map, or all channels of another):
    one undo step. `add` stamps dabs along the path from the last point."""

    maps: DesignMaps
    layer: str
    brush: Brush
    channel: int | None = None  # density: which grass type
    # (rows, columns) weights 0 … 1 over the map: where a rule lets the brush take
    # (core/paint_rule.py); None: everywhere
    mask: np.ndarray | None = None
    # the trample map: the brush's lean turned the way the stroke moves on the ground, whose
    # texels are `texel` (x, z) world units
    follow: bool = False
    texel: tuple[float, float] = (1.0, 1.0)
    saved: dict[tuple[int, int], np.ndarray] = field(default_factory=dict)
    after: dict[tuple[int, int], np.ndarray] = field(default_factory=dict)
    dabs: int = 0
    _last: tuple[float, float] | None = None
    _carry: float = 0.0

    def __post_init__(self) -> None:
        index = LAYER_INDEX[self.layer]  # KeyError names the map
        if self.layer == "density" and self.channel == ALL_TYPES:
            self.channel = None  # every channel; one value is painted into all of them
        elif self.layer == "density" and self.channel is None:
            self.channel = 0  # the density map has a channel per grass type: the first
        channels = 1 if self.channel is not None else LAYERS[index].channels
        single = self.layer == "density" and len(self.brush.value) == 1
        if self.brush.mode == "paint" and len(self.brush.value) != channels and not single:
            raise ValueError(
                f"a brush for the {self.layer} map needs {channels} value(s), "
                f"got {len(self.brush.value)}"
            )
        if self.mask is not None and self.mask.shape != (self.maps.size[1], self.maps.size[0]):
            raise ValueError("a brush mask must have the maps' size")
        if self.brush.mode == "fill":
            w, h = self.maps.size
            self._save(0, 0, w, h)
            target = np.broadcast_to(np.asarray(self.brush.value, np.float32), (h, w, channels))
            if self.mask is not None:  # fill by rule: only where it holds
                current = self._read(0, 0, w, h)
                target = current + (target - current) * self.mask[..., None]
            self._write(0, 0, np.array(target))

    # -- stamping ----------------------------------------------------------------------------
    def add(self, x: float, y: float) -> None:
        """Extend the stroke to map position (x, y) in texels (column, row)."""
        if self.brush.mode == "fill":
            return
        if self._last is None:
            self._last = (x, y)
            if not self._follows:
                self._stamp(x, y)
            return
        step = max(self.brush.size * self.brush.spacing, 0.5)
        lx, ly = self._last
        length = math.hypot(x - lx, y - ly)
        if self._follows:
            if length == 0.0:
                return
            self._turn((x - lx) * self.texel[0], (y - ly) * self.texel[1])
            if self.dabs == 0:
                self._stamp(lx, ly)  # where it began, once the way it goes is known
        t = step - self._carry
        while t <= length:
            f = t / length
            self._stamp(lx + (x - lx) * f, ly + (y - ly) * f)
            t += step
        self._carry = length - (t - step)
        self._last = (x, y)

    @property
    def _follows(self) -> bool:
        return self.follow and self.brush.mode == "paint"

    def _turn(self, dx: float, dz: float) -> None:
        """The brush's lean, its amount kept, turned to the ground direction (dx, dz)."""
        amount = float(np.linalg.norm(decode(np.asarray(self.brush.value))))
        way = np.array([dx, dz]) / math.hypot(dx, dz)
        self.brush = replace(self.brush, value=tuple(float(v) for v in encode(way * amount)))

    def _stamp(self, x: float, y: float) -> None:
        b = self.brush
        radius = b.size / 2.0
        x0, y0 = math.floor(x - radius), math.floor(y - radius)
        weights = _dab(b.size, b.falloff, x - radius - x0, y - radius - y0) * b.strength
        h, w = weights.shape
        mw, mh = self.maps.size
        cx0, cy0 = max(x0, 0), max(y0, 0)
        cx1, cy1 = min(x0 + w, mw), min(y0 + h, mh)
        if cx1 <= cx0 or cy1 <= cy0:
            return
        weights = weights[cy0 - y0 : cy1 - y0, cx0 - x0 : cx1 - x0, None]
        if self.mask is not None:
            weights = weights * self.mask[cy0:cy1, cx0:cx1, None]
        self._save(cx0, cy0, cx1, cy1)
        current = self._read(cx0, cy0, cx1, cy1)
        target = self._target(current, cx0, cy0, cx1, cy1)
        self._write(cx0, cy0, current + (target - current) * weights)
        self.dabs += 1

    def _target(self, current, x0, y0, x1, y1) -> np.ndarray:
        mode = self.brush.mode
        if mode == "paint":
            return np.broadcast_to(np.asarray(self.brush.value, np.float32), current.shape)
        if mode == "erase":  # density: no grass; every other map back to its default
            if self.layer == "density":  # (no tint, neutral light, flat ground)
                return np.zeros_like(current)
            default = np.asarray(LAYERS[LAYER_INDEX[self.layer]].default, np.float32)
            default = default[[self.channel]] if self.channel is not None else default
            return np.broadcast_to(default[: current.shape[2]], current.shape)
        # smooth: towards the 3 × 3 mean of the texels, read with a one-texel border
        mw, mh = self.maps.size
        bx0, by0, bx1, by1 = max(x0 - 1, 0), max(y0 - 1, 0), min(x1 + 1, mw), min(y1 + 1, mh)
        region = np.pad(self._read(bx0, by0, bx1, by1), ((1, 1), (1, 1), (0, 0)), mode="edge")
        sums = np.zeros_like(region[1:-1, 1:-1])
        for dy in range(3):
            for dx in range(3):  # nine shifted views, each a whole-array add
                sums += region[dy : dy + region.shape[0] - 2, dx : dx + region.shape[1] - 2]
        mean = sums / 9.0
        return mean[y0 - by0 : y0 - by0 + (y1 - y0), x0 - bx0 : x0 - bx0 + (x1 - x0)]

    # -- map access --------------------------------------------------------------------------
    def _read(self, x0, y0, x1, y1) -> np.ndarray:
        layer = self.maps.layer(self.layer)
        if self.channel is not None:
            return np.array(layer[y0:y1, x0:x1, self.channel : self.channel + 1])
        return np.array(layer[y0:y1, x0:x1])

    def _write(self, x0, y0, values) -> None:
        self.maps.write(self.layer, x0, y0, values, channel=self.channel)

    def _save(self, x0, y0, x1, y1) -> None:
        """Keep the original texels of every tile the rectangle touches (once per stroke)."""
        layer = self.maps.layer(self.layer)
        for ty in range(y0 // TILE, (y1 - 1) // TILE + 1):
            for tx in range(x0 // TILE, (x1 - 1) // TILE + 1):
                if (tx, ty) not in self.saved:
                    tile = layer[ty * TILE : (ty + 1) * TILE, tx * TILE : (tx + 1) * TILE]
                    self.saved[(tx, ty)] = np.array(tile)

    # -- undo ------------------------------------------------------------------------------
    def finish(self) -> None:
        """Keep the painted texels of the touched tiles too, so the stroke can be redone."""
        layer = self.maps.layer(self.layer)
        self.after = {
            (tx, ty): np.array(layer[ty * TILE : (ty + 1) * TILE, tx * TILE : (tx + 1) * TILE])
            for tx, ty in self.saved
        }

    def undo(self) -> None:
        """Put back every texel the stroke changed."""
        self._put(self.saved)

    def redo(self) -> None:
        """Paint the stroke's texels again after an undo (needs `finish`)."""
        self._put(self.after)

    def _put(self, tiles: dict[tuple[int, int], np.ndarray]) -> None:
        for (tx, ty), tile in tiles.items():
            if self.channel is not None:
                self.maps.write(
                    self.layer, tx * TILE, ty * TILE, tile[..., self.channel], channel=self.channel
                )
            else:
                self.maps.write(self.layer, tx * TILE, ty * TILE, tile)

    @property
    def memory_bytes(self) -> int:
        """What the stroke keeps for undo and redo."""
        tiles = [*self.saved.values(), *self.after.values()]
        return sum(t.nbytes for t in tiles)

    @property
    def bounds(self) -> tuple[int, int, int, int] | None:
        """(x, y, width, height) in texels of the tiles the stroke touched."""
        if not self.saved:
            return None
        xs = [tx for tx, _ in self.saved]
        ys = [ty for _, ty in self.saved]
        w, h = self.maps.size
        x0, y0 = min(xs) * TILE, min(ys) * TILE
        return (x0, y0, min((max(xs) + 1) * TILE, w) - x0, min((max(ys) + 1) * TILE, h) - y0)
