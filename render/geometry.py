"""Geometry-based grass renderer (thesis 5.1): prepare / draw / finalize.

The patch's vertices live in one buffer; the cells to draw are per-instance attributes, so every
cell of the representation is drawn in ONE instanced call.
"""

from __future__ import annotations

import moderngl
import numpy as np

from core.patch import GrassPatch, blade_texture, draft_indices
from render.buffers import InstancedRenderer, instance_layout, layout, upload
from render.shaders import load_program, reads
from render.uniforms import FrameUniforms

# (attribute, float count) in the order of core.patch.VERTEX_DTYPE.
VERTEX_ATTRIBUTES = (
    ("in_position", 3),
    ("in_normal", 3),
    ("in_uv", 2),
    ("in_color", 3),
    ("in_root", 2),
    ("in_threshold", 1),
    ("in_ctrl1", 3),
    ("in_ctrl2", 3),
)


class GeometryRenderer(InstancedRenderer):
    technique_color = (1.0, 0.15, 0.1)  # --view techniques (thesis Figs. 7.1-7.6)
    alpha_ref = 0.25
    density_channel = 0  # the grass type's channel of the density map (render/layer.py)
    epsilon = 0.05  # LOD crossover window (eq. 5.26)

    def __init__(self, ctx: moderngl.Context, program: str = "geometry.glsl") -> None:
        self.ctx = ctx
        self.file = program
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
        self._counts = (0, 0)  # the index buffer's full triangles, then a draft's
        self._draft = False  # this frame's a draft: blades of fewer segments

    # -- resources ---------------------------------------------------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        """Upload a new patch; buffers are reused when the size fits. The index buffer holds
        the patch's triangles and after them a draft's (core/patch.py draft_indices)."""
        self.patch = patch
        blades, s = len(patch.roots), patch.params.subdivisions
        if len(patch.indices) == blades * s * 6:  # generate_patch's strips
            coarse = draft_indices(blades, s)
        else:  # a selection of them (render/conversion.py): drafts draw them all
            coarse = patch.indices
        self._counts = (len(patch.indices), len(coarse))
        vbo = upload(self.ctx, self.vbo, patch.vertices)
        ibo = upload(self.ctx, self.ibo, np.concatenate([patch.indices, coarse]))
        if vbo is not self.vbo or ibo is not self.ibo:
            self.vbo, self.ibo = vbo, ibo
            self._rebuild_vao()

    def _make_vao(self) -> moderngl.VertexArray | None:
        if self.vbo is None or self.instances is None or self.ibo is None:
            return None
        return self.ctx.vertex_array(
            self.program,
            [
                layout(self.program, self.vbo, VERTEX_ATTRIBUTES),
                instance_layout(self.program, self.instances),
            ],
            index_buffer=self.ibo,
            index_element_size=4,
        )

    # -- the three passes --------------------------------------------------------------------
    def prepare(self, frame: FrameUniforms) -> None:
        self.use_program(load_program(self.ctx, self.file, frame.defines))
        frame.apply(self.program, self.technique_color)
        if reads(self.program, "u_density_channel"):
            self.program["u_density_channel"].value = self.density_channel
        self.program["u_density"].value = float(self.density)
        if reads(self.program, "u_cell_size"):  # where the wind is read: still air does not
            self.program["u_cell_size"].value = 1.0
        self.program["u_alpha_ref"].value = self.alpha_ref
        self.program["u_blade"].value = 0
        self.program["u_epsilon"].value = self.epsilon
        self.blade_texture.use(0)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.disable(moderngl.CULL_FACE)
        self._draft = frame.draft

    def draw(self) -> None:
        if self.vao is not None and self.instance_count > 0:
            full, coarse = self._counts
            if self._draft:
                self.vao.render(
                    moderngl.TRIANGLES, vertices=coarse, first=full, instances=self.instance_count
                )
            else:
                self.vao.render(moderngl.TRIANGLES, vertices=full, instances=self.instance_count)

    def finalize(self) -> None:
        """Nothing to undo: the shader sets the samples its fragments cover."""

    def release(self) -> None:
        self._release_vaos()
        for obj in (self.vbo, self.ibo, self.instances, self.blade_texture):
            if obj is not None:
                obj.release()
