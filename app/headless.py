"""Rendering without a window: a standalone EGL context and the same frame pipeline."""

from __future__ import annotations

import moderngl
import numpy as np

from app.scenes import Scene
from core.camera import Camera
from core.params import PatchParams
from core.patch import GrassPatch, generate_patch
from core.stats import FrameStats
from render import context
from render.frame import FramePipeline


class HeadlessRenderer:
    """Owns one standalone context and pipeline; renders frames to numpy images."""

    def __init__(self, ctx: moderngl.Context | None = None, samples: int = 4) -> None:
        self.ctx = ctx or context.standalone()
        self.pipeline = FramePipeline(self.ctx, samples=samples)
        self._out: moderngl.Framebuffer | None = None
        self._size = (0, 0)

    def load(
        self, scene: Scene, params: PatchParams | None = None, density: float | None = None
    ) -> GrassPatch:
        patch = generate_patch(params or scene.params)
        self.pipeline.set_slice_params(scene.slices)
        self.pipeline.set_patch(patch)
        self.pipeline.set_grass_types(
            [(generate_patch(kind.params), kind.lod, kind.channel) for kind in scene.grass]
        )
        self.pipeline.set_terrain(scene.terrain())
        self.pipeline.set_design_maps(scene.design_maps())
        self.pipeline.set_props(scene.prop_boxes())
        self.pipeline.lighting = scene.light()
        self.pipeline.set_density(scene.density if density is None else density)
        return patch

    def _target(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        if self._out is None or self._size != size:
            if self._out is not None:
                context.release_framebuffer(self._out, *self._out.color_attachments)
            self._out = self.ctx.framebuffer(self.ctx.renderbuffer(size, 4))
            self._size = size
        return self._out

    def render(
        self, camera: Camera, size: tuple[int, int], measure: bool = True, preview: bool = False
    ) -> tuple[np.ndarray, FrameStats]:
        """One frame: an (h, w, 3) uint8 image, top row first, and its statistics; `preview`:
        the viewport's half-resolution frame (render/frame.py)."""
        out = self._target(size)
        stats = self.pipeline.render(camera, out, size, measure=measure, preview=preview)
        return context.read_rgb(out, size), stats

    def release(self) -> None:
        self.pipeline.release()
        if self._out is not None:
            context.release_framebuffer(self._out, *self._out.color_attachments)
