"""Putting a frame into the caller's framebuffer: preview frames (half resolution, no MSAA)
scaled up by one textured quad, and every pixel made opaque before a window composes it."""

from __future__ import annotations

import moderngl
import numpy as np

from render.context import release_framebuffer
from render.shaders import load_program

PREVIEW_SCALE = 2  # preview frames are drawn at 1 / 2 of the width and height


class Presenter:
    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self._fbo: moderngl.Framebuffer | None = None  # one size kept
        self._vao: moderngl.VertexArray | None = None
        self._vbo: moderngl.Buffer | None = None

    def target(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        """A single-sampled frame with a texture to scale up."""
        if self._fbo is None or self._fbo.size != size:
            if self._fbo is not None:
                release_fbo(self._fbo)
            color = self.ctx.texture(size, 4)
            color.filter = (moderngl.LINEAR, moderngl.LINEAR)
            self._fbo = self.ctx.framebuffer(color, self.ctx.depth_renderbuffer(size))
        return self._fbo

    def scale_up(self, fbo: moderngl.Framebuffer, out: moderngl.Framebuffer, size) -> None:
        if self._vao is None:
            program = load_program(self.ctx, "present.glsl")
            corners = np.array([-1, -1, 1, -1, -1, 1, 1, 1], np.float32)
            self._vbo = self.ctx.buffer(corners.tobytes())
            self._vao = self.ctx.vertex_array(program, [(self._vbo, "2f", "in_corner")])
            program["u_frame"].value = 0
        out.use()
        self.ctx.viewport = (0, 0, *size)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND | moderngl.CULL_FACE)
        fbo.color_attachments[0].use(0)
        self._vao.render(moderngl.TRIANGLE_STRIP)
        self.ctx.enable(moderngl.DEPTH_TEST)

    def release(self) -> None:
        if self._fbo is not None:
            release_fbo(self._fbo)
        for obj in (self._vao, self._vbo):
            if obj is not None:
                obj.release()


def opaque_alpha(fbo: moderngl.Framebuffer) -> None:
    """Set every pixel's alpha to 1. Alpha-to-coverage and the alpha test leave the fragment's
    alpha in the image; a window compositor (Qt draws the viewport's framebuffer over the window)
    would show the background through the grass."""
    fbo.color_mask = (False, False, False, True)
    fbo.depth_mask = False
    fbo.use()
    fbo.clear(0.0, 0.0, 0.0, 1.0)
    fbo.color_mask = (True, True, True, True)
    fbo.depth_mask = True
    fbo.use()


def release_fbo(fbo: moderngl.Framebuffer) -> None:
    release_framebuffer(fbo, *fbo.color_attachments, fbo.depth_attachment)
