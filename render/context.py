"""The one place that makes GL contexts.

Renderers receive a moderngl context and never create one: the render processes, the command
line, tests and benchmarks use `standalone` (the window itself draws no GL).
"""

from __future__ import annotations

import moderngl
import numpy as np


class GLUnavailableError(RuntimeError):
    """No OpenGL 3.3 context could be created."""


def standalone() -> moderngl.Context:
    """A headless GL 3.3+ context through EGL (Mesa llvmpipe on a machine with no GPU)."""
    try:
        return moderngl.create_standalone_context(backend="egl", require=330)
    except Exception as exc:  # moderngl raises plain Exceptions from glcontext
        raise GLUnavailableError(
            f"could not create a headless OpenGL 3.3 context through EGL ({exc}); "
            "on Debian install libegl1 libegl-mesa0 libgl1-mesa-dri"
        ) from exc


def describe(ctx: moderngl.Context) -> str:
    info = ctx.info
    return f"{info['GL_RENDERER']} / {info['GL_VERSION']} (max samples {ctx.max_samples})"


def read_rgb(fbo: moderngl.Framebuffer, size: tuple[int, int], components: int = 3) -> np.ndarray:
    """An (h, w, 3) uint8 image of a framebuffer, top row first (4 components: with alpha)."""
    raw = fbo.read(viewport=(0, 0, *size), components=components, alignment=1)
    image = np.frombuffer(raw, dtype=np.uint8).reshape(size[1], size[0], components)[::-1]
    return np.ascontiguousarray(image)


def release_framebuffer(fbo: moderngl.Framebuffer, *attachments) -> None:
    """Release a framebuffer (and the given attachments) without leaving it bound: moderngl
    rebinds its last bound framebuffer after creating the next one, and a released one there
    raises GL_INVALID_OPERATION."""
    fbo.ctx.detect_framebuffer(0).use()
    fbo.release()
    for attachment in attachments:
        attachment.release()
