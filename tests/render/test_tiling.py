"""Aperiodic tiling inside macro-cells (thesis 6.3): a macro-cell's instance carries the mirror
bits of its first cell only, while the blades of every cell it covers are mirrored by that cell's
own. The volume and image-based shaders read each cell's bits from the noise map on the GPU
(render/tiling.py, shaders/_design.glsl `cell_mirror`)."""

from __future__ import annotations

import numpy as np

from core.tiling import mirror_bits
from render.context import release_framebuffer
from render.shaders import snippet_source
from render.tiling import TilingNoise
from render.uniforms import TILING_UNIT

_VERTEX = """#version 330 core
in vec2 in_pos;
void main() { gl_Position = vec4(in_pos, 0.0, 1.0); }
"""
_MAIN = """
uniform vec2 u_first;
out vec4 f_color;
void main() {
    vec2 s = cell_mirror(u_first + floor(gl_FragCoord.xy), vec2(0.0));
    f_color = vec4(s * 0.5 + 0.5, 0.0, 1.0);
}
"""


def _cell_mirrors(ctx, seed, first, size):
    """What cell_mirror gives for the size × size cells from `first` (x along columns)."""
    source = "#version 330 core\n" + snippet_source("_design.glsl") + _MAIN
    program = ctx.program(vertex_shader=_VERTEX, fragment_shader=source)
    tiling = TilingNoise(ctx)
    tiling.set_seed(seed)
    tiling.use()
    program["u_tiling_noise"].value = TILING_UNIT
    program["u_tiling"].value = 1.0
    program["u_first"].value = first
    quad = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], np.float32).tobytes())
    vao = ctx.vertex_array(program, [(quad, "2f", "in_pos")])
    fbo = ctx.simple_framebuffer((size, size), components=4)
    fbo.use()
    vao.render()
    texels = np.frombuffer(fbo.read(components=2), np.uint8).reshape(size, size, 2)
    for obj in (vao, quad, program):
        obj.release()
    release_framebuffer(fbo, *fbo.color_attachments)
    tiling.release()
    return np.where(texels > 127, 1.0, -1.0)  # [row = z, column = x, axis]


def test_the_shaders_mirror_each_cell_by_the_bits_its_blades_have(ctx):
    first, size = (-37.0, 5.0), 80  # negative origins and more cells than the map wraps at
    gpu = _cell_mirrors(ctx, 4, first, size)
    x, z = np.meshgrid(first[0] + np.arange(size), first[1] + np.arange(size), indexing="xy")
    cpu = mirror_bits(np.stack([x.ravel(), z.ravel()], -1), seed=4).reshape(size, size, 2)
    assert np.array_equal(gpu, cpu)
    assert 0.3 < (gpu < 0).mean() < 0.7  # and they vary: half the cells mirror along an axis
