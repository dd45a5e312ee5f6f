"""The ground under the grass (part of t_m, the rest of the scenery): a large plane and, on
uneven terrain, a grid over the grassed cells that follows the height map (6.4.4)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import moderngl
import numpy as np

from core.ground_mesh import GROUND_CHUNKS, chunked_mesh
from core.lighting import Lighting
from render.design_maps import DesignMapTextures
from render.shaders import load_program
from render.uniforms import SINK_UNIT, FrameUniforms

if TYPE_CHECKING:
    from render.shadows import GroundShadows

MAX_TYPES = 4  # grass types whose shadows the ground takes (render/shadows.py)


def chunk_levels(
    lo: np.ndarray, hi: np.ndarray, deviation: np.ndarray, frame: FrameUniforms
) -> np.ndarray:
    """Per chunk (rows along v), the level to draw it at: the coarsest that moves its ground
    by under half a pixel seen from the eye at its nearest point (never less than the finest
    already does); -1 where it lies outside the view. lo, hi: the lowest and highest corner
    (x, y, z) of its box, each (chunks, chunks, 3); deviation: (levels, chunks, chunks), what
    each level moves its ground by (GroundChunks.deviation), all in world units."""
    eye = np.asarray(frame.eye, np.float64)
    gap = np.maximum(np.maximum(lo - eye, eye - hi), 0.0)
    pixel = 2.0 * np.tan(np.radians(frame.fov_y) / 2.0) / max(frame.viewport_height, 1)
    allowed = np.maximum(0.5 * pixel * np.linalg.norm(gap, axis=-1), deviation[0])
    level = np.zeros(allowed.shape, np.int64)
    for k in range(1, deviation.shape[0]):
        level[deviation[k] <= allowed] = k
    # outside the view: every corner of its box beyond one plane of the clip volume
    corners = np.stack(
        [np.stack([xs, ys, zs], -1) for xs in (lo[..., 0], hi[..., 0])
         for ys in (lo[..., 1], hi[..., 1]) for zs in (lo[..., 2], hi[..., 2])], axis=-2
    )  # fmt: skip
    clip = (
        np.concatenate([corners, np.ones((*corners.shape[:-1], 1))], -1)
        @ np.asarray(frame.view_proj, np.float64).T
    )
    w = clip[..., 3:4]
    outside = np.concatenate([clip[..., :3] > w, clip[..., :3] < -w], -1).all(axis=-2).any(-1)
    level[outside] = -1
    return level


class GroundRenderer:
    extent = 2000.0

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = load_program(ctx, "ground.glsl")
        corners = np.array([-1, -1, 1, -1, -1, 1, 1, 1], dtype=np.float32)
        self.vbo = ctx.buffer(corners.tobytes())
        # the plane's vertex array for each program variant drawn with (the light maps' define)
        self._plane: dict[moderngl.Program, moderngl.VertexArray] = {}
        # the grid over the grassed cells at each of its levels (core/ground_mesh.py mesh_levels),
        # in chunks: quads -> its buffers, each chunk's run of indices and a vertex array per
        # program variant
        self.meshes: dict[tuple[int, int], tuple[list, np.ndarray, dict]] = {}
        self.chunks_drawn: np.ndarray | None = None  # each chunk's level last frame (-1: none)
        self.grass_rect = (0.0, 0.0, 0.0, 0.0)
        # the soil under the grass, shaded by it (diagnostics draw it black to see the grass)
        self.under_grass = tuple(0.55 * c for c in (0.30, 0.30, 0.12))
        # where no blades cast shadows, what they would take (render/shadows.py); None: off
        self.shadows: GroundShadows | None = None
        # the shadows' fields as texture layers, and the fields they were made from
        self._shadow_field: moderngl.TextureArray | None = None
        self._field_of: tuple = ()

    def _mesh(self, quads: tuple[int, int]) -> tuple[moderngl.VertexArray, np.ndarray]:
        if quads not in self.meshes:
            verts, indices, ranges = chunked_mesh(*quads, GROUND_CHUNKS)
            buffers = [self.ctx.buffer(verts.tobytes()), self.ctx.buffer(indices.tobytes())]
            self.meshes[quads] = (buffers, ranges, {})
        (vbo, ibo), ranges, vaos = self.meshes[quads]
        if self.program not in vaos:
            vaos[self.program] = self.ctx.vertex_array(
                self.program,
                [(vbo, "2f 1f", "in_corner", "in_drop")],
                index_buffer=ibo,
                index_element_size=4,
            )
        return vaos[self.program], ranges

    def _release_mesh(self, keep: list[tuple[int, int]] | None = None) -> None:
        """Release the meshes of every level (but those of `keep`)."""
        for quads in [q for q in self.meshes if keep is None or q not in keep]:
            buffers, _, vaos = self.meshes.pop(quads)
            for obj in (*vaos.values(), *buffers):
                obj.release()

    def _draw_mesh(self, frame: FrameUniforms, maps: DesignMapTextures) -> None:
        """The grid over the grassed cells, each chunk at its level (chunk_levels)."""
        p = self.program
        sinks, levels, chunks = maps.ground_levels()
        self._release_mesh(keep=levels)  # another map's levels: let go
        scale = frame.height_scale
        x0, z0, x1, z1 = self.grass_rect
        c = GROUND_CHUNKS
        xs, zs = np.linspace(x0, x1, c + 1), np.linspace(z0, z1, c + 1)
        margin = scale * chunks.deviation.max(axis=0)
        lo = np.stack(
            np.broadcast_arrays(xs[None, :-1], scale * chunks.low - margin, zs[:-1, None]), -1
        )
        hi = np.stack(np.broadcast_arrays(xs[None, 1:], scale * chunks.high, zs[1:, None]), -1)
        drawn = chunk_levels(lo, hi, scale * chunks.deviation, frame)
        self.chunks_drawn = drawn
        # a crack between two chunks is at most both levels' deviations wide
        p["u_skirt"].value = 2.0 * float(scale * chunks.deviation.max()) + 1e-3
        p["u_mesh"].value = 1.0
        p["u_sink_map"].value = SINK_UNIT
        for k, (texture, quads) in enumerate(zip(sinks, levels, strict=True)):
            mine = np.flatnonzero(drawn.ravel() == k)
            if mine.size == 0:
                continue
            texture.use(SINK_UNIT)
            vao, ranges = self._mesh(quads)
            firsts, counts = ranges.reshape(-1, 2)[mine].T
            # chunks next to each other in the index buffer are drawn in one call
            breaks = np.flatnonzero(firsts[1:] != firsts[:-1] + counts[:-1]) + 1
            for run in np.split(np.arange(mine.size), breaks):
                first, last = run[0], run[-1]
                total = int(firsts[last] + counts[last] - firsts[first])
                vao.render(moderngl.TRIANGLES, vertices=total, first=int(firsts[first]))

    def _field_texture(self, shadows: GroundShadows) -> moderngl.TextureArray:
        """The shadows' fields as a mipmapped texture array, uploaded when they change (a new
        sun or patch): a mip level's texel holds the mean of the texels it covers, and the last
        level the cell's mean. Eight bits a share: a 255th of the sun's share at most."""
        same = len(shadows.fields) == len(self._field_of) and all(
            a is b for a, b in zip(shadows.fields, self._field_of, strict=False)
        )
        if same and self._shadow_field is not None:
            return self._shadow_field
        layers = shadows.layers()
        size = (layers.shape[2], layers.shape[1], layers.shape[0])
        if self._shadow_field is None or self._shadow_field.size != size:
            if self._shadow_field is not None:
                self._shadow_field.release()
            self._shadow_field = self.ctx.texture_array(size, 4)
            self._shadow_field.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        self._shadow_field.write(layers.tobytes())
        self._shadow_field.build_mipmaps()
        self._field_of = shadows.fields
        return self._shadow_field

    def soil_uniforms(self, light: Lighting) -> dict:
        """shaders/_soil.glsl's uniforms: the ground's colour here and under blade shadows."""
        return {
            "u_soil_color": light.soil_color,
            "u_under_grass": self.under_grass,
            "u_fog_color": light.sky_color,
            "u_fog_distance": light.fog_distance,
            "u_grass_rect": self.grass_rect,
        }

    def draw(self, frame: FrameUniforms, maps: DesignMapTextures | None = None) -> None:
        """The plane, and on uneven ground (with `maps`) the grid over the grassed cells, each
        vertex sunk so that the grid lies under the ground the grass stands on."""
        defines = ("LIGHT_MAPS",) if frame.light_maps else ()
        defines += ("SHADOWS",) if self.shadows is not None else ()
        self.program = load_program(self.ctx, "ground.glsl", defines)
        if self.program not in self._plane:
            self._plane[self.program] = self.ctx.vertex_array(
                self.program, [(self.vbo, "2f", "in_corner")]
            )
        frame.apply(self.program)
        p = self.program
        p["u_extent"].value = self.extent
        for name, value in self.soil_uniforms(frame.light).items():
            p[name].value = value
        if self.shadows is not None:
            self.shadows.apply(p, self._field_texture(self.shadows))
        self.ctx.enable(moderngl.DEPTH_TEST)
        # pushed back a little in depth: grass lying on it (the image-based quads, the volume's
        # floor) must win over the soil even far away, where depth precision is coarse
        self.ctx.polygon_offset = (2.0, 4.0)
        uneven = frame.height_scale > 0
        p["u_mesh"].value = 0.0
        # on uneven ground the plane sinks a little so the grid over the cells lies on top
        p["u_sink"].value = 0.02 if uneven else 0.0
        self._plane[self.program].render(moderngl.TRIANGLE_STRIP)
        if uneven and maps is not None:
            self._draw_mesh(frame, maps)
        self.ctx.polygon_offset = (0.0, 0.0)

    def release(self) -> None:
        self._release_mesh()
        if self._shadow_field is not None:
            self._shadow_field.release()
        for vao in self._plane.values():
            vao.release()
        self.vbo.release()
