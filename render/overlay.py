"""Overlay lines over the finished image: the brush outline on the ground under the cursor and
the LOD zone rings (widgets set them; the pipeline draws them last, outside the timings)."""

from __future__ import annotations

import moderngl
import numpy as np

from render.shaders import load_program
from render.uniforms import FrameUniforms

Line = tuple[np.ndarray, tuple[float, float, float, float]]  # (points (n, 3), RGBA)


class OverlayRenderer:
    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "overlay.glsl")
        self.groups: dict[str, list[Line]] = {}  # e.g. "brush", "zones"
        self._buffer: moderngl.Buffer | None = None
        self._vao: moderngl.VertexArray | None = None
        self._strips: list[tuple[int, int, tuple]] = []  # (first, count, colour)
        self._dirty = False

    def set_lines(self, group: str, lines: list[Line]) -> None:
        """Replace one group of line strips (an empty list removes it)."""
        self.groups[group] = list(lines)
        self._dirty = True

    def _upload(self) -> None:
        lines = [line for group in self.groups.values() for line in group]
        self._strips = []
        points = []
        first = 0
        for pts, colour in lines:
            pts = np.asarray(pts, np.float32).reshape(-1, 3)
            self._strips.append((first, len(pts), colour))
            points.append(pts)
            first += len(pts)
        data = np.concatenate(points) if points else np.zeros((1, 3), np.float32)
        if self._buffer is None or self._buffer.size < data.nbytes:
            for obj in (self._vao, self._buffer):
                if obj is not None:
                    obj.release()
            self._buffer = self.ctx.buffer(reserve=max(data.nbytes, 4096))
            self._vao = self.ctx.vertex_array(self.program, [(self._buffer, "3f", "in_position")])
        self._buffer.write(data.tobytes())
        self._dirty = False

    def draw(self, frame: FrameUniforms) -> None:
        if self._dirty:
            self._upload()
        if not self._strips or self._vao is None:
            return
        frame.apply(self.program)
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA
        for first, count, colour in self._strips:
            self.program["u_color"].value = tuple(float(c) for c in colour)
            self._vao.render(moderngl.LINE_STRIP, vertices=count, first=first)
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)

    def release(self) -> None:
        for obj in (self._vao, self._buffer):
            if obj is not None:
                obj.release()
