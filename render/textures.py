"""Textures whose mip levels Sward computes itself (thesis 4.2.2: alpha-weighted, coverage-
preserving slice mips). moderngl 5.13's TextureArray.write takes no mip level, Texture.write
does, so slices are kept in 2D textures and every level is written explicitly."""

from __future__ import annotations

import moderngl
import numpy as np

from core.mipmaps import to_uint8


def texture_with_mips(ctx: moderngl.Context, levels: list[np.ndarray]) -> moderngl.Texture:
    """An RGBA8 texture whose level k holds levels[k] ((h, w, 4) floats, row 0 at v = 0)."""
    base = levels[0]
    h, w = base.shape[:2]
    tex = ctx.texture((w, h), 4, to_uint8(base).tobytes())
    tex.build_mipmaps(0, len(levels) - 1)  # allocates the chain; overwritten below
    for k, level in enumerate(levels[1:], start=1):
        lh, lw = level.shape[:2]
        expected = (max(w >> k, 1), max(h >> k, 1))
        if (lw, lh) != expected:
            raise ValueError(
                f"mip level {k} is {lw} × {lh}, expected {expected[0]} × {expected[1]}"
            )
        tex.write(to_uint8(level).tobytes(), viewport=(0, 0, lw, lh), level=k)
    tex.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
    return tex
