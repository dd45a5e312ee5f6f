"""Props (core/props.py) in one instanced draw: part of t_m with the ground."""

from __future__ import annotations

import moderngl
import numpy as np

from core.props import PROP_DTYPE
from render.buffers import upload
from render.shaders import load_program
from render.uniforms import FrameUniforms


def _cube() -> np.ndarray:
    """36 vertices (position, normal) of a unit cube centred on the origin, faces outward."""
    verts = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = np.zeros(3)
            n[axis] = sign
            u, v = np.roll(np.eye(3), 1, axis=0)[axis], np.roll(np.eye(3), 2, axis=0)[axis]
            if sign > 0:  # u × v = n: counter-clockwise seen from outside
                u, v = v, u
            c = n * 0.5
            quad = [c - u / 2 - v / 2, c + u / 2 - v / 2, c + u / 2 + v / 2, c - u / 2 + v / 2]
            for k in (0, 1, 2, 0, 2, 3):
                verts.append(np.concatenate([quad[k], n]))
    return np.array(verts, np.float32)


class PropRenderer:
    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "props.glsl")
        self.vbo = ctx.buffer(_cube().tobytes())
        self.instances: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self.count = 0

    def set_props(self, props: np.ndarray) -> None:
        if props.dtype != PROP_DTYPE:
            raise TypeError("props must be a PROP_DTYPE array")
        self.count = int(props.size)
        data = props if props.size else np.zeros(1, PROP_DTYPE)
        buf = upload(self.ctx, self.instances, data, grow_only=True)
        if buf is not self.instances or self.vao is None:
            self.instances = buf
            if self.vao is not None:
                self.vao.release()
            self.vao = self.ctx.vertex_array(
                self.program,
                [
                    (self.vbo, "3f 3f", "in_position", "in_normal"),
                    (self.instances, "3f 3f 3f/i", "in_centre", "in_size", "in_color"),
                ],
            )

    def draw(self, frame: FrameUniforms) -> None:
        if not self.count or self.vao is None:
            return
        frame.apply(self.program)
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.vao.render(moderngl.TRIANGLES, instances=self.count)
        self.ctx.disable(moderngl.CULL_FACE)

    def release(self) -> None:
        for obj in (self.vao, self.instances, self.vbo):
            if obj is not None:
                obj.release()
