"""A fragment covers the share of a pixel's samples its alpha says, on every driver
(shaders/_coverage.glsl): Mesa's own alpha-to-coverage rounds up by up to a sample and gives
every fragment of a pixel the same samples."""

import moderngl
import numpy as np
import pytest

from render.context import release_framebuffer
from render.present import Presenter
from render.shaders import shader_source

VERTEX = """#version 400 core
in vec2 in_pos;
void main() { gl_Position = vec4(in_pos, 0.0, 1.0); }
"""
FRAGMENT = (
    "#version 400 core\n#define FRAGMENT_SHADER\n"
    + shader_source("_coverage.glsl")
    + """
uniform float u_alpha;
out vec4 f_color;
void main() {
    f_color = vec4(1.0);
    gl_SampleMask[0] = coverage_mask(u_alpha, uint(gl_PrimitiveID));
}
"""
)
QUAD = [(-1, -1), (1, -1), (-1, 1), (-1, 1), (1, -1), (1, 1)]


def covered(ctx, alpha: float, quads: int, resolve: str = "blit") -> float:
    """The resolved share of a 64 × 64 4× MSAA target that `quads` full-screen quads, each its
    own two primitives, cover at `alpha`; resolved by GL's blit or the frame's own pass
    (render/present.py Presenter.resolve), which also makes every pixel opaque."""
    program = ctx.program(vertex_shader=VERTEX, fragment_shader=FRAGMENT)
    vbo = ctx.buffer(np.array(QUAD * quads, np.float32).tobytes())
    vao = ctx.vertex_array(program, [(vbo, "2f", "in_pos")])
    targets = [ctx.texture((64, 64), 4, samples=4), ctx.renderbuffer((64, 64), 4)]
    samples, resolved = (ctx.framebuffer(target) for target in targets)
    presenter = Presenter(ctx)
    try:
        samples.use()
        ctx.clear(0.0, 0.0, 0.0, 0.0)
        program["u_alpha"].value = alpha
        vao.render(moderngl.TRIANGLES)
        if resolve == "blit":
            ctx.copy_framebuffer(resolved, samples)
        else:
            presenter.resolve(samples, resolved, 4)
        image = np.frombuffer(resolved.read(components=4), np.uint8).reshape(64, 64, 4)
        if resolve != "blit":
            assert (image[..., 3] == 255).all()
        return float(image[..., 0].mean() / 255.0)
    finally:
        presenter.release()
        for obj in (vao, vbo, program):
            obj.release()
        for fbo, target in zip((samples, resolved), targets, strict=True):
            release_framebuffer(fbo, target)


@pytest.mark.parametrize("resolve", ["blit", "frame"])
@pytest.mark.parametrize("alpha", [0.1, 0.3, 0.5, 0.7, 0.82])
def test_a_fragment_covers_its_alpha_share_of_the_samples(ctx, alpha, resolve):
    assert covered(ctx, alpha, 1, resolve) == pytest.approx(alpha, abs=0.02)


def test_overlapping_fragments_cover_independently(ctx):
    """Two blades of half cover over one pixel cover three quarters of it, as two random
    layers do, not the same half twice."""
    assert covered(ctx, 0.5, 2) == pytest.approx(0.75, abs=0.03)
