"""GL mirror of the design-map stack (core/design_maps.py): one RGBA texture array, one layer a
map, linearly filtered (thesis 6.4.1: smooth transitions). Beside it, for each density channel a
two-channel texture of the height and that channel's density: the volume's rays read both at every
step, and one fetch of one texture costs half of two fetches of the array on llvmpipe.

Edits upload only their rectangle, and not at once: a map may be edited while no GL context is
current (a brush stroke from a mouse event), so each edit grows the pending dirty rectangle of
its map, and `flush` (called by `use`, i.e. when a frame is drawn) uploads it. The dabs of one
mouse move become one upload.

The far representations read the colour map as a pixel's footprint on the ground sees it: a
mipmapped copy of it (a field marking a texel wide, read at the base level far away, breaks into
dots). An edit redoes its levels over the edit's rectangle only, as GL's mipmap generation
filters them: a brush dab on a 2048² map does not rebuild the whole chain. The stack itself
stays without mip levels: on llvmpipe a mipmapped sampler costs the ground pass several times
over even at level 0."""

from __future__ import annotations

import hashlib
from concurrent.futures import Future
from dataclasses import dataclass

import moderngl
import numpy as np

from core.design_maps import LAYER_INDEX, DesignMaps, Rect, union
from core.ground_mesh import (
    GROUND_CHUNKS,
    chunk_deviation,
    chunked_mesh,
    mesh_heights,
    mesh_levels,
    mesh_sink,
    quad_excess,
    vertex_sink,
)
from core.mipmaps import mip_sizes, reduce_rect
from core.trample import largest_lean
from render import derived_cache
from render.uniforms import DESIGN_UNIT, FAR_DESIGN_UNIT, GROUND_UNIT

DENSITY, HEIGHT = LAYER_INDEX["density"], LAYER_INDEX["height"]
COLOR = LAYER_INDEX["color"]
TRAMPLE = LAYER_INDEX["trample"]
LIGHT_LAYERS = (LAYER_INDEX["ambient"], LAYER_INDEX["diffuse"])


@dataclass(frozen=True)
class GroundChunks:
    """The ground mesh's chunks (core/ground_mesh.py GROUND_CHUNKS per side, rows along v), in
    height-map units: how far drawing each at each level moves its ground at most (core/
    ground_mesh.py chunk_deviation), and the lowest and highest its finest level reaches."""

    deviation: np.ndarray  # (levels, chunks along v, chunks along u)
    low: np.ndarray  # (chunks along v, chunks along u)
    high: np.ndarray

    @classmethod
    def of(cls, heights: np.ndarray, levels: list[tuple[int, int]], sinks: list[np.ndarray]):
        deviation = chunk_deviation(heights, levels, sinks)
        fine = mesh_heights(heights, levels[0], sinks[0])
        c = deviation.shape[1]
        nv, nu = fine.shape[0] - 1, fine.shape[1] - 1
        lo = np.minimum(
            np.minimum(fine[:-1, :-1], fine[1:, :-1]), np.minimum(fine[:-1, 1:], fine[1:, 1:])
        )
        hi = np.maximum(
            np.maximum(fine[:-1, :-1], fine[1:, :-1]), np.maximum(fine[:-1, 1:], fine[1:, 1:])
        )
        shape = (c, nv // c, c, nu // c)  # each quad's lowest and highest corner, per chunk
        return cls(
            deviation, lo.reshape(shape).min(axis=(1, 3)), hi.reshape(shape).max(axis=(1, 3))
        )


def _ground_arrays(
    heights: np.ndarray, levels: list[tuple[int, int]]
) -> tuple[list[tuple[np.ndarray, np.ndarray]], GroundChunks]:
    """Per level of the ground mesh its sink and per-quad excess (kept by the heights they are
    of), and its chunks; each level's chunked mesh made ready (render/ground.py draws them)."""
    sinks = []
    of_heights = hashlib.blake2b(np.ascontiguousarray(heights).tobytes(), digest_size=16)
    for quads in levels:
        digest = of_heights.copy()
        digest.update(np.asarray(quads, np.int64).tobytes())
        made = derived_cache.fetch(
            "sink", digest.hexdigest(), lambda q=quads: mesh_sink(heights, q)
        )
        assert made is not None
        if made[1].shape != (quads[1], quads[0]):  # not this mesh's: made again
            made = mesh_sink(heights, quads)
        sinks.append(made)
    chunks = GroundChunks.of(heights, levels, [vertex_sink(e) for _, e in sinks])
    for quads in levels:
        chunked_mesh(*quads, GROUND_CHUNKS)
    return sinks, chunks


class DesignMapTextures:
    def __init__(self, ctx: moderngl.Context, maps: DesignMaps) -> None:
        self.ctx = ctx
        self.maps = maps
        w, h = maps.size
        layers = maps.stack.shape[0]
        data = maps.stack.astype(np.float16).tobytes()
        self.texture = ctx.texture_array((w, h, layers), 4, data, dtype="f2")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = False
        self.texture.repeat_y = False
        self.far = ctx.texture((w, h), 4, self._far_texels((0, 0, w, h)), dtype="f2")
        self.far.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        self.far.repeat_x = False
        self.far.repeat_y = False
        self.far.build_mipmaps()
        # its levels as GL made them, read back at the first edit, which then redoes only the
        # texels over its rectangle
        self._far_levels: list[np.ndarray] = []
        self.uploaded_texels = w * h * layers  # for tests and the profiler: what went to the GPU
        self.pending: dict[int, Rect] = {}  # layer index -> dirty rectangle not yet uploaded
        self.grounds: dict[int, moderngl.Texture] = {}  # density channel -> (height, density)
        # the ground mesh's levels (core/ground_mesh.py mesh_levels): each one's sink per vertex,
        # its per-quad excess (core/ground_mesh.py), and what each chunk moves by at each level
        self._sinks: list[moderngl.Texture] = []
        self._excess: list[np.ndarray] = []
        self._chunks: GroundChunks | None = None
        self._ahead: Future | None = None  # ground_ahead's sinks and chunks
        # whether a light map holds anything but ones (FrameUniforms.light_maps): checked once,
        # and from the first edit of either on, painted (an undo back to ones keeps it so)
        self.light_maps = any(bool(np.any(maps.stack[i][..., :3] != 1.0)) for i in LIGHT_LAYERS)
        # the most the trample map lays grass over (FrameUniforms.trample_lean): the whole map
        # once, then what each edit's rectangle holds (an undo keeps it, as for the light maps)
        self.trample_lean = largest_lean(maps.stack[TRAMPLE])
        maps.changed.connect(self.update)

    def _far_texels(self, rect: Rect) -> bytes:
        """A rectangle of the colour map for the mipmapped copy, its RGB times its weight, so
        that a mip level's mean mixes the blades' colour as the mean of its texels would (a
        white line's share of a far pixel)."""
        x, y, w, h = rect
        texels = self.maps.stack[COLOR, y : y + h, x : x + w]
        weighted = np.concatenate([texels[..., :3] * texels[..., 3:], texels[..., 3:]], axis=-1)
        return np.ascontiguousarray(weighted.astype(np.float16)).tobytes()

    def _update_far(self, rect: Rect) -> None:
        """The mipmapped colour map over `rect`: its base level, then at each level the texels
        whose filter reads what changed below them (core/mipmaps.py reduce_rect), as GL's
        mipmap generation would make them, without making the whole chain again."""
        if not self._far_levels:
            self._far_levels = [
                np.frombuffer(self.far.read(level=level), np.float16).reshape(lh, lw, 4).copy()
                for level, (lw, lh) in enumerate(mip_sizes(*self.maps.size))
            ]
        x, y, w, h = rect
        levels = self._far_levels
        levels[0][y : y + h, x : x + w] = np.frombuffer(self._far_texels(rect), np.float16).reshape(
            h, w, 4
        )
        self.far.write(levels[0][y : y + h, x : x + w].tobytes(), viewport=rect)
        for level in range(1, len(levels)):
            rect, values = reduce_rect(levels[level - 1], rect, levels[level].shape[:2])
            x, y, w, h = rect
            levels[level][y : y + h, x : x + w] = values
            self.far.write(
                levels[level][y : y + h, x : x + w].tobytes(), viewport=rect, level=level
            )

    def _ground_texels(self, channel: int, rect: Rect) -> bytes:
        x, y, w, h = rect
        out = np.empty((h, w, 2), np.float16)
        out[..., 0] = self.maps.stack[HEIGHT, y : y + h, x : x + w, 0]
        out[..., 1] = self.maps.stack[DENSITY, y : y + h, x : x + w, channel]
        return out.tobytes()

    def ground(self, channel: int) -> moderngl.Texture:
        """The height map and one density channel in one texture (made at first use)."""
        texture = self.grounds.get(channel)
        if texture is None:
            w, h = self.maps.size
            texture = self.ctx.texture(
                (w, h), 2, self._ground_texels(channel, (0, 0, w, h)), dtype="f2"
            )
            texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
            texture.repeat_x = False
            texture.repeat_y = False
            self.grounds[channel] = texture
        return texture

    def mesh_sink(self) -> tuple[moderngl.Texture, tuple[int, int]]:
        """How far each vertex of the ground mesh's finest level sinks to lie under the grass's
        ground, and its quads per side (ground_levels)."""
        textures, levels = self.ground_levels()[:2]
        return textures[0], levels[0]

    def ground_ahead(self) -> None:
        """Begin making the ground mesh's sinks and chunks (ground_levels) beside the set-up
        (derived_cache.beside): a renderer of uneven ground draws it in its first frame."""
        if not self._sinks and self._ahead is None:
            heights = self.maps.stack[HEIGHT, ..., 0].copy()  # edits may follow on this thread
            self._ahead = derived_cache.beside(_ground_arrays, heights, mesh_levels(self.maps.size))

    def ground_levels(self) -> tuple[list[moderngl.Texture], list[tuple[int, int]], GroundChunks]:
        """Per level of the ground mesh (core/ground_mesh.py mesh_levels), how far each vertex
        sinks to lie under the grass's ground (core/ground_mesh.py mesh_sink), and its quads per
        side; and its chunks' extents. Made at first use (or begun ahead), the rows an edit
        reaches redone when heights change; kept between runs by the heights they are of
        (render/derived_cache.py)."""
        levels = mesh_levels(self.maps.size)
        if not self._sinks:
            ahead, self._ahead = self._ahead, None
            made = ahead.result() if ahead is not None else None
            if made is None:
                made = _ground_arrays(self.maps.stack[HEIGHT, ..., 0], levels)
            sinks, self._chunks = made
            for quads, (sink, excess) in zip(levels, sinks, strict=True):
                self._excess.append(excess.copy())  # its rows are redone in place after an edit
                texture = self.ctx.texture(
                    (quads[0] + 1, quads[1] + 1), 1, sink.tobytes(), dtype="f4"
                )
                texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
                self._sinks.append(texture)
        if self._chunks is None:
            heights = self.maps.stack[HEIGHT, ..., 0]
            sinks = [vertex_sink(e) for e in self._excess]
            self._chunks = GroundChunks.of(heights, levels, sinks)
        return self._sinks, levels, self._chunks

    def _update_sink(self, rect: Rect) -> None:
        """Redo the quad rows of each level of the ground mesh that the height texels in
        `rect` reach."""
        if not self._sinks:
            return
        heights = self.maps.stack[HEIGHT, ..., 0]
        texel_rows = self.maps.size[1]
        for (nu, nv), excess, texture in zip(
            mesh_levels(self.maps.size), self._excess, self._sinks, strict=True
        ):
            b0 = max(int(np.floor((rect[1] - 1) * nv / texel_rows)), 0)
            b1 = min(int(np.ceil((rect[1] + rect[3] + 1) * nv / texel_rows)), nv)
            if b1 > b0:
                excess[b0:b1] = quad_excess(heights, (nu, nv), (b0, b1))
                texture.write(vertex_sink(excess).tobytes())
        self._chunks = None

    def update(self, name: str, rect: Rect) -> None:
        """Note a changed rectangle of one map; the next `flush` uploads it."""
        if rect[2] > 0 and rect[3] > 0:
            i = LAYER_INDEX[name]
            if i == HEIGHT:
                self._ahead = None  # of the heights before
            self.pending[i] = union(self.pending.get(i), rect)
            if i in LIGHT_LAYERS:
                self.light_maps = True
            if i == TRAMPLE:
                x, y, w, h = rect
                lean = largest_lean(self.maps.stack[TRAMPLE, y : y + h, x : x + w])
                self.trample_lean = max(self.trample_lean, lean)

    def flush(self) -> None:
        """Upload the dirty rectangle of every edited map (the context must be current)."""
        self.uploaded_texels = 0
        for i, (x, y, w, h) in self.pending.items():
            data = np.ascontiguousarray(self.maps.stack[i, y : y + h, x : x + w].astype(np.float16))
            self.texture.write(data.tobytes(), viewport=(x, y, i, w, h, 1))
            self.uploaded_texels += w * h
        if COLOR in self.pending:
            self._update_far(self.pending[COLOR])
        rect = None
        for i in (DENSITY, HEIGHT):
            if i in self.pending:
                rect = union(rect, self.pending[i])
        if rect is not None:
            for channel, texture in self.grounds.items():
                texture.write(self._ground_texels(channel, rect), viewport=rect)
        if HEIGHT in self.pending:
            self._update_sink(self.pending[HEIGHT])
        self.pending.clear()

    def use(self, channels=()) -> None:
        """Bind the stack where every program's u_design looks (FrameUniforms sets the unit),
        and the height + density texture of each of `channels` at GROUND_UNIT + channel, after
        uploading what changed since the last frame."""
        if self.pending:
            self.flush()
        self.texture.use(DESIGN_UNIT)
        self.far.use(FAR_DESIGN_UNIT)
        for channel in channels:
            self.ground(channel).use(GROUND_UNIT + channel)

    def release(self) -> None:
        self.maps.changed.disconnect(self.update)
        self.texture.release()
        self.far.release()
        for texture in self.grounds.values():
            texture.release()
        for texture in self._sinks:
            texture.release()
