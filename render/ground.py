"""The ground under the grass (part of t_m, the rest of the scenery): a large plane and, on
uneven terrain, a grid over the grassed cells that follows the height map (6.4.4)."""

from __future__ import annotations

import moderngl
import numpy as np

from render.design_maps import DesignMapTextures
from render.shaders import load_program
from render.uniforms import SINK_UNIT, FrameUniforms


def grid_mesh(nu: int, nv: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (0 … 1)² and triangle indices of an nu × nv grid (nv = nu if not given), each
    quad split from its (u + 1, v) corner to its (u, v + 1) corner (core/heights.py mesh_sink
    assumes this split)."""
    nv = nu if nv is None else nv
    u, v = np.meshgrid(
        np.linspace(0.0, 1.0, nu + 1, dtype=np.float32),
        np.linspace(0.0, 1.0, nv + 1, dtype=np.float32),
        indexing="xy",
    )
    verts = np.stack([u.ravel(), v.ravel()], axis=1)
    i = np.arange(nv)[:, None] * (nu + 1) + np.arange(nu)[None, :]  # lower-left of each quad
    quads = np.stack([i, i + 1, i + nu + 1, i + 1, i + nu + 2, i + nu + 1], axis=-1)
    return verts, quads.astype(np.uint32).ravel()


class GroundRenderer:
    extent = 2000.0

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "ground.glsl")
        corners = np.array([-1, -1, 1, -1, -1, 1, 1, 1], dtype=np.float32)
        self.vbo = ctx.buffer(corners.tobytes())
        self.vao = ctx.vertex_array(self.program, [(self.vbo, "2f", "in_corner")])
        # the grid over the grassed cells: one quad per height-map texel (core/heights.py
        # mesh_size), made when the map's size is first seen
        self.mesh_quads: tuple[int, int] | None = None
        self.mesh_vbo: moderngl.Buffer | None = None
        self.mesh_ibo: moderngl.Buffer | None = None
        self.mesh_vao: moderngl.VertexArray | None = None
        self.grass_rect = (0.0, 0.0, 0.0, 0.0)
        # the soil under the grass, shaded by it (diagnostics draw it black to see the grass)
        self.under_grass = tuple(0.55 * c for c in (0.30, 0.30, 0.12))

    def _mesh(self, quads: tuple[int, int]) -> moderngl.VertexArray:
        if quads != self.mesh_quads or self.mesh_vao is None:
            self._release_mesh()
            verts, indices = grid_mesh(*quads)
            self.mesh_vbo = self.ctx.buffer(verts.tobytes())
            self.mesh_ibo = self.ctx.buffer(indices.tobytes())
            self.mesh_vao = self.ctx.vertex_array(
                self.program,
                [(self.mesh_vbo, "2f", "in_corner")],
                index_buffer=self.mesh_ibo,
                index_element_size=4,
            )
            self.mesh_quads = quads
        return self.mesh_vao

    def _release_mesh(self) -> None:
        for obj in (self.mesh_vao, self.mesh_vbo, self.mesh_ibo):
            if obj is not None:
                obj.release()
        self.mesh_vao = self.mesh_vbo = self.mesh_ibo = None

    def draw(self, frame: FrameUniforms, maps: DesignMapTextures | None = None) -> None:
        """The plane, and on uneven ground (with `maps`) the grid over the grassed cells, each
        vertex sunk so that the grid lies under the ground the grass stands on."""
        frame.apply(self.program)
        light = frame.lighting
        p = self.program
        p["u_extent"].value = self.extent
        p["u_soil_color"].value = light.soil_color
        p["u_under_grass"].value = self.under_grass
        p["u_fog_color"].value = light.sky_color
        p["u_fog_distance"].value = light.fog_distance
        p["u_grass_rect"].value = self.grass_rect
        self.ctx.enable(moderngl.DEPTH_TEST)
        # pushed back a little in depth: grass lying on it (the image-based quads, the volume's
        # floor) must win over the soil even far away, where depth precision is coarse
        self.ctx.polygon_offset = (2.0, 4.0)
        uneven = frame.height_scale > 0
        p["u_mesh"].value = 0.0
        # on uneven ground the plane sinks a little so the grid over the cells lies on top
        p["u_sink"].value = 0.02 if uneven else 0.0
        self.vao.render(moderngl.TRIANGLE_STRIP)
        if uneven and maps is not None:
            sink, quads = maps.mesh_sink()
            sink.use(SINK_UNIT)
            p["u_mesh"].value = 1.0
            p["u_sink_map"].value = SINK_UNIT
            self._mesh(quads).render(moderngl.TRIANGLES)
        self.ctx.polygon_offset = (0.0, 0.0)

    def release(self) -> None:
        self._release_mesh()
        self.vao.release()
        self.vbo.release()
