"""The aperiodic tiling's noise map (thesis 6.3, core/tiling.py) on the GPU, for the shaders
that draw macro-cells: a macro-cell instance carries the symmetry vector of its first cell only,
and the blades of each cell it covers are mirrored by that cell's own bits (core/terrain.py), so
the volume and image-based shaders read the bits of the cell a sample lies in from this texture
(shaders/_design.glsl `cell_mirror`)."""

from __future__ import annotations

import moderngl
import numpy as np

from core.tiling import NOISE_RESOLUTION, noise_map
from render.uniforms import TILING_UNIT


class TilingNoise:
    def __init__(self, ctx: moderngl.Context) -> None:
        self.texture = ctx.texture((NOISE_RESOLUTION, NOISE_RESOLUTION), 2, dtype="f4")
        self.texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.seed: int | None = None

    def set_seed(self, seed: int | None) -> None:
        """The noise of `seed`; None: no tiling (the shaders use each instance's own bits)."""
        if seed is not None and seed != self.seed:
            # texel (x = i, y = j) holds noise[i, j] as mirror_sign reads it
            texels = np.ascontiguousarray(noise_map(seed).transpose(1, 0, 2))
            self.texture.write(texels.tobytes())
        self.seed = seed

    def use(self, unit: int = TILING_UNIT) -> None:
        self.texture.use(unit)

    def release(self) -> None:
        self.texture.release()
