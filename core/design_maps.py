"""The design-map stack (thesis 6.4, Fig. 6.7): maps projected along the terrain's up axis that
shape the grass locally — density (6.4.1), colour modulation with alpha (6.4.2, eq. 6.8),
ambient and diffuse light (6.4.3), height (6.4.4) and trampled grass (the lean a path or a
track gives the blades, core/trample.py).

All layers share one size and live in one float array (layers, rows, columns, 4), row = v along
z, column = u along x, so the GL mirror is one texture array and a renderer reaches every map
with the same uv (cells carry the config transform into this space: core/grid.py). Every edit
announces the layer and the dirty rectangle, so the mirror uploads only that rectangle.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from psygnal import Signal

from core.noise import fractal_noise


@dataclass(frozen=True)
class MapLayer:
    name: str
    channels: int
    default: tuple[float, float, float, float]
    description: str
    top: float = 1.0  # the values a project file may hold: 0 … top


LAYERS = (
    # one channel per grass type (thesis 6.4.5: several density maps), up to four types
    MapLayer("density", 4, (1.0, 1.0, 1.0, 1.0), "grass density per type, 0 bare … 1 full"),
    MapLayer("color", 4, (1.0, 1.0, 1.0, 0.0), "colour modulation: RGB and its weight A (eq. 6.8)"),
    MapLayer("ambient", 3, (1.0, 1.0, 1.0, 0.0), "ambient light × scene occlusion (eq. 6.9)", 4.0),
    MapLayer("diffuse", 3, (1.0, 1.0, 1.0, 0.0), "diffuse light, e.g. shadows (eq. 6.9)", 4.0),
    MapLayer("height", 1, (0.0, 0.0, 0.0, 0.0), "terrain height, 0 … 1 times the height scale"),
    # trampled grass (core/trample.py): the blades' lean (x, z), 0.5 + 0.5 · lean / MAX_LEAN
    MapLayer("trample", 2, (0.5, 0.5, 0.0, 0.0), "trampled grass: the blades' lean, 0.5 none"),
)
# the layers a project file written before trampled grass holds (core/project_file.py)
FIRST_LAYERS = 5
LAYER_INDEX = {layer.name: i for i, layer in enumerate(LAYERS)}
MAX_SIZE = 8192

Rect = tuple[int, int, int, int]  # x (column), y (row), width, height


def union(a: Rect | None, b: Rect) -> Rect:
    """The smallest rectangle holding both (x, y, width, height)."""
    if a is None:
        return b
    x0, y0 = min(a[0], b[0]), min(a[1], b[1])
    x1, y1 = max(a[0] + a[2], b[0] + b[2]), max(a[1] + a[3], b[1] + b[3])
    return (x0, y0, x1 - x0, y1 - y0)


class DesignMaps:
    """Qt-free model of the stack. `changed(layer_name, rect)` follows every edit."""

    changed = Signal(str, tuple)

    def __init__(self, width: int = 256, height: int | None = None) -> None:
        height = width if height is None else height
        for label, value in (("width", width), ("height", height)):
            if not 1 <= value <= MAX_SIZE:
                raise ValueError(
                    f"design map {label} = {value} is out of range; allowed 1 … {MAX_SIZE}"
                )
        self.stack = np.empty((len(LAYERS), height, width, 4), np.float32)
        for i, layer in enumerate(LAYERS):
            self.stack[i] = layer.default

    @classmethod
    def from_stack(cls, stack: np.ndarray, copy: bool = True) -> DesignMaps:
        """Maps holding a copy of `stack` (layers, rows, columns, 4); `copy=False` adopts a
        float32 array read from a file (no second full copy in memory)."""
        stack = np.asarray(stack, np.float32)
        if stack.ndim != 4 or stack.shape[0] != len(LAYERS) or stack.shape[3] != 4:
            raise ValueError(
                f"a design-map stack must be ({len(LAYERS)}, rows, columns, 4), got {stack.shape}"
            )
        if not np.all(np.isfinite(stack)):
            raise ValueError("a design-map stack must hold finite numbers")
        if not copy and stack.flags.c_contiguous and stack.flags.writeable:
            maps = cls.__new__(cls)
            maps.stack = stack
            return maps
        maps = cls(stack.shape[2], stack.shape[1])
        maps.stack[:] = stack
        return maps

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) in texels."""
        return self.stack.shape[2], self.stack.shape[1]

    def layer(self, name: str) -> np.ndarray:
        """A read-only view (rows, columns, channels) of one map."""
        i = _index(name)
        view = self.stack[i, :, :, : LAYERS[i].channels]
        view.flags.writeable = False
        return view

    def write(
        self, name: str, x: int, y: int, values: np.ndarray, channel: int | None = None
    ) -> Rect:
        """Replace a rectangle of one map from (column x, row y) with `values` (rows, columns[,
        channels]); the part outside the map is dropped. Returns the rectangle written.

        The density map has a channel per grass type: (rows, columns) values go to `channel`
        (the first type's unless given)."""
        i = _index(name)
        channels = LAYERS[i].channels
        values = np.asarray(values, np.float32)
        if values.ndim == 2:
            values = values[..., None]
        first = 0
        if name == "density" and values.ndim == 3 and values.shape[2] == 1:
            first = 0 if channel is None else channel
            if not 0 <= first < channels:
                raise ValueError(
                    f"density channel {first} out of range; grass types 0 … {channels - 1}"
                )
            channels = 1
        if values.ndim != 3 or values.shape[2] != channels:
            raise ValueError(
                f"{name} map values must be (rows, columns, {channels}), got {values.shape}"
            )
        if not np.all(np.isfinite(values)):
            raise ValueError(f"{name} map values must be finite numbers")
        w, h = self.size
        x0, y0 = max(x, 0), max(y, 0)
        x1, y1 = min(x + values.shape[1], w), min(y + values.shape[0], h)
        if x1 <= x0 or y1 <= y0:
            return (x0, y0, 0, 0)
        self.stack[i, y0:y1, x0:x1, first : first + channels] = values[
            y0 - y : y1 - y, x0 - x : x1 - x
        ]
        rect = (x0, y0, x1 - x0, y1 - y0)
        self.changed.emit(name, rect)
        return rect

    def fill(self, name: str, value) -> None:
        """Set a whole map to one value (a scalar or one per channel)."""
        channels = LAYERS[_index(name)].channels
        w, h = self.size
        values = np.broadcast_to(np.asarray(value, np.float32), (h, w, channels))
        self.write(name, 0, 0, values)

    @classmethod
    def procedural(cls, width: int = 256, seed: int = 0, tint: float = 0.25) -> DesignMaps:
        """Default maps: full density, even light and a low-alpha colour modulation from noise
        that breaks the remaining repetition across patches (thesis 6.4.2)."""
        maps = cls(width)
        c = (np.arange(width) + 0.5) / width
        u, v = np.meshgrid(c, c, indexing="xy")  # rows along v
        n = np.clip(fractal_noise(u, v, period=6, seed=seed, octaves=3) * 1.2 + 0.5, 0.0, 1.0)
        dry = np.array([0.60, 0.56, 0.26], np.float32)
        lush = np.array([0.22, 0.42, 0.12], np.float32)
        rgb = lush + (dry - lush) * n[..., None]
        alpha = tint * np.abs(n - 0.5)[..., None] * 2.0
        maps.write("color", 0, 0, np.concatenate([rgb, alpha], axis=-1))
        return maps


def _index(name: str) -> int:
    try:
        return LAYER_INDEX[name]
    except KeyError:
        raise KeyError(f"unknown design map {name!r}; maps: {', '.join(LAYER_INDEX)}") from None
