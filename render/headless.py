"""Rendering without a window: a standalone EGL context, one frame pipeline, one document."""

from __future__ import annotations

import moderngl
import numpy as np

from core.camera import Camera
from core.document import Document
from core.stats import FrameStats
from core.view_mode import ViewMode
from render import context
from render.binding import DocumentBinding
from render.frame import FramePipeline


class HeadlessRenderer:
    """Draws a document's frames to numpy images: `HeadlessRenderer(doc).render(camera, size)`.
    Changes of the document after it was made reach the frames (render/binding.py)."""

    def __init__(
        self,
        document: Document,
        ctx: moderngl.Context | None = None,
        mode: str = ViewMode.LOD,
        view: str = "shaded",
        samples: int = 4,
    ) -> None:
        self._own_ctx = ctx is None
        self.ctx = ctx or context.standalone()
        self.pipeline = FramePipeline(self.ctx, samples=samples)
        self.pipeline.view = view
        self.pipeline.set_mode(mode)
        self.binding = DocumentBinding(self.pipeline, document)
        self._out: moderngl.Framebuffer | None = None
        self._size = (0, 0)

    def _target(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        if self._out is None or self._size != size:
            if self._out is not None:
                context.release_framebuffer(self._out, *self._out.color_attachments)
            self._out = self.ctx.framebuffer(self.ctx.renderbuffer(size, 4))
            self._size = size
        return self._out

    def render(
        self,
        camera: Camera,
        size: tuple[int, int],
        measure: bool = True,
        half_resolution: bool = False,
        alpha: bool = False,
    ) -> tuple[np.ndarray, FrameStats]:
        """One frame: an (h, w, 3) uint8 image, top row first ((h, w, 4) with `alpha`), and its
        statistics; `half_resolution`: drawn at half the width and height (render/frame.py)."""
        out = self._target(size)
        stats = self.pipeline.render(
            camera, out, size, measure=measure, half_resolution=half_resolution
        )
        return context.read_rgb(out, size, 4 if alpha else 3), stats

    def release(self) -> None:
        self.binding.detach()
        self.pipeline.release()
        if self._out is not None:
            context.release_framebuffer(self._out, *self._out.color_attachments)
            self._out = None
        if self._own_ctx:
            self.ctx.release()

    def __enter__(self) -> HeadlessRenderer:
        return self

    def __exit__(self, *_exc) -> None:
        self.release()
