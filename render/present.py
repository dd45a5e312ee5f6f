"""Putting a frame into the caller's framebuffer, every pixel opaque (shaders/present.glsl):
half-resolution frames (no MSAA) scaled up by one textured quad, full frames' samples
averaged."""

from __future__ import annotations

import moderngl
import numpy as np

from render.context import release_framebuffer
from render.shaders import load_program

HALF = 2  # half-resolution frames are drawn at 1 / 2 of the width and height


class Presenter:
    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self._fbo: moderngl.Framebuffer | None = None  # one size kept
        self._vaos: dict[moderngl.Program, moderngl.VertexArray] = {}  # per program variant
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
        """The half-resolution frame `fbo` over the whole of `out`, linearly filtered."""
        self._draw(fbo, out, size, ())

    def resolve(self, fbo: moderngl.Framebuffer, out: moderngl.Framebuffer, samples: int) -> None:
        """Average the `samples` samples of each pixel of `fbo` (its colour a texture; 0: one
        sample) into `out`, of the same size. One pass of our own rather than a blit: on
        llvmpipe the blit builds its resolve anew in every process, while this program
        comes from Mesa's shader cache."""
        self._draw(fbo, out, fbo.size, (f"RESOLVE {max(samples, 1)}",))

    def _draw(self, fbo: moderngl.Framebuffer, out: moderngl.Framebuffer, size, defines) -> None:
        program = load_program(self.ctx, "present.glsl", defines)
        if self._vbo is None:
            corners = np.array([-1, -1, 1, -1, -1, 1, 1, 1], np.float32)
            self._vbo = self.ctx.buffer(corners.tobytes())
        if program not in self._vaos:
            self._vaos[program] = self.ctx.vertex_array(program, [(self._vbo, "2f", "in_corner")])
            program["u_frame"].value = 0
        out.use()
        self.ctx.viewport = (0, 0, *size)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND | moderngl.CULL_FACE)
        fbo.color_attachments[0].use(0)
        self._vaos[program].render(moderngl.TRIANGLE_STRIP)
        self.ctx.enable(moderngl.DEPTH_TEST)

    def release(self) -> None:
        if self._fbo is not None:
            release_fbo(self._fbo)
        for obj in (*self._vaos.values(), self._vbo):
            if obj is not None:
                obj.release()
        self._vaos = {}


def release_fbo(fbo: moderngl.Framebuffer) -> None:
    release_framebuffer(fbo, *fbo.color_attachments, fbo.depth_attachment)
