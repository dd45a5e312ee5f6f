"""The facing-lambert table of one grass type on the GPU (core/facing.py): a small float
texture over the azimuth and elevation of the direction to the viewer, rebuilt when the patch or
the light changes. The volume and image-based shaders light with it (shaders/_lighting.glsl)."""

from __future__ import annotations

from collections.abc import Callable

import moderngl
import numpy as np

from core.facing import AZIMUTHS, ELEVATIONS, facing_lambert
from core.lighting import Lighting
from core.patch import GrassPatch

FACING_UNIT = 6  # texture unit of the table (render/uniforms.py has the others)


class FacingTable:
    def __init__(self, ctx: moderngl.Context, patch: Callable[[], GrassPatch | None]) -> None:
        self.ctx = ctx
        self._patch = patch
        self.texture = ctx.texture((AZIMUTHS, ELEVATIONS), 1, dtype="f4")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = True  # azimuth wraps
        self.texture.repeat_y = False
        self._patch_used: GrassPatch | None = None  # the patch and light the table is of
        self._light_used: tuple | None = None

    def table(self, lighting: Lighting) -> np.ndarray | None:
        patch = self._patch()
        if patch is None:
            return None
        return facing_lambert(
            patch.vertices["normal"], lighting.sun_direction, lighting.translucency
        )

    def use(self, lighting: Lighting, unit: int = FACING_UNIT) -> None:
        patch = self._patch()
        light = (*lighting.sun_direction, lighting.translucency)
        if patch is not None and (patch is not self._patch_used or light != self._light_used):
            self.texture.write(np.ascontiguousarray(self.table(lighting)).tobytes())
            self._patch_used, self._light_used = patch, light
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()
