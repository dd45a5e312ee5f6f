"""Geometry-based grass renderer (thesis 5.1): prepare / draw / finalize.

The patch's vertices live in one buffer; the cells to draw are per-instance attributes. Blades
far away are drawn with fewer segments (core/segments.py): the index buffer holds each level's
strips, the instances are sorted by their level, and one indirect command per level draws its
range of them (glMultiDrawElementsIndirect's base instance), a handful of calls a frame.

Each level's strips list the blades by their density threshold, lowest first, so the blades a
cell can show (eq. 5.26: those below its density, and in a transition those below w · density)
are one run of them: each command draws only its cells' run, and the blades a transition or a
thin density drops cost no vertex work.
"""

from __future__ import annotations

import itertools

import moderngl
import numpy as np

from core import segments
from core.lod import shown_thresholds
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
    spans = 16  # the runs of blades a command draws start and end on sixteenths of the patch

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
        self._density = 1.0
        self._levels: list[tuple[int, int]] = []  # (first index, index count) per level
        self._sorted: np.ndarray | None = None  # the blades' thresholds in the strips' order
        self._cells: tuple | None = None  # the last set_instances' arguments
        # core/segments.py curvature of the patch's blades, by the largest lean they bend by
        self._curvature: dict[float, float] = {}
        # where the frame is seen from: (eye, radians per pixel, the largest lean the wind and
        # the trampling give, draft, tolerance in pixels); set before the instances
        # (render/frame_draw.py), None: every blade with all its segments
        self.view: tuple | None = None
        # (level, first instance, count, whether any of them slides toward the next level,
        # first blade, end blade)
        self._ranges: list[tuple[int, int, int, bool, int, int]] = []
        self._scale = 0.0  # this frame's segments.error_scale (0: every row drawn)
        self._commands: moderngl.Buffer | None = None
        # prepare's programs: the WHOLE_STRIP variant for level 0 (True), the other levels'
        self._variants: dict[bool, moderngl.Program] = {}

    def default_rows(self, instances: np.ndarray) -> np.ndarray:
        return np.zeros((instances.size, 1), np.float32)

    @property
    def density(self) -> float:
        """The document's global density (u_density): which blades each cell can show."""
        return self._density

    @density.setter
    def density(self, value: float) -> None:
        self._density = float(value)
        self._replan()

    def _replan(self) -> None:
        if self._cells is not None:
            self.set_instances(*self._cells)

    # -- resources ---------------------------------------------------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        """Upload a new patch; buffers are reused when the size fits. The index buffer holds
        each segment level's strips one after the other (core/segments.py level_indices)."""
        self.patch = patch
        blades, s = len(patch.roots), patch.params.subdivisions
        self._sorted = None
        if len(patch.indices) == blades * s * 6:  # generate_patch's strips
            order = np.argsort(patch.thresholds, kind="stable")
            self._sorted = patch.thresholds[order]
            levels = range(segments.level_count(s))
            parts = [segments.level_indices(blades, s, k, order) for k in levels]
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
        self._replan()

    def _blade_runs(self, instances: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Per cell the run of blades (first, end in the strips' order) it can show, widened
        to whole `spans`ths of the patch so that cells share commands."""
        if self._sorted is None:  # no patch yet (nothing), or a selection (one run: all of it)
            whole = 0 if self.patch is None else 1
            return np.zeros(instances.size, np.int64), np.full(instances.size, whole)
        blades = len(self._sorted)
        lo, hi = shown_thresholds(
            self._density * instances["density"], instances["lod"], self.epsilon
        )
        step = -(-blades // self.spans)
        first = np.searchsorted(self._sorted, lo, "left") // step * step
        end = np.minimum(-(-np.searchsorted(self._sorted, hi, "right") // step) * step, blades)
        return first, end

    def set_instances(self, instances: np.ndarray, rows: np.ndarray | None = None) -> None:
        """The cells to draw, sorted by the segment level their blades are drawn at and the run
        of blades they show; cells that show none are left out. (`rows`, the second buffer's,
        are this renderer's own: each cell's segment level.)"""
        self._cells = (instances, rows)
        first, end = self._blade_runs(instances)
        instances, first, end = instances[end > first], first[end > first], end[end > first]
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
        slides = f > levels + 1e-6  # toward the next level
        order = np.lexsort((end, first, slides, levels))
        instances, f = instances[order], f[order]
        key = np.stack([levels, slides, first, end], axis=1)[order]
        super().set_instances(instances, f.astype(np.float32)[:, None])
        # one command per run of cells alike in level, sliding, first and end blade
        new = np.r_[True, (key[1:] != key[:-1]).any(axis=1)] if len(key) else np.zeros(0, bool)
        bounds = np.r_[np.flatnonzero(new), len(key)]
        self._ranges = [
            (int(key[a, 0]), int(a), int(b - a), bool(key[a, 1]), int(key[a, 2]), int(key[a, 3]))
            for a, b in itertools.pairwise(bounds)
        ]

    def triangles(self) -> int:
        """The triangles this frame's commands draw (the blades a cell cannot show included,
        where they share a run with those it can)."""
        return sum(n * (b - a) * self._per_blade(k) // 3 for k, _i, n, _m, a, b in self._ranges)

    def _per_blade(self, level: int) -> int:
        """Indices per blade at a segment level (the whole selection where not by blade)."""
        blades = 1 if self._sorted is None else len(self._sorted)
        return self._levels[level][1] // blades

    def _commands_for(self, ranges: list, level: int | None = None) -> np.ndarray:
        """glMultiDrawElementsIndirect's commands for `ranges`, at their own segment levels or
        all at `level`."""
        rows = []
        for k, a, n, _m, lo, hi in ranges:
            k = k if level is None else level
            per = self._per_blade(k)
            rows.append((per * (hi - lo), n, self._levels[k][0] + per * lo, 0, a))
        return np.array(rows, np.uint32).reshape(-1, 5)

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
        """`defines` on top of the frame's: SHADOW draws the blades' shadows (render/shadows.py).
        Draws of the full strips (segment level 0) take the WHOLE_STRIP variant: their vertices'
        normals interpolated are the strip's, which the other levels rebuild per fragment."""
        defines = frame.defines + defines
        # geometry.glsl's shaded blades light from normals; its shadows and the slices'
        # capture (slice_capture.glsl) have one program for every level
        lit = self.file == "geometry.glsl" and "SHADOW" not in defines
        whole = (*defines, "WHOLE_STRIP") if lit else defines
        self._variants = {
            level0: load_program(self.ctx, self.file, d)
            for level0, d in ((True, whole), (False, defines))
        }
        for program in set(self._variants.values()):
            self._apply(program, frame)
        self.use_program(self._variants[False])
        self.blade_texture.use(0)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.disable(moderngl.CULL_FACE)

    def _apply(self, program: moderngl.Program, frame: FrameUniforms) -> None:
        frame.apply(program, self.technique_color)
        if reads(program, "u_density_channel"):
            program["u_density_channel"].value = self.density_channel
        program["u_density"].value = float(self.density)
        if reads(program, "u_cell_size"):  # where the wind or the segments read it
            program["u_cell_size"].value = 1.0
        program["u_alpha_ref"].value = self.alpha_ref
        program["u_blade"].value = 0
        program["u_epsilon"].value = self.epsilon
        if self.patch is not None:
            for name, value in (
                ("u_segment_scale", self._scale),
                ("u_segment_last", len(self._levels) - 1),
                ("u_subdivisions", self.patch.params.subdivisions),
            ):
                if reads(program, name):
                    program[name].value = float(value)

    def draw(self) -> None:
        """One indirect command per segment level: its strips, its range of the instances."""
        if self.vao is None or not self._ranges:
            return
        commands = self._commands_for(self._ranges)
        self._commands = upload(self.ctx, self._commands, commands, grow_only=True)
        j = 0
        while j < len(self._ranges):  # one call per level and sliding: its runs of blades
            k, slides = self._ranges[j][0], self._ranges[j][3]
            n = 1
            while j + n < len(self._ranges) and self._ranges[j + n][0:4:3] == (k, slides):
                n += 1
            self.use_program(self._variants[k == 0])
            leveled = reads(self.program, "u_segment_level")
            if leveled:  # a draw where nothing slides skips the sliding's work
                self.program["u_segment_level"].value = float(k)
                self.program["u_segment_scale"].value = self._scale if slides else 0.0
            self.vao.render_indirect(self._commands, moderngl.TRIANGLES, count=n, first=j)
            j += n

    def draw_coarsest(self) -> None:
        """Every instance at the last segment level, one segment a blade (the blades' shadows,
        render/shadows.py: an outline on the ground needs no more)."""
        if self.vao is None or not self._ranges:
            return
        self.use_program(self._variants[False])
        last = len(self._levels) - 1
        if reads(self.program, "u_segment_level"):
            self.program["u_segment_level"].value = float(last)
            self.program["u_segment_scale"].value = 0.0
        commands = self._commands_for(self._ranges, last)
        self._commands = upload(self.ctx, self._commands, commands, grow_only=True)
        self.vao.render_indirect(self._commands, moderngl.TRIANGLES, count=len(commands))

    def finalize(self) -> None:
        """Nothing to undo: the shader sets the samples its fragments cover."""

    def release(self) -> None:
        self._release_vaos()
        for obj in (self.vbo, self.ibo, self.instances, self.blade_texture, self._commands):
            if obj is not None:
                obj.release()
