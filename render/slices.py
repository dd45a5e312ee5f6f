"""GPU textures of a converted patch: each layer's slices stacked along v in one 2D texture,
with mip levels computed per slice in core/mipmaps.py and written explicitly (thesis 4.2.2-4.2.3).

Levels stop at log2(slice height), so a level never mixes two slices; shaders clamp v inside the
slice they sample.
"""

from __future__ import annotations

from dataclasses import dataclass

import moderngl
import numba
import numpy as np

from core.canopy import Canopy
from core.mipmaps import row_depths, stacked_slice_mips, threshold_spread, weighted_chain
from render.conversion import SlicedPatch, SliceLayers
from render.textures import texture_with_mips

# Blades are two-sided: a normal and its negation light alike once a shader turns it to the
# viewer. The data textures keep every normal turned up (n.y >= 0) before the mips average them,
# so two faces of similar blades do not cancel out. Averaging shortens the normal, and the
# shortened normal is kept: its length says how many ways the texel's blades face. The lambert
# term of a short average is not the average of its blades' (each blade turns its face to the
# viewer, and max(·, 0) is not linear): the volume blends a texel's lambert towards the facing
# table (core/facing.py) as far as its normal is shortened, and the image-based grass takes its
# mean diffuse factor from the table and only the variation about the patch's mean normal from
# these.
# Every data texel: rgb = normal · 0.5 + 0.5, a = density threshold. (Rebuilding a third
# component from two averaged ones would lengthen the normal again and brighten the mips.)


SPREAD_LEVELS = 12  # entries of the shaders' per-level spread tables (shaders/_lod.glsl)


def spread_levels(spread: np.ndarray) -> bytes:
    """A per-level spread as the shaders' table: SPREAD_LEVELS floats, the last level repeated."""
    table = np.full(SPREAD_LEVELS, spread[-1] if len(spread) else 0.0, np.float32)
    table[: min(len(spread), SPREAD_LEVELS)] = spread[:SPREAD_LEVELS]
    return table.tobytes()


@dataclass
class LayerTextures:
    color: moderngl.Texture
    data: moderngl.Texture  # see above: normal, threshold
    count: int  # slices stacked along v
    spread: np.ndarray  # per mip level: the thresholds' spread under a texel (core/mipmaps.py)
    # (3,) the family's colour: its smallest level, where the alpha-weighted reductions (eq.
    # 4.10) leave the blades' mean colour
    mean_color: np.ndarray
    mean_normal: np.ndarray  # (3,): the data's normal over the whole family (smallest level)
    # vertical slices: their rows' mean optical depth per mip level (core/mipmaps.py
    # row_depths), one level a row of the texture, linear along the height and between levels
    depths: moderngl.Texture | None = None

    def release(self) -> None:
        self.color.release()
        self.data.release()
        if self.depths is not None:
            self.depths.release()


def canonical_data(layers: SliceLayers) -> np.ndarray:
    """(n, h, w, 4): the normal turned up and encoded 0 … 1, and the density threshold."""
    out = np.empty((*layers.threshold.shape, 4), np.float32)
    _canonical_into(layers.normal, layers.threshold, out)
    return out


@numba.njit(cache=True)
def _canonical_into(normal, threshold, out):
    """canonical_data per texel, compiled (one pass instead of several numpy array passes);
    in float64 before the float32 store, as the array arithmetic does."""
    for k in range(out.shape[0]):
        for y in range(out.shape[1]):
            for x in range(out.shape[2]):
                sign = -1.0 if normal[k, y, x, 1] < 0 else 1.0
                for c in range(3):
                    out[k, y, x, c] = np.float64(normal[k, y, x, c]) * sign * 0.5 + 0.5
                out[k, y, x, 3] = threshold[k, y, x]


def slice_levels(height: int, width: int) -> int:
    return int(np.log2(min(height, width))) + 1


@dataclass
class LayerLevels:
    """One slice family's mip chains, computed without GL (safe on a worker thread)."""

    color: list[np.ndarray]
    data: list[np.ndarray]
    count: int  # slices stacked along v
    repeat_v: bool
    spread: np.ndarray  # per mip level (core/mipmaps.py: threshold_spread)
    mean_color: np.ndarray  # (3,)
    depths: np.ndarray | None = None  # vertical slices: core/mipmaps.py row_depths


def layer_levels(layers: SliceLayers, top: bool = False) -> LayerLevels:
    n, h, w = layers.threshold.shape
    count = slice_levels(h, w)
    # vertical slices: their upper rows hide the lower ones in the reduced levels
    color_levels = stacked_slice_mips(layers.color, count, upper_first=not top)
    data = canonical_data(layers)
    chain = weighted_chain(data, layers.color[..., 3], count)
    data_levels = [level.reshape(-1, *level.shape[2:]) for level in chain]
    spread = threshold_spread(layers.threshold, layers.color[..., 3], count)
    return LayerLevels(
        color_levels, data_levels, n, repeat_v=top, spread=spread,
        mean_color=color_levels[-1][..., :3].reshape(-1, 3).mean(axis=0),
        depths=None if top else row_depths(color_levels, n),
    )  # fmt: skip


def upload_levels(ctx: moderngl.Context, levels: LayerLevels) -> LayerTextures:
    color = texture_with_mips(ctx, levels.color)
    data = texture_with_mips(ctx, levels.data)
    for tex in (color, data):
        tex.repeat_x = True  # slices tile along u like the patch
        tex.repeat_y = levels.repeat_v  # only the top slice tiles along v
    mean_normal = levels.data[-1][..., :3].reshape(-1, 3).mean(axis=0) * 2.0 - 1.0
    depths = None
    if levels.depths is not None:
        table = np.ascontiguousarray(levels.depths, np.float32)
        depths = ctx.texture((table.shape[1], table.shape[0]), 1, table.tobytes(), dtype="f4")
        depths.filter = (moderngl.LINEAR, moderngl.LINEAR)
        depths.repeat_x = depths.repeat_y = False
    return LayerTextures(
        color, data, levels.count, levels.spread, levels.mean_color, mean_normal, depths
    )


@dataclass
class SliceLevels:
    """Every mip level of a converted patch, ready to upload (thesis 4.2.2-4.2.3)."""

    x: LayerLevels
    z: LayerLevels
    top: LayerLevels
    height: float
    level_colors: np.ndarray  # (n, 3): what a view from each elevation meets (core/canopy.py)
    canopy: Canopy  # the rows' extinction and colour, for views over another type's grass
    top_alpha: float  # the top view's mean alpha at its base level: its cover from above

    @classmethod
    def compute(cls, sliced: SlicedPatch) -> SliceLevels:
        h = sliced.height
        top = (sliced.top.color[..., 3], sliced.top.height)
        canopy = Canopy.of([sliced.x.color, sliced.z.color], h, sliced.blades, top)
        return cls(
            layer_levels(sliced.x),
            layer_levels(sliced.z),
            layer_levels(sliced.top, top=True),
            h,
            canopy.level_colors(),
            canopy,
            float(np.clip(sliced.top.color[..., 3].mean(), 0.0, 1.0)),
        )


def _stacked(first: LayerLevels, second: LayerLevels) -> LayerLevels:
    """Two slice families in one chain, the second's slices after the first's along v."""
    return LayerLevels(
        [np.concatenate(pair) for pair in zip(first.color, second.color, strict=True)],
        [np.concatenate(pair) for pair in zip(first.data, second.data, strict=True)],
        first.count + second.count,
        repeat_v=False,
        spread=0.5 * (first.spread + second.spread),
        mean_color=0.5 * (first.mean_color + second.mean_color),
        depths=None
        if first.depths is None or second.depths is None
        else 0.5 * (first.depths + second.depths),
    )


@dataclass
class SliceTextures:
    """The slices on the GPU. Both vertical families share one texture pair (`sides`: the
    slices across x, then those across z, stacked along v): a ray step reads one colour and one
    data texel whichever family it meets — with a texture per family, llvmpipe fetched from
    both and selected (sward bench --suite volume_cost measures the pass)."""

    sides: LayerTextures
    top: LayerTextures
    height: float
    slices: int  # per direction
    level_colors: np.ndarray  # SliceLevels
    canopy: Canopy  # SliceLevels
    top_alpha: float  # SliceLevels

    @classmethod
    def upload(cls, ctx: moderngl.Context, sliced: SlicedPatch) -> SliceTextures:
        return cls.from_levels(ctx, SliceLevels.compute(sliced))

    @classmethod
    def from_levels(cls, ctx: moderngl.Context, levels: SliceLevels) -> SliceTextures:
        return cls(
            upload_levels(ctx, _stacked(levels.x, levels.z)),
            upload_levels(ctx, levels.top),
            levels.height,
            levels.x.count,
            levels.level_colors,
            levels.canopy,
            levels.top_alpha,
        )

    def release(self) -> None:
        for layers in (self.sides, self.top):
            layers.release()
