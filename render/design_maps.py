"""GL mirror of the design-map stack (core/design_maps.py): one RGBA texture array, one layer a
map, linearly filtered (thesis 6.4.1: smooth transitions). Edits upload only their rectangle."""

from __future__ import annotations

import moderngl
import numpy as np

from core.design_maps import LAYER_INDEX, DesignMaps, Rect
from render.uniforms import DESIGN_UNIT


class DesignMapTextures:
    def __init__(self, ctx: moderngl.Context, maps: DesignMaps) -> None:
        self.ctx = ctx
        self.maps = maps
        w, h = maps.size
        layers = maps.stack.shape[0]
        data = maps.stack.astype(np.float16).tobytes()
        self.texture = ctx.texture_array((w, h, layers), 4, data, dtype="f2")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = False
        self.texture.repeat_y = False
        self.uploaded_texels = w * h * layers  # for tests and the profiler: what went to the GPU
        maps.changed.connect(self.update)

    def update(self, name: str, rect: Rect) -> None:
        """Upload one rectangle of one map."""
        x, y, w, h = rect
        if w <= 0 or h <= 0:
            return
        i = LAYER_INDEX[name]
        data = np.ascontiguousarray(self.maps.stack[i, y : y + h, x : x + w].astype(np.float16))
        self.texture.write(data.tobytes(), viewport=(x, y, i, w, h, 1))
        self.uploaded_texels = w * h

    def use(self) -> None:
        """Bind the stack where every program's u_design looks (FrameUniforms sets the unit)."""
        self.texture.use(DESIGN_UNIT)

    def release(self) -> None:
        self.maps.changed.disconnect(self.update)
        self.texture.release()
