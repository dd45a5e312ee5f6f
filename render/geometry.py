"""Geometry-based grass renderer (thesis 5.1): prepare / draw / finalize.

The patch's vertices live in one buffer; the cells to draw are per-instance attributes. Blades
far away are drawn with fewer segments (core/segments.py): the index buffer holds each level's
strips, the instances are sorted by their level, and one indirect command per level draws its
range of them (glMultiDrawElementsIndirect's base instance), a handful of calls a frame.
"""

from __future__ import annotations

import moderngl
import numpy as np

from core import segments
from core.patch import GrassPatch, blade_texture
from render.buffers import InstancedRenderer, layout, upload
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
    ("in_chord_color", 3),
    ("in_level_width", 4),
)


class GeometryRenderer(InstancedRenderer):
    technique_color = (1.0, 0.15, 0.1)  # --view techniques (thesis Figs. 7.1-7.6)
    alpha_ref = 0.25
    density_channel = 0  # the grass type's channel of the density map (render/layer.py)
    rows_layout = ("1f/i", ("in_segment",))  # each instance's continuous segment level
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
        self._levels: list[tuple[int, int]] = []  # (first index, index count) per level
        # core/segments.py curvature of the patch's blades, by the largest lean they bend by
        self._curvature: dict[float, float] = {}
        # where the frame is seen from: (eye, radians per pixel, the largest lean the wind and
        # the trampling give, draft, tolerance in pixels); set before the instances
        # (render/frame_draw.py), None: every blade with all its segments
        self.view: tuple | None = None
        # (level, first instance, count, whether any of them slides toward the next level)
        self._ranges: list[tuple[int, int, int, bool]] = []
        self._scale = 0.0  # this frame's segments.error_scale (0: every row drawn)
        self._commands: moderngl.Buffer | None = None

    def default_rows(self, instances: np.ndarray) -> np.ndarray:
        return np.zeros((instances.size, 1), np.float32)

    # -- resources ---------------------------------------------------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        """Upload a new patch; buffers are reused when the size fits. The index buffer holds
        each segment level's strips one after the other (core/segments.py level_indices)."""
        self.patch = patch
        blades, s = len(patch.roots), patch.params.subdivisions
        if len(patch.indices) == blades * s * 6:  # generate_patch's strips
            parts = [segments.level_indices(blades, s, k) for k in range(segments.level_count(s))]
        else:  # a selection of them (render/conversion.py): drawn whole
            parts = [patch.indices]
        starts = np.cumsum([0] + [len(p) for p in parts])
        self._levels = [(int(a), len(p)) for a, p in zip(starts, parts, strict=False)]
        v = patch.vertices
        self._curvature = {}
        vbo = upload(self.ctx, self.vbo, v)
        ibo = upload(self.ctx, self.ibo, np.concatenate(parts))
        if vbo is not self.vbo or ibo is not self.ibo:
            self.vbo, self.ibo = vbo, ibo
            self._rebuild_vao()

    def set_instances(self, instances: np.ndarray, rows: np.ndarray | None = None) -> None:
        """The cells to draw, sorted by the segment level their blades are drawn at."""
        levels = np.zeros(instances.size, np.int64)
        f = np.zeros(instances.size)
        self._scale = 0.0
        if self.view is not None and len(self._levels) > 1 and instances.size:
            eye, pixel, lean, draft, tolerance = self.view
            s = self.patch.params.subdivisions
            if lean not in self._curvature:
                if len(self._curvature) >= 8:  # leans come and go with the wind's settings
                    self._curvature.clear()
                v = self.patch.vertices
                self._curvature[lean] = segments.curvature(v["ctrl1"], v["ctrl2"], lean)
            g = self._curvature[lean]
            self._scale = min(segments.error_scale(g, s, 1.0, pixel, tolerance), 1e30)
            distance = segments.cell_distance(eye, instances, 1.0, self.patch.height)
            f = segments.segment_level(distance, self._scale, len(self._levels), int(draft))
            levels = np.floor(f).astype(np.int64)
            order = np.argsort(levels, kind="stable")
            instances, levels, f = instances[order], levels[order], f[order]
        super().set_instances(instances, f.astype(np.float32)[:, None])
        counts = np.bincount(levels, minlength=len(self._levels))
        firsts = np.cumsum(counts) - counts
        self._ranges = [
            (k, int(a), int(n), bool((f[a : a + n] > k + 1e-6).any()))
            for k, (a, n) in enumerate(zip(firsts, counts, strict=True))
            if n
        ]

    def triangles(self, visible: int) -> int:
        """The triangles this frame's instances draw of `visible` blades each."""
        if self.patch is None:
            return 0
        blades = max(len(self.patch.roots), 1)
        return sum(
            visible * n * (self._levels[k][1] // blades // 3) for k, _a, n, _m in self._ranges
        )

    def _make_vao(self) -> moderngl.VertexArray | None:
        if self.vbo is None or self.instances is None or self.ibo is None:
            return None
        return self.ctx.vertex_array(
            self.program,
            self._buffers(layout(self.program, self.vbo, VERTEX_ATTRIBUTES)),
            index_buffer=self.ibo,
            index_element_size=4,
        )

    # -- the three passes --------------------------------------------------------------------
    def prepare(self, frame: FrameUniforms, defines: tuple[str, ...] = ()) -> None:
        """`defines` on top of the frame's: SHADOW draws the blades' shadows (render/shadows.py)."""
        self.use_program(load_program(self.ctx, self.file, frame.defines + defines))
        frame.apply(self.program, self.technique_color)
        if reads(self.program, "u_density_channel"):
            self.program["u_density_channel"].value = self.density_channel
        self.program["u_density"].value = float(self.density)
        if reads(self.program, "u_cell_size"):  # where the wind or the segments read it
            self.program["u_cell_size"].value = 1.0
        self.program["u_alpha_ref"].value = self.alpha_ref
        self.program["u_blade"].value = 0
        self.program["u_epsilon"].value = self.epsilon
        if self.patch is not None:
            for name, value in (
                ("u_segment_scale", self._scale),
                ("u_segment_last", len(self._levels) - 1),
                ("u_subdivisions", self.patch.params.subdivisions),
            ):
                if reads(self.program, name):
                    self.program[name].value = float(value)
        self.blade_texture.use(0)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.disable(moderngl.CULL_FACE)

    def draw(self) -> None:
        """One indirect command per segment level: its strips, its range of the instances."""
        if self.vao is None or not self._ranges:
            return
        commands = np.array(
            [(self._levels[k][1], n, self._levels[k][0], 0, a) for k, a, n, _m in self._ranges],
            np.uint32,
        )
        self._commands = upload(self.ctx, self._commands, commands, grow_only=True)
        leveled = reads(self.program, "u_segment_level")
        for j, (k, _first, _n, slides) in enumerate(self._ranges):
            if leveled:  # a draw where nothing slides skips the sliding's work
                self.program["u_segment_level"].value = float(k)
                self.program["u_segment_scale"].value = self._scale if slides else 0.0
            self.vao.render_indirect(self._commands, moderngl.TRIANGLES, count=1, first=j)

    def draw_coarsest(self) -> None:
        """Every instance at the last segment level, one segment a blade (the blades' shadows,
        render/shadows.py: an outline on the ground needs no more)."""
        if self.vao is None or not self._ranges:
            return
        last = len(self._levels) - 1
        if reads(self.program, "u_segment_level"):
            self.program["u_segment_level"].value = float(last)
            self.program["u_segment_scale"].value = 0.0
        first, count = self._levels[last]
        total = sum(n for _k, _a, n, _m in self._ranges)
        self.vao.render(moderngl.TRIANGLES, vertices=count, first=first, instances=total)

    def finalize(self) -> None:
        """Nothing to undo: the shader sets the samples its fragments cover."""

    def release(self) -> None:
        self._release_vaos()
        for obj in (self.vbo, self.ibo, self.instances, self.blade_texture, self._commands):
            if obj is not None:
                obj.release()
