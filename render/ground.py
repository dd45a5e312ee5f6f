"""The ground plane under the grass (part of t_m, the rest of the scenery)."""

from __future__ import annotations

import moderngl
import numpy as np

from render.shaders import load_program
from render.uniforms import FrameUniforms


class GroundRenderer:
    extent = 2000.0

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "ground.glsl")
        corners = np.array([-1, -1, 1, -1, -1, 1, 1, 1], dtype=np.float32)
        self.vbo = ctx.buffer(corners.tobytes())
        self.vao = ctx.vertex_array(self.program, [(self.vbo, "2f", "in_corner")])
        self.grass_rect = (0.0, 0.0, 0.0, 0.0)

    def draw(self, frame: FrameUniforms) -> None:
        frame.apply(self.program)
        light = frame.lighting
        p = self.program
        p["u_extent"].value = self.extent
        p["u_soil_color"].value = light.soil_color
        p["u_under_grass"].value = tuple(0.55 * c for c in (0.30, 0.30, 0.12))
        p["u_fog_color"].value = light.sky_color
        p["u_fog_distance"].value = light.fog_distance
        p["u_grass_rect"].value = self.grass_rect
        self.ctx.enable(moderngl.DEPTH_TEST)
        # pushed back a little in depth: grass lying on it (the image-based quads, the volume's
        # floor) must win over the soil even far away, where depth precision is coarse
        self.ctx.polygon_offset = (2.0, 4.0)
        self.vao.render(moderngl.TRIANGLE_STRIP)
        self.ctx.polygon_offset = (0.0, 0.0)

    def release(self) -> None:
        self.vao.release()
        self.vbo.release()
