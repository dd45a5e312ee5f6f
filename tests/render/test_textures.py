"""The mip levels Sward writes are the levels the GPU samples."""

import numpy as np
import pytest

from core.mipmaps import build_mips
from render.context import release_framebuffer
from render.textures import texture_with_mips

PROBE_VS = """
#version 330 core
in vec2 in_pos;
void main() { gl_Position = vec4(in_pos, 0.0, 1.0); }
"""
PROBE_FS = """
#version 330 core
uniform sampler2D u_tex;
uniform float u_lod;
out vec4 f_color;
void main() { f_color = textureLod(u_tex, vec2(0.5), u_lod); }
"""


class Probe:
    """Draws one pixel with textureLod(u_tex, (0.5, 0.5), lod) and reads it back."""

    def __init__(self, ctx):
        self.ctx = ctx
        self.prog = ctx.program(vertex_shader=PROBE_VS, fragment_shader=PROBE_FS)
        self.vbo = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], np.float32).tobytes())
        self.vao = ctx.vertex_array(self.prog, [(self.vbo, "2f", "in_pos")])
        self.fbo = ctx.simple_framebuffer((1, 1))

    def sample(self, tex, lod):
        self.fbo.use()
        tex.use(0)
        self.prog["u_lod"].value = float(lod)
        self.vao.render()
        return np.frombuffer(self.fbo.read(components=4), np.uint8)

    def release(self):
        for obj in (self.vao, self.vbo, self.prog):
            obj.release()
        depth = [self.fbo.depth_attachment] if self.fbo.depth_attachment else []
        release_framebuffer(self.fbo, *self.fbo.color_attachments, *depth)


def test_each_written_level_is_sampled(ctx):
    levels = []
    for k, size in enumerate([16, 8, 4, 2, 1]):
        level = np.zeros((size, size, 4), np.float32)
        level[..., k % 3] = 1.0  # a different colour per level: red, green, blue, red, green
        level[..., 3] = 1.0
        levels.append(level)
    tex = texture_with_mips(ctx, levels)
    tex.filter = (ctx.NEAREST_MIPMAP_NEAREST, ctx.NEAREST)
    probe = Probe(ctx)
    for k in range(5):
        rgba = probe.sample(tex, k)
        assert int(np.argmax(rgba[:3])) == k % 3 and rgba[k % 3] == 255
    probe.release()
    tex.release()


def test_wrong_level_size_is_refused(ctx):
    with pytest.raises(ValueError, match="level 1"):
        texture_with_mips(ctx, [np.zeros((8, 8, 4), np.float32), np.zeros((3, 3, 4), np.float32)])


def test_built_pyramid_uploads(ctx):
    base = np.random.default_rng(0).random((64, 256, 4)).astype(np.float32)
    tex = texture_with_mips(ctx, build_mips(base))
    assert tex.size == (256, 64)
    tex.release()
