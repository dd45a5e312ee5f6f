"""GL mirror of the design-map stack (core/design_maps.py): one RGBA texture array, one layer a
map, linearly filtered (thesis 6.4.1: smooth transitions).

Edits upload only their rectangle, and not at once: a map may be edited while no GL context is
current (a brush stroke from a mouse event), so each edit grows the pending dirty rectangle of
its map, and `flush` (called by `use`, i.e. when a frame is drawn) uploads it. The dabs of one
mouse move become one upload."""

from __future__ import annotations

import moderngl
import numpy as np

from core.design_maps import LAYER_INDEX, DesignMaps, Rect
from render.uniforms import DESIGN_UNIT


def union(a: Rect | None, b: Rect) -> Rect:
    """The smallest rectangle holding both (x, y, width, height)."""
    if a is None:
        return b
    x0, y0 = min(a[0], b[0]), min(a[1], b[1])
    x1, y1 = max(a[0] + a[2], b[0] + b[2]), max(a[1] + a[3], b[1] + b[3])
    return (x0, y0, x1 - x0, y1 - y0)


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
        self.pending: dict[int, Rect] = {}  # layer index -> dirty rectangle not yet uploaded
        maps.changed.connect(self.update)

    def update(self, name: str, rect: Rect) -> None:
        """Note a changed rectangle of one map; the next `flush` uploads it."""
        if rect[2] > 0 and rect[3] > 0:
            i = LAYER_INDEX[name]
            self.pending[i] = union(self.pending.get(i), rect)

    def flush(self) -> None:
        """Upload the dirty rectangle of every edited map (the context must be current)."""
        self.uploaded_texels = 0
        for i, (x, y, w, h) in self.pending.items():
            data = np.ascontiguousarray(self.maps.stack[i, y : y + h, x : x + w].astype(np.float16))
            self.texture.write(data.tobytes(), viewport=(x, y, i, w, h, 1))
            self.uploaded_texels += w * h
        self.pending.clear()

    def use(self) -> None:
        """Bind the stack where every program's u_design looks (FrameUniforms sets the unit),
        after uploading what changed since the last frame."""
        if self.pending:
            self.flush()
        self.texture.use(DESIGN_UNIT)

    def release(self) -> None:
        self.maps.changed.disconnect(self.update)
        self.texture.release()
