"""Image-based grass renderer (thesis 5.3): one quad per (macro-)cell, textured with the
horizontal slice; its alpha covers the pixel's samples under MSAA like the geometry's
(shaders/_coverage.glsl). On uneven ground a cell's slice
is a grid whose vertices follow the height map (6.4.4), as fine as the ground's bends seen from
the eye need (core/heights.py slice_grids); cells on flat ground are one quad, as in the thesis.
Each grid is one instanced call."""

from __future__ import annotations

import moderngl
import numpy as np

from core.canopy import Canopy
from core.ground_mesh import grid_mesh
from core.heights import SLICE_GRIDS, slice_grids
from core.lod import NO_FADE
from core.terrain import Terrain
from render.buffers import InstancedRenderer
from render.facing import FACING_UNIT, FacingTable, SlopeTable, bind_slopes
from render.shaders import load_program, reads
from render.slices import SliceTextures, spread_levels
from render.uniforms import FrameUniforms

# AO_blade (eq. 6.11) is that of the heights a view meets of the blades (core/canopy.py
# Canopy.shade_met), not of fixed heights: a view from low over the grass meets its darker lower
# parts too.


class _Batch(InstancedRenderer):
    """Instances drawn with one mesh (a grid of n × n quads per instance)."""

    # per cell, the rectangle of it (x0, z0, x1, z1 in cells from its corner) its slice keeps to
    rows_layout = ("4f/i", ("in_rect",))

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program, n: int) -> None:
        self.ctx = ctx
        self.program = program
        verts, indices = grid_mesh(n)
        self.vbo = ctx.buffer(verts.tobytes())
        self.ibo = ctx.buffer(indices.tobytes())
        self.instances: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self.instance_count = 0

    def default_rows(self, instances: np.ndarray) -> np.ndarray:
        rects = np.zeros((instances.size, 4), np.float32)
        rects[:, 2:] = instances["size"]
        return rects

    def _make_vao(self) -> moderngl.VertexArray:
        return self.ctx.vertex_array(
            self.program,
            self._buffers((self.vbo, "2f", "in_corner")),
            index_buffer=self.ibo,
            index_element_size=4,
        )

    def draw(self) -> None:
        if self.vao is not None and self.instance_count:
            self.vao.render(moderngl.TRIANGLES, instances=self.instance_count)

    def release(self) -> None:
        self._release_vaos()
        for obj in (self.instances, self.rows_buffer, self.vbo, self.ibo):
            if obj is not None:
                obj.release()


class ImageRenderer:
    epsilon = 0.05  # LOD crossover window (eq. 5.26)
    fade = NO_FADE  # the level's transitions' distances (core/lod.py fades), set per frame
    density_channel = 0  # the grass type's channel of the density map (render/layer.py)
    technique_color = (0.15, 0.35, 1.0)  # --view techniques (thesis Figs. 7.1-7.6)
    lift = 0.01
    # The slice lies at this fraction of its grass type's height, where what it shows (the
    # patch seen from above) is: there the far terrain's silhouette is the grass's, as in the
    # geometry, and of two grass types the taller one's slice lies in front of the shorter's,
    # which at one height would hide it wherever both grow (thesis 6.4.5).
    canopy = 0.7
    flat_ground = 0.5 * lift  # a cell whose ground varies less is one quad (set_instances)

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "image.glsl")
        # On llvmpipe the grid's small triangles cost most of the pass (every 4 × 4 pixel block
        # a triangle touches is shaded whole): flat cells get one quad, which lies within
        # flat_ground of the ground wherever that varies by less, so it stays above it; the
        # others the coarsest grid whose chords stray from the ground by under a pixel seen
        # from the eye (`view`; core/heights.py slice_grids), or the finest without one.
        self.batches = {n: _Batch(ctx, self.program, n) for n in SLICE_GRIDS}
        # (eye, radians a pixel, the terrain: its ground's bends, core/terrain.py curvature_of),
        # set each frame
        self.view: tuple[np.ndarray, float, Terrain | None] | None = None
        self.instance_count = 0
        self.textures: SliceTextures | None = None
        self.facing: FacingTable | None = None  # set by the grass type (render/grass_type.py)
        self.slope: SlopeTable | None = None  # the same
        self.density = 1.0
        # the types whose grass lies beneath this one's (render/frame.py)
        self.under_channels: tuple[int, ...] = ()
        self.under: Canopy | None = None  # the tallest of those types' (core/canopy.py)
        # over_colors' last result and the two canopies it is of (held, so never mistaken for
        # new ones that reuse their ids)
        self._over: tuple[tuple[Canopy, Canopy], np.ndarray] | None = None
        # level_shade's last result and what it is of (held, as _over)
        self._shade: tuple[tuple, tuple[np.ndarray, np.ndarray]] | None = None

    def over_colors(self) -> np.ndarray:
        """Per elevation of core/canopy.py's table, the colour this grass shows a ray above the
        grass beneath it (cached for the two canopies)."""
        t = self.textures
        assert t is not None
        assert self.under is not None
        key = (t.canopy, self.under)
        if self._over is None or self._over[0][0] is not key[0] or self._over[0][1] is not key[1]:
            self._over = (key, t.canopy.over(self.under)[1])
        return self._over[1]

    def level_shade(self, ao_height: float) -> tuple[np.ndarray, np.ndarray]:
        """core/canopy.py Canopy.shade_met for the light's B_height: this grass's own, and
        standing in the grass beneath it (`under`; the own again without), cached."""
        t = self.textures
        assert t is not None
        held = self._shade
        canopy, under, b_height = t.canopy, self.under, float(ao_height)
        if (
            held is None
            or held[0][0] is not canopy
            or held[0][1] is not under
            or held[0][2] != b_height
        ):
            own = canopy.shade_met(b_height)
            over = own if under is None else canopy.shade_met(b_height, under)
            held = self._shade = ((canopy, under, b_height), (own, over))
        return held[1]

    def layer_height(self) -> float | None:
        """Height of the slice above the ground (None without slices)."""
        if self.textures is None:
            return None
        return self.lift + self.canopy * float(self.textures.height)

    def set_instances(self, instances: np.ndarray, rects: np.ndarray | None = None) -> None:
        """The cells to draw: an INSTANCE_DTYPE array, split by the grid their ground needs;
        `rects`: per cell, the rectangle of it where its grass can grow (render/volume.py
        carriers; None: the whole cell), which its slice keeps to."""
        finest = SLICE_GRIDS[-1]
        grids = np.full(instances.size, finest, np.int32)
        if self.view is not None and instances.size:
            eye, pixel, terrain = self.view
            bends = terrain.curvature_of(instances) if terrain is not None else 0.0
            grids = slice_grids(instances, eye, pixel, bends)
        grids[instances["ground"][:, 1] <= self.flat_ground] = 1
        for n, batch in self.batches.items():
            batch.set_instances(instances[grids == n], None if rects is None else rects[grids == n])
        self.instance_count = int(instances.size)

    def prepare(self, frame: FrameUniforms) -> None:
        if self.textures is None:
            return
        program = load_program(self.ctx, "image.glsl", frame.defines)
        if program is not self.program:
            self.program = program
            for batch in self.batches.values():
                batch.use_program(program)
        p = self.program
        frame.apply(p, self.technique_color)
        if self.facing is not None:
            self.facing.use(frame.light, frame.wind.enabled, draft=frame.draft)
            p["u_facing"].value = FACING_UNIT
        bind_slopes(p, self.slope, frame.light, draft=frame.draft)
        p["u_density_channel"].value = self.density_channel
        p["u_under"].value = tuple(1.0 if c in self.under_channels else 0.0 for c in range(4))
        p["u_lift"].value = self.layer_height()
        if reads(p, "u_grass_height"):  # the wind's bend (_wind.glsl): still air reads neither
            p["u_grass_height"].value = float(self.textures.height)
            p["u_canopy"].value = self.canopy
        p["u_level_colors"].write(np.ascontiguousarray(self.textures.level_colors, np.float32))
        own, over = self.level_shade(frame.light.blade_ao_height)
        p["u_level_shade"].write(np.ascontiguousarray(own, np.float32))
        p["u_over_shade"].write(np.ascontiguousarray(over, np.float32))
        canopy = self.textures.canopy
        p["u_top_depth"].value = -float(np.log(max(1.0 - self.textures.top_alpha, 1e-4)))
        p["u_side_column"].value = canopy.side_column()
        p["u_over_column"].value = canopy.side_column(self.under.height) if self.under else 0.0
        if self.under_channels and self.under is not None:
            colours = self.over_colors()
            p["u_over_colors"].write(np.ascontiguousarray(colours, np.float32))
        p["u_top_mean"].value = tuple(float(v) for v in self.textures.top.mean_color)
        p["u_density"].value = float(self.density)
        p["u_epsilon"].value = self.epsilon
        if reads(p, "u_fade"):  # the transitions' distances, per blade or sample (_lod.glsl)
            p["u_fade"].value = self.fade
        p["u_top_spread"].write(spread_levels(self.textures.top.spread))
        p["u_mean_normal"].value = tuple(float(v) for v in self.textures.top.mean_normal)
        p["u_top_color"].value = 0
        p["u_top_data"].value = 1
        self.textures.top.color.use(0)
        self.textures.top.data.use(1)
        self.ctx.enable(moderngl.DEPTH_TEST)

    def draw(self) -> None:
        if self.textures is not None:
            for batch in self.batches.values():
                batch.draw()

    def finalize(self) -> None:
        """Nothing to undo: the shader sets the samples its fragments cover."""

    def release(self) -> None:
        for batch in self.batches.values():
            batch.release()
