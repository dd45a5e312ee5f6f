"""The wind's noise map on the GPU (core/wind.py noise_map, read by shaders/_wind.glsl), bound
once a frame like the tiling's noise."""

from __future__ import annotations

import moderngl

from core.wind import NOISE_RESOLUTION, noise_map
from render.uniforms import WIND_UNIT


class WindNoise:
    def __init__(self, ctx: moderngl.Context) -> None:
        n = NOISE_RESOLUTION
        self.texture = ctx.texture((n, n), 3, noise_map().tobytes(), dtype="f4")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = True
        self.texture.repeat_y = True

    def use(self, unit: int = WIND_UNIT) -> None:
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()
