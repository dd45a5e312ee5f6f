"""GPU textures of a converted patch: each layer's slices stacked along v in one 2D texture,
with mip levels computed per slice in core/mipmaps.py and written explicitly (thesis 4.2.2-4.2.3).

Levels stop at log2(slice height), so a level never mixes two slices; shaders clamp v inside the
slice they sample.
"""

from __future__ import annotations

from dataclasses import dataclass

import moderngl
import numpy as np

from core.mipmaps import mean_alpha_chain, stacked_slice_mips, weighted_chain
from render.conversion import SlicedPatch, SliceLayers
from render.textures import texture_with_mips

# The axis each slice family looks along: x-slices 0, top slice 1 (y), z-slices 2. Blades are
# two-sided, so a normal and its negation light alike (shaders turn it to the viewer): the data
# texture keeps the normal turned to +axis and stores only its two other components
# (shaders/_slices.glsl rebuilds the third), which frees a channel for the height.
KEPT_COMPONENTS = {0: (1, 2), 1: (0, 2), 2: (0, 1)}


@dataclass
class LayerTextures:
    color: moderngl.Texture
    data: moderngl.Texture  # rg = two normal components · 0.5 + 0.5, b = height, a = threshold
    count: int  # slices stacked along v

    def release(self) -> None:
        self.color.release()
        self.data.release()


def pack_data(layers: SliceLayers, axis: int, height: float) -> np.ndarray:
    """(n, h, w, 4) floats in 0 … 1: the normal's two kept components, height / patch height and
    the density threshold."""
    n = layers.normal * np.where(layers.normal[..., axis : axis + 1] < 0, -1.0, 1.0)
    kept = n[..., list(KEPT_COMPONENTS[axis])] * 0.5 + 0.5
    h = np.clip(layers.height / max(height, 1e-6), 0.0, 1.0)
    return np.concatenate([kept, h[..., None], layers.threshold[..., None]], axis=-1)


def slice_levels(height: int, width: int) -> int:
    return int(np.log2(min(height, width))) + 1


@dataclass
class LayerLevels:
    """One slice family's mip chains, computed without GL (safe on a worker thread)."""

    color: list[np.ndarray]
    data: list[np.ndarray]
    count: int  # slices stacked along v
    repeat_v: bool


def layer_levels(
    layers: SliceLayers, axis: int, height: float, alpha_ref: float = 0.5, repeat_v: bool = False
) -> LayerLevels:
    n, h, w = layers.threshold.shape
    count = slice_levels(h, w)
    color_levels = stacked_slice_mips(layers.color, count, alpha_ref)
    data = pack_data(layers, axis, height)
    chains = [
        weighted_chain(data[i], mean_alpha_chain(layers.color[i, ..., 3], count)) for i in range(n)
    ]
    data_levels = [np.concatenate(level, axis=0) for level in zip(*chains, strict=True)]
    return LayerLevels(color_levels, data_levels, n, repeat_v)


def upload_levels(ctx: moderngl.Context, levels: LayerLevels) -> LayerTextures:
    color = texture_with_mips(ctx, levels.color)
    data = texture_with_mips(ctx, levels.data)
    for tex in (color, data):
        tex.repeat_x = True  # slices tile along u like the patch
        tex.repeat_y = levels.repeat_v  # only the top slice tiles along v
    return LayerTextures(color, data, levels.count)


@dataclass
class SliceLevels:
    """Every mip level of a converted patch, ready to upload (thesis 4.2.2-4.2.3)."""

    x: LayerLevels
    z: LayerLevels
    top: LayerLevels
    height: float

    @classmethod
    def compute(cls, sliced: SlicedPatch) -> SliceLevels:
        h = sliced.height
        return cls(
            layer_levels(sliced.x, axis=0, height=h),
            layer_levels(sliced.z, axis=2, height=h),
            layer_levels(sliced.top, axis=1, height=h, repeat_v=True),
            h,
        )


@dataclass
class SliceTextures:
    x: LayerTextures
    z: LayerTextures
    top: LayerTextures
    height: float

    @classmethod
    def upload(cls, ctx: moderngl.Context, sliced: SlicedPatch) -> SliceTextures:
        return cls.from_levels(ctx, SliceLevels.compute(sliced))

    @classmethod
    def from_levels(cls, ctx: moderngl.Context, levels: SliceLevels) -> SliceTextures:
        return cls(
            upload_levels(ctx, levels.x),
            upload_levels(ctx, levels.z),
            upload_levels(ctx, levels.top),
            levels.height,
        )

    def release(self) -> None:
        for layers in (self.x, self.z, self.top):
            layers.release()
