"""Patch conversion (thesis 4.2.1): render the geometry patch into slices.

Vertical slices: N slabs across x and N across z. Each slab [i/N, (i+1)/N] is drawn between two
clip planes by an orthographic camera looking along the axis, onto an image whose u runs along
the other horizontal axis and v up the patch height. The horizontal slice: the whole patch from
above. The patch's neighbouring tiles are drawn too, so blades of the next tile that lean into the
square are captured and the slices tile seamlessly like the geometry does; but each slab draws
only the blades that reach it (one run of indices per slab and tile offset), not the whole patch
nine times, which made conversion cost 9× the patch's vertices per slice.

Every slice keeps: albedo + alpha, patch-space normal, density threshold and the height of what
each texel shows. The results are numpy arrays, row 0 at the ground (v = 0) for vertical slices
and at z = 0 for the horizontal slice.
"""

from __future__ import annotations

from collections.abc import Generator
from dataclasses import dataclass, replace

import moderngl
import numpy as np

from core.camera import look_at, orthographic
from core.canopy import BladeDepths
from core.grid import INSTANCE_DTYPE
from core.lighting import Lighting
from core.patch import GrassPatch
from render.context import release_framebuffer
from render.geometry import GeometryRenderer
from render.uniforms import FrameUniforms

GL_CLIP_DISTANCE0 = 0x3000


@dataclass
class SliceLayers:
    color: np.ndarray  # (n, h, w, 4) float32, albedo + alpha
    normal: np.ndarray  # (n, h, w, 3) float32, unit normals in patch space
    threshold: np.ndarray  # (n, h, w) float32, 0 where empty
    height: np.ndarray  # (n, h, w) float32: the height over the ground of what a texel shows


@dataclass
class SlicedPatch:
    x: SliceLayers  # slabs across x; u runs along z
    z: SliceLayers  # slabs across z; u runs along x
    top: SliceLayers  # one slice, n = 1
    height: float
    blades: BladeDepths | None = None  # the blades' depths from the side and above (core/canopy.py)


def _tiles(offsets) -> np.ndarray:
    """Instances of the patch at the given (x, z) tile offsets."""
    inst = np.zeros(len(offsets), dtype=INSTANCE_DTYPE)
    inst["origin"] = np.asarray(offsets, np.float32).reshape(-1, 2)
    inst["density"] = 1.0
    inst["lod"] = (2.0, 0.0)
    inst["size"] = 1.0
    inst["mirror"] = 1.0
    inst["config"] = (0.5, 0.5, 0.0, 0.0)  # design maps are applied when drawing, not here
    return inst


@dataclass
class _BladeRuns:
    """One index buffer made of runs: each run the indices of exactly the blades of the patch
    that reach an interval along x or z (a slab, moved by a tile offset), so a slab draws
    those and no others (a run of blades sorted along the axis, bounded by the widest blade,
    drew many that never reach the slab)."""

    blades: np.ndarray  # (blades, indices per blade): the patch's triangle indices
    extent: dict[int, tuple[np.ndarray, np.ndarray]]  # axis -> each blade's (lowest, highest)
    chunks: list[np.ndarray]
    size: int = 0

    @classmethod
    def of(cls, patch: GrassPatch) -> _BladeRuns:
        n = patch.roots.shape[0]
        extent = {}
        for axis in (0, 2):
            pos = patch.vertices["position"][:, axis].reshape(n, -1)
            extent[axis] = (pos.min(axis=1), pos.max(axis=1))
        return cls(patch.indices.reshape(n, -1), extent, [])

    def run(self, axis: int, lo: float, hi: float) -> tuple[int, int]:
        """(first index, index count) of a new run of the blades overlapping [lo, hi]."""
        low, high = self.extent[axis]
        chunk = self.blades[(low <= hi) & (high >= lo)].ravel()
        self.chunks.append(chunk)
        self.size += chunk.size
        return self.size - chunk.size, chunk.size

    def indices(self) -> np.ndarray:
        return np.concatenate(self.chunks) if self.chunks else np.zeros(0, np.uint32)


class PatchConverter:
    alpha_ref = 0.1

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.geometry = GeometryRenderer(ctx, program="slice_capture.glsl")
        self.geometry.set_instances(_tiles([(0.0, 0.0)] * 9))
        self._fbo: tuple[tuple[int, int], moderngl.Framebuffer, list] | None = None

    def convert(
        self, patch: GrassPatch, slices: int, size: tuple[int, int] = (256, 64), top_size: int = 128
    ) -> SlicedPatch:
        steps = self.steps(patch, slices, size, top_size)
        while True:
            try:
                next(steps)
            except StopIteration as done:
                return done.value

    def steps(
        self, patch: GrassPatch, slices: int, size: tuple[int, int] = (256, 64), top_size: int = 128
    ) -> Generator[tuple[int, int], None, SlicedPatch]:
        """The conversion one slice at a time: yields (done, total) after each capture and
        returns the SlicedPatch, so a window can keep responding between the captures."""
        runs = _BladeRuns.of(patch)
        across_x, across_z = _extent(patch)  # the patch's reach beyond its square
        plans = [
            self._plan(runs, slices, axis, across_z if axis == 0 else across_x) for axis in (0, 2)
        ]
        # from above: the whole tile, and of each neighbour the blades that reach into the square
        top_runs = [(runs.run(0, -np.inf, np.inf), [(0, 0)])]
        for ox, oz in [(ox, oz) for ox in (-1, 0, 1) for oz in (-1, 0, 1) if (ox, oz) != (0, 0)]:
            axis, t = (2, oz) if ox == 0 else (0, ox)
            other = across_x if ox == 0 else across_z
            if _overlaps(other, ox if ox == 0 else oz):
                top_runs.append((runs.run(axis, -t, 1.0 - t), [(ox, oz)]))
        self.geometry.set_patch(replace(patch, indices=runs.indices()))
        h = patch.height  # the tallest tip: slices and cuboids fit the grass, not the box
        total = 2 * slices + 1
        x = yield from self._layers(plans[0], slices, size, 0, h, done=0, total=total)
        z = yield from self._layers(plans[1], slices, size, 2, h, done=slices, total=total)
        self._begin((top_size, top_size))
        self._draw(
            orthographic(0.0, 1.0, -1.0, 0.0, 0.1, 10.0) @ look_at((0, h + 1.0, 0), (0, 0, 0)),
            (0, 0, top_size, top_size),
            None,
            None,
            top_runs,
        )
        top = self._read((top_size, top_size))
        yield total, total
        top = SliceLayers(*(a[None] for a in top))
        blades = BladeDepths.of(
            patch.vertices["position"], patch.vertices["uv"], patch.indices.reshape(-1, 3)
        )
        return SlicedPatch(x=x, z=z, top=top, height=h, blades=blades)

    @staticmethod
    def _plan(runs: _BladeRuns, n: int, axis: int, across) -> list[list]:
        """Per slab [i/n, (i+1)/n] along `axis`: (index run, tile offsets) pairs: per tile
        offset along the axis, the blades of that tile that reach the slab, drawn in the tiles
        beside it across the slice that reach into the square (`across`: the patch's extent
        across the slice)."""
        side = [s for s in (-1, 0, 1) if _overlaps(across, s)]
        plan = []
        for i in range(n):
            lo, hi = i / n, (i + 1) / n
            slab = []
            for t in (-1, 0, 1):
                first, count = runs.run(axis, lo - t, hi - t)
                if count:
                    slab.append(((first, count), [(t, s) if axis == 0 else (s, t) for s in side]))
            plan.append(slab)
        return plan

    def _layers(
        self,
        plan: list[list],
        n: int,
        size: tuple[int, int],
        axis: int,
        height: float,
        done: int,
        total: int,
    ) -> Generator[tuple[int, int], None, SliceLayers]:
        w, h = size
        self._begin((w, h * n))  # the family's slabs side by side in one target, read once
        for i in range(n):
            lo, hi = i / n, (i + 1) / n
            plane_lo = np.zeros(4, np.float32)
            plane_hi = np.zeros(4, np.float32)
            plane_lo[axis], plane_lo[3] = 1.0, -lo  # x >= lo
            plane_hi[axis], plane_hi[3] = -1.0, hi  # x <= hi
            if axis == 0:  # look along +x: screen right = +z
                view = look_at((lo - 2.0, 0, 0), (lo, 0, 0))
            else:  # look along -z from beyond the slab: screen right = +x
                view = look_at((0, 0, hi + 2.0), (0, 0, hi))
            proj = orthographic(0.0, 1.0, 0.0, height, 0.1, 10.0)
            self._target((w, h * n))[0].use()  # again: a frame may have been drawn between
            self._draw(proj @ view, (0, i * h, w, h), plane_lo, plane_hi, plan[i])
            yield done + i + 1, total
        color, normal, threshold, height = self._read((w, h * n))
        return SliceLayers(
            color.reshape(n, h, w, 4),
            normal.reshape(n, h, w, 3),
            threshold.reshape(n, h, w),
            height.reshape(n, h, w),
        )

    def _target(self, size: tuple[int, int]) -> tuple[moderngl.Framebuffer, list]:
        """One framebuffer per size, kept for the next capture."""
        if self._fbo is None or self._fbo[0] != size:
            self._release_target()
            targets = [self.ctx.texture(size, 4, dtype="f4") for _ in range(3)]
            depth = self.ctx.depth_renderbuffer(size)
            self._fbo = (size, self.ctx.framebuffer(targets, depth), [depth, *targets])
        return self._fbo[1], self._fbo[2][1:]

    def _release_target(self) -> None:
        if self._fbo is not None:
            release_framebuffer(self._fbo[1], *self._fbo[2])
            self._fbo = None

    def _begin(self, size: tuple[int, int]) -> None:
        fbo, _ = self._target(size)
        fbo.use()
        fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)

    def _draw(self, view_proj, viewport, plane_lo, plane_hi, runs) -> None:
        """Draw each (index run, tile offsets) between the clip planes into `viewport`."""
        ctx = self.ctx
        ctx.viewport = viewport
        prog = self.geometry.program
        keep = (0.0, 0.0, 0.0, 1.0)
        prog["u_clip_lo"].value = tuple(plane_lo) if plane_lo is not None else keep
        prog["u_clip_hi"].value = tuple(plane_hi) if plane_hi is not None else keep
        frame = FrameUniforms(view_proj=view_proj, eye=np.zeros(3), light=Lighting())
        self.geometry.alpha_ref = self.alpha_ref
        self.geometry.prepare(frame)
        ctx.enable_direct(GL_CLIP_DISTANCE0)
        ctx.enable_direct(GL_CLIP_DISTANCE0 + 1)
        for (first, count), tiles in runs:
            if not tiles:
                continue
            self.geometry.instances.write(_tiles(tiles).tobytes())
            self.geometry.vao.render(
                moderngl.TRIANGLES, vertices=count, first=first, instances=len(tiles)
            )
        self.geometry.finalize()
        ctx.disable_direct(GL_CLIP_DISTANCE0)
        ctx.disable_direct(GL_CLIP_DISTANCE0 + 1)

    def _read(self, size: tuple[int, int]) -> tuple[np.ndarray, ...]:
        """Albedo + alpha, unit normal, threshold and height of the target, row 0 at the
        bottom."""
        _, targets = self._target(size)
        w, h = size
        color = np.frombuffer(targets[0].read(), np.float32).reshape(h, w, 4).copy()
        normal = np.frombuffer(targets[1].read(), np.float32).reshape(h, w, 4)[..., :3] * 2 - 1
        data = np.frombuffer(targets[2].read(), np.float32).reshape(h, w, 4)
        return color, normal, data[..., 0].copy(), data[..., 1].copy()

    def release(self) -> None:
        self._release_target()
        self.geometry.release()


def _extent(patch: GrassPatch) -> tuple[tuple[float, float], tuple[float, float]]:
    """(x range, z range) of every vertex of the patch, in patch units."""
    pos = patch.vertices["position"]
    return (float(pos[:, 0].min()), float(pos[:, 0].max())), (
        float(pos[:, 2].min()),
        float(pos[:, 2].max()),
    )


def _overlaps(extent: tuple[float, float], offset: float) -> bool:
    """Whether the patch moved by `offset` tiles reaches into the square [0, 1]."""
    return extent[0] + offset < 1.0 and extent[1] + offset > 0.0
