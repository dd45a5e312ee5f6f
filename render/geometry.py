"""Geometry-based grass renderer (thesis 5.1): prepare / draw / finalize.

The patch's vertices live in one buffer; the cells to draw are per-instance attributes, so every
cell of the representation is drawn in ONE instanced call.
"""

from __future__ import annotations

import moderngl
import numpy as np

from core.grid import INSTANCE_DTYPE
from core.patch import GrassPatch, blade_texture
from render.buffers import upload
from render.shaders import load_program
from render.uniforms import FrameUniforms

GL_SAMPLE_ALPHA_TO_COVERAGE = 0x809E

# (attribute, float count) in the order of core.patch.VERTEX_DTYPE and core.grid.INSTANCE_DTYPE.
VERTEX_ATTRIBUTES = (
    ("in_position", 3),
    ("in_normal", 3),
    ("in_uv", 2),
    ("in_color", 3),
    ("in_root", 2),
    ("in_threshold", 1),
)
INSTANCE_ATTRIBUTES = (("in_origin", 2), ("in_cell_density", 1), ("in_lod", 2))


class GeometryRenderer:
    technique_color = (1.0, 0.15, 0.1)  # --view techniques (thesis Figs. 7.1-7.6)
    alpha_ref = 0.25
    epsilon = 0.05  # LOD crossover window (eq. 5.26)
    ao_root = 0.45

    def __init__(self, ctx: moderngl.Context, program: str = "geometry.glsl") -> None:
        self.ctx = ctx
        self.program = load_program(ctx, program)
        tex = blade_texture()
        self.blade_texture = ctx.texture((tex.shape[1], tex.shape[0]), 4, tex.tobytes())
        self.blade_texture.build_mipmaps()
        self.blade_texture.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        self.blade_texture.repeat_x = False
        self.blade_texture.repeat_y = False
        self.vbo: moderngl.Buffer | None = None
        self.ibo: moderngl.Buffer | None = None
        self.instances: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self.instance_count = 0
        self.patch: GrassPatch | None = None
        self.density = 1.0

    # -- resources ---------------------------------------------------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        """Upload a new patch; buffers are reused when the size fits."""
        self.patch = patch
        vbo = upload(self.ctx, self.vbo, patch.vertices)
        ibo = upload(self.ctx, self.ibo, patch.indices)
        if vbo is not self.vbo or ibo is not self.ibo:
            self.vbo, self.ibo = vbo, ibo
            self._rebuild_vao()

    def set_instances(self, instances: np.ndarray) -> None:
        """The cells to draw: an INSTANCE_DTYPE array. The buffer only grows, so selecting a
        new subset every frame writes into it without new GL objects."""
        if instances.dtype != INSTANCE_DTYPE:
            raise TypeError("instances must be an INSTANCE_DTYPE array")
        self.instance_count = int(instances.size)
        data = instances if instances.size else np.zeros(1, INSTANCE_DTYPE)
        buf = upload(self.ctx, self.instances, data, grow_only=True)
        if buf is not self.instances:
            self.instances = buf
            self._rebuild_vao()

    def _rebuild_vao(self) -> None:
        if self.vbo is None or self.instances is None or self.ibo is None:
            return
        if self.vao is not None:
            self.vao.release()
        self.vao = self.ctx.vertex_array(
            self.program,
            [
                _layout(self.program, self.vbo, VERTEX_ATTRIBUTES, ""),
                _layout(self.program, self.instances, INSTANCE_ATTRIBUTES, "/i"),
            ],
            index_buffer=self.ibo,
            index_element_size=4,
        )

    # -- the three passes --------------------------------------------------------------------
    def prepare(self, frame: FrameUniforms) -> None:
        frame.apply(self.program, self.technique_color)
        self.program["u_density"].value = float(self.density)
        self.program["u_cell_size"].value = 1.0
        self.program["u_alpha_ref"].value = self.alpha_ref
        self.program["u_ao_root"].value = self.ao_root
        self.program["u_blade"].value = 0
        self.program["u_epsilon"].value = self.epsilon
        self.blade_texture.use(0)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.disable(moderngl.CULL_FACE)
        self.ctx.enable_direct(GL_SAMPLE_ALPHA_TO_COVERAGE)

    def draw(self) -> None:
        if self.vao is not None and self.instance_count > 0:
            self.vao.render(moderngl.TRIANGLES, instances=self.instance_count)

    def finalize(self) -> None:
        self.ctx.disable_direct(GL_SAMPLE_ALPHA_TO_COVERAGE)

    def release(self) -> None:
        for obj in (self.vao, self.vbo, self.ibo, self.instances, self.blade_texture):
            if obj is not None:
                obj.release()


def _layout(
    program: moderngl.Program,
    buffer: moderngl.Buffer,
    attributes: tuple[tuple[str, int], ...],
    suffix: str,
) -> tuple:
    """A vertex-array entry that skips attributes the program does not use."""
    parts, names = [], []
    for name, count in attributes:
        if name in program:
            parts.append(f"{count}f")
            names.append(name)
        else:
            parts.append(f"{count * 4}x")
    return (buffer, " ".join(parts) + suffix, *names)
