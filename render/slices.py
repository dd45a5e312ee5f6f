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


@dataclass
class LayerTextures:
    color: moderngl.Texture
    normal_threshold: moderngl.Texture  # rgb = normal · 0.5 + 0.5, a = density threshold
    count: int  # slices stacked along v

    def release(self) -> None:
        self.color.release()
        self.normal_threshold.release()


def slice_levels(height: int, width: int) -> int:
    return int(np.log2(min(height, width))) + 1


def upload_layers(
    ctx: moderngl.Context, layers: SliceLayers, alpha_ref: float = 0.5, repeat_v: bool = False
) -> LayerTextures:
    n, h, w = layers.threshold.shape
    count = slice_levels(h, w)
    color_levels = stacked_slice_mips(layers.color, count, alpha_ref)
    data = np.concatenate([layers.normal * 0.5 + 0.5, layers.threshold[..., None]], axis=-1)
    data_levels = None
    for i in range(n):
        alphas = mean_alpha_chain(layers.color[i, ..., 3], count)
        chain = weighted_chain(data[i], alphas)
        data_levels = (
            chain
            if data_levels is None
            else [np.concatenate([a, b], axis=0) for a, b in zip(data_levels, chain, strict=True)]
        )
    color = texture_with_mips(ctx, color_levels)
    normal_threshold = texture_with_mips(ctx, data_levels)
    for tex in (color, normal_threshold):
        tex.repeat_x = True  # slices tile along u like the patch
        tex.repeat_y = repeat_v  # only the top slice tiles along v
    return LayerTextures(color, normal_threshold, n)


@dataclass
class SliceTextures:
    x: LayerTextures
    z: LayerTextures
    top: LayerTextures
    height: float

    @classmethod
    def upload(cls, ctx: moderngl.Context, sliced: SlicedPatch) -> SliceTextures:
        return cls(
            upload_layers(ctx, sliced.x),
            upload_layers(ctx, sliced.z),
            upload_layers(ctx, sliced.top, repeat_v=True),
            sliced.height,
        )

    def release(self) -> None:
        for layers in (self.x, self.z, self.top):
            layers.release()
