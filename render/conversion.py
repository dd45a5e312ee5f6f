"""Patch conversion (thesis 4.2.1): render the geometry patch into slices.

Vertical slices: N slabs across x and N across z. Each slab [i/N, (i+1)/N] is drawn between two
clip planes by an orthographic camera looking along the axis, onto an image whose u runs along
the other horizontal axis and v up the patch height. The horizontal slice: the whole patch from
above. The patch is drawn 3 × 3 times (its neighbours too), so blades of the next tile that lean
into the square are captured and the slices tile seamlessly like the geometry does.

Every slice keeps: albedo + alpha, patch-space normal and density threshold. The results are numpy arrays, row 0 at the ground (v = 0) for vertical slices and at
z = 0 for the horizontal slice.
"""

from __future__ import annotations

from collections.abc import Generator
from dataclasses import dataclass

import moderngl
import numpy as np

from core.camera import look_at, orthographic
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


@dataclass
class SlicedPatch:
    x: SliceLayers  # slabs across x; u runs along z
    z: SliceLayers  # slabs across z; u runs along x
    top: SliceLayers  # one slice, n = 1
    height: float


def _neighbours() -> np.ndarray:
    inst = np.zeros(9, dtype=INSTANCE_DTYPE)
    ox, oz = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0], indexing="ij")
    inst["origin"][:, 0] = ox.ravel()
    inst["origin"][:, 1] = oz.ravel()
    inst["density"] = 1.0
    inst["lod"] = (2.0, 0.0)
    inst["size"] = 1.0
    inst["mirror"] = 1.0
    inst["config"] = (0.5, 0.5, 0.0, 0.0)  # design maps are applied when drawing, not here
    return inst


class PatchConverter:
    alpha_ref = 0.1

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.geometry = GeometryRenderer(ctx, program="slice_capture.glsl")
        self.geometry.set_instances(_neighbours())

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
        self.geometry.set_patch(patch)
        h = patch.height  # the tallest tip: slices and cuboids fit the grass, not the box
        total = 2 * slices + 1
        x = yield from self._layers(slices, size, axis=0, height=h, done=0, total=total)
        z = yield from self._layers(slices, size, axis=2, height=h, done=slices, total=total)
        top = self._capture(
            orthographic(0.0, 1.0, -1.0, 0.0, 0.1, 10.0) @ look_at((0, h + 1.0, 0), (0, 0, 0)),
            (top_size, top_size),
            None,
            None,
        )
        yield total, total
        top = SliceLayers(*(a[None] for a in top))
        return SlicedPatch(x=x, z=z, top=top, height=h)

    def _layers(
        self, n: int, size: tuple[int, int], axis: int, height: float, done: int, total: int
    ) -> Generator[tuple[int, int], None, SliceLayers]:
        parts = []
        for i in range(n):
            lo, hi = i / n, (i + 1) / n
            plane_lo = np.zeros(4, np.float32)
            plane_hi = np.zeros(4, np.float32)
            plane_lo[axis], plane_lo[3] = 1.0, -lo  # x >= lo
            plane_hi[axis], plane_hi[3] = -1.0, hi  # x <= hi
            if axis == 0:  # look along +x: screen right = +z
                view = look_at((lo - 2.0, 0, 0), (lo, 0, 0))
                proj = orthographic(0.0, 1.0, 0.0, height, 0.1, 10.0)
            else:  # look along -z from beyond the slab: screen right = +x
                view = look_at((0, 0, hi + 2.0), (0, 0, hi))
                proj = orthographic(0.0, 1.0, 0.0, height, 0.1, 10.0)
            parts.append(self._capture(proj @ view, size, plane_lo, plane_hi))
            yield done + i + 1, total
        return SliceLayers(*(np.stack(p) for p in zip(*parts, strict=True)))

    def _capture(self, view_proj, size, plane_lo, plane_hi):
        ctx = self.ctx
        targets = [ctx.texture(size, 4, dtype="f4") for _ in range(3)]
        depth = ctx.depth_renderbuffer(size)
        fbo = ctx.framebuffer(targets, depth)
        fbo.use()
        ctx.viewport = (0, 0, *size)
        fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        prog = self.geometry.program
        keep = (0.0, 0.0, 0.0, 1.0)
        prog["u_clip_lo"].value = tuple(plane_lo) if plane_lo is not None else keep
        prog["u_clip_hi"].value = tuple(plane_hi) if plane_hi is not None else keep
        frame = FrameUniforms(view_proj=view_proj, eye=np.zeros(3), lighting=Lighting())
        self.geometry.alpha_ref = self.alpha_ref
        self.geometry.prepare(frame)
        ctx.disable_direct(0x809E)  # single-sampled targets: no alpha-to-coverage
        ctx.enable_direct(GL_CLIP_DISTANCE0)
        ctx.enable_direct(GL_CLIP_DISTANCE0 + 1)
        self.geometry.draw()
        self.geometry.finalize()
        ctx.disable_direct(GL_CLIP_DISTANCE0)
        ctx.disable_direct(GL_CLIP_DISTANCE0 + 1)
        w, h = size
        color = np.frombuffer(targets[0].read(), np.float32).reshape(h, w, 4).copy()
        normal = np.frombuffer(targets[1].read(), np.float32).reshape(h, w, 4)[..., :3] * 2 - 1
        data = np.frombuffer(targets[2].read(), np.float32).reshape(h, w, 4)
        release_framebuffer(fbo, depth, *targets)
        return color, normal, data[..., 0].copy()

    def release(self) -> None:
        self.geometry.release()
