"""Volume-based grass renderer (thesis 5.2): prepare / draw / finalize.

One cuboid carrier per (macro-)cell instance, all instances in one instanced draw, back faces
culled; the fragment shader ray-casts through the slices (shaders/volume.glsl). On a slope the
cuboid's bottom and top follow the ground's plane (core/terrain.py planes_of, a second
per-instance buffer) instead of spanning its whole height range.
"""

from __future__ import annotations

import math

import moderngl
import numpy as np

from core.lod import NO_FADE
from core.occupancy import DensityOccupancy
from core.terrain import Terrain
from render.buffers import InstancedRenderer
from render.facing import FACING_UNIT, FacingTable, SlopeTable, bind_slopes
from render.shaders import load_program, reads
from render.slices import SliceTextures, spread_levels
from render.uniforms import GROUND_UNIT, FrameUniforms

# 8 corners of the unit cube and its 12 triangles, wound counter-clockwise seen from outside.
_CORNERS = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=np.float32)
_FACES = np.array(
    [0, 2, 1, 1, 2, 3,  4, 5, 6, 5, 7, 6,  0, 1, 4, 1, 5, 4,
     2, 6, 3, 3, 6, 7,  0, 4, 2, 2, 4, 6,  1, 3, 5, 3, 7, 5],
    dtype=np.uint32,
)  # fmt: skip


def carriers(
    terrain: Terrain, occupancy: DensityOccupancy | None, channel: int, instances: np.ndarray
) -> np.ndarray:
    """(n, 8) float32 per instance: the planes its cuboid lies between (Terrain.planes_of)
    and the rectangle of its cells where the grass of density `channel` can grow
    (DensityOccupancy.rects; the whole block without an occupancy)."""
    out = np.empty((len(instances), 8), np.float32)
    out[:, :4] = terrain.planes_of(instances)
    out[:, 4:6] = 0.0
    out[:, 6:] = instances["size"]
    if occupancy is not None and len(instances):
        out[:, 4:] = occupancy.rects(channel, *terrain.blocks_of(instances))
    return out


class VolumeRenderer(InstancedRenderer):
    epsilon = 0.05  # LOD crossover window (eq. 5.26)
    fade = NO_FADE  # the level's transitions' distances (core/lod.py fades), set per frame
    density_channel = 0  # the grass type's channel of the density map (render/layer.py)
    technique_color = (1.0, 0.85, 0.1)  # --view techniques (thesis Figs. 7.1-7.6)
    max_steps = 12
    skip_steps = 8  # height-map steps over empty space in extruded cuboids (volume.glsl)
    opaque = 0.95
    # The horizontal slice is a layer of the volume at this fraction of the grass height: rays
    # from above meet it where, among vertical slices alone, they would fall between them
    # down to the roots and look too dark (steep views; thesis 5.2 has vertical slices only).
    floor: float | None = 0.5
    # the density channels of the grass types growing beneath this one (render/frame.py):
    # where their grass grows, a ray that passes this type's slices meets their volume below,
    # not this type's layer, which would cover them with its own top view
    under_channels: tuple[int, ...] = ()
    # the heights over the ground a pass counts (grass types that grow among each other are
    # drawn in bands of height: render/volume_order.py)
    band = (0.0, float("inf"))
    # the cells of the frame, far to near, and their distances (render/grass_type.py upload)
    cells: np.ndarray | None = None
    distances: np.ndarray | None = None
    # per cell, the ground's slope and the lowest and highest ground over it (core/terrain.py
    # planes_of), and the rectangle where the grass grows in it (carriers): the cuboid's
    # bottom and top follow the slope, its walls that rectangle; None: level, whole cuboids
    carrier_rows: np.ndarray | None = None
    # the second instance buffer: those planes and that rectangle (render/buffers.py)
    rows_layout = ("4f 4f/i", ("in_plane", "in_rect"))

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "volume.glsl")
        self.vbo = ctx.buffer(_CORNERS.tobytes())
        self.ibo = ctx.buffer(_FACES.tobytes())
        self.instances: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self.instance_count = 0
        self.textures: SliceTextures | None = None
        self._owned = False
        self.slices = 0
        self.density = 1.0
        self.facing: FacingTable | None = None  # set by the grass type (render/grass_type.py)
        self.slope: SlopeTable | None = None  # the same

    def set_slices(self, textures: SliceTextures | None, owned: bool = True) -> None:
        """The slices to draw. With owned=False the caller keeps and releases them."""
        if self.textures is not None and self._owned and self.textures is not textures:
            self.textures.release()
        self.textures = textures
        self._owned = owned
        self.slices = textures.slices if textures is not None else 0

    def carriers_of(self, part: slice) -> np.ndarray | None:
        """The carrier rows of `cells[part]` (None: level cuboids over whole cells)."""
        return None if self.carrier_rows is None else self.carrier_rows[part]

    def default_rows(self, instances: np.ndarray) -> np.ndarray:
        """Level cuboids over each cell's height range and over the whole cell."""
        rows = np.zeros((instances.size, 8), np.float32)
        rows[:, 3] = instances["ground"][:, 1]
        rows[:, 6:] = instances["size"]
        return rows

    def _make_vao(self) -> moderngl.VertexArray:
        return self.ctx.vertex_array(
            self.program,
            self._buffers((self.vbo, "3f", "in_corner")),
            index_buffer=self.ibo,
            index_element_size=4,
        )

    def prepare(self, frame: FrameUniforms) -> None:
        t = self.textures
        if t is None:
            return
        # the horizontal slice's height; none in a band pass whose heights leave it out (the
        # shader would find where its rays cross it only to count nothing there)
        floor = -1.0 if self.floor is None else self.floor * float(t.height)
        if not self.band[0] <= floor < min(self.band[1], float(t.height) + 1.0):
            floor = -1.0
        defines = frame.defines + (("FLOOR",) if floor >= 0.0 else ())
        self.use_program(load_program(self.ctx, "volume.glsl", defines))
        p = self.program
        frame.apply(p, self.technique_color)
        p["u_ground"].value = GROUND_UNIT + self.density_channel
        p["u_height"].value = float(t.height)
        p["u_density"].value = float(self.density)
        p["u_epsilon"].value = self.epsilon
        if reads(p, "u_fade"):  # the transitions' distances, per blade or sample (_lod.glsl)
            p["u_fade"].value = self.fade
        p["u_side_spread"].write(spread_levels(t.sides.spread))
        p["u_slices"].value = float(self.slices)
        p["u_max_steps"].value = self.max_steps
        p["u_opaque"].value = self.opaque
        p["u_band"].value = (self.band[0], min(self.band[1], 1e9))
        pixel = 2.0 * math.tan(math.radians(frame.fov_y) / 2.0) / max(frame.viewport_height, 1)
        p["u_lod_scale"].value = pixel * t.sides.color.width
        p["u_pixel"].value = pixel
        if floor >= 0.0:  # the horizontal slice and the run the crossings leave uncounted
            self._floor_uniforms(floor, frame)
        p["u_skip_steps"].value = self.skip_steps
        # how short averaging makes a normal at most (shaders/volume.glsl blends by it)
        p["u_side_mean_length"].value = min(float(np.linalg.norm(t.sides.mean_normal)), 0.99)
        if self.facing is not None:
            self.facing.use(frame.light, frame.wind.enabled, draft=frame.draft)
            p["u_facing"].value = FACING_UNIT
        bind_slopes(p, self.slope, frame.light, draft=frame.draft)
        if t.sides.depths is None:
            raise ValueError("vertical slices uploaded without their rows' depths")
        for unit, (name, tex) in enumerate(
            [
                ("u_side_color", t.sides.color),
                ("u_side_data", t.sides.data),
                ("u_top_color", t.top.color),
                ("u_top_data", t.top.data),
                ("u_side_depths", t.sides.depths),  # unit 4: free (render/uniforms.py)
            ]
        ):
            if reads(p, name):  # a pass without the horizontal slice reads no top view
                p[name].value = unit
                tex.use(unit)
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE | moderngl.BLEND)
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        self.ctx.fbo.depth_mask = False

    def _floor_uniforms(self, floor: float, frame: FrameUniforms) -> None:
        """What a pass with the horizontal slice reads of it: its height, its top view's
        spread and mip offset, AO_blade of what it shows, the grass beneath, and the blades'
        depth and colour from the side over the pass's heights (volume.glsl missed_blades)."""
        p, t = self.program, self.textures
        assert t is not None
        p["u_floor"].value = floor
        p["u_top_spread"].write(spread_levels(t.top.spread))
        p["u_top_lod_offset"].value = math.log2(t.top.color.width / t.sides.color.width)
        p["u_floor_shade"].value = t.canopy.top_shade(frame.light.blade_ao_height)
        p["u_under"].value = tuple(1.0 if c in self.under_channels else 0.0 for c in range(4))
        top = min(self.band[1], float(t.height))
        column = t.canopy.side_column(self.band[0]) - t.canopy.side_column(top)
        p["u_band_column"].value = max(column, 0.0)
        p["u_side_colors"].write(np.ascontiguousarray(t.canopy.side_colors, np.float32))

    def draw(self) -> None:
        if self.vao is not None and self.textures is not None and self.instance_count:
            self.vao.render(moderngl.TRIANGLES, instances=self.instance_count)

    def finalize(self) -> None:
        self.ctx.disable(moderngl.CULL_FACE | moderngl.BLEND)
        self.ctx.fbo.depth_mask = True
        self.ctx.blend_func = moderngl.DEFAULT_BLENDING

    def release(self) -> None:
        self._release_vaos()
        for obj in (self.instances, self.rows_buffer, self.vbo, self.ibo):
            if obj is not None:
                obj.release()
        if self.textures is not None and self._owned:
            self.textures.release()
