"""Mip maps for semi-transparent slices (thesis 4.2.2-4.2.3), on float arrays.

Each level takes colour weighted by alpha (eqs. 4.9-4.10) and the plain mean of alpha: the
share of the texel's footprint the blades cover. The thesis rescales alpha so that the share of
texels passing an alpha test stays the base level's (eqs. 4.11-4.15, Fig. 4.8: thin blades fade
away in a box-filtered level drawn with an alpha test). Sward draws no slice with an alpha test:
the volume composites a texel's alpha as the opacity of the blades in it, and the image-based
grass covers that share of the pixel's samples (shaders/_coverage.glsl); for both, alpha must
stay the covered share, which the rescale changes (a dense top view, whose texels all pass the
test far away, was drawn with a third less cover than its blades).

After the pyramid is built, colour bleeding fills the transparent part of every texel with the
colour of the next level (eq. 4.16), from the smallest level down, so bilinear filtering at
blade edges mixes in blade colour instead of the background (no grey halo, Fig. 4.9).

Images are float32 arrays (h, w, 4) with values in 0 … 1, rows first.
"""

from __future__ import annotations

import numba
import numpy as np


def _quads(image: np.ndarray) -> np.ndarray:
    """(h, w, c) → (h/2, w/2, 4, c): the four texels under each texel of the next level.

    Sides must be even or 1 (power-of-two slices); a side of 1 stays 1.
    """
    h, w = image.shape[:2]
    if (h > 1 and h % 2) or (w > 1 and w % 2):
        raise ValueError(f"mip sizes must be even or 1, got {w} × {h}")
    if h == 1:
        image = np.repeat(image, 2, axis=0)
    if w == 1:
        image = np.repeat(image, 2, axis=1)
    h, w = image.shape[:2]
    q = image.reshape(h // 2, 2, w // 2, 2, -1).transpose(0, 2, 1, 3, 4)
    return q.reshape(h // 2, w // 2, 4, -1)


def box_reduce(image: np.ndarray) -> np.ndarray:
    """OpenGL's box filter (eqs. 4.7-4.8): plain average of colour and alpha."""
    return _quads(image).mean(axis=2)


def alpha_weighted_reduce(image: np.ndarray, alpha: str = "mean") -> np.ndarray:
    """Colour weighted by alpha (eq. 4.10); alpha the mean of the four, or their max
    (eq. 4.12) with alpha="max"."""
    q = _quads(image)
    a = q[..., 3]
    s_a = a.sum(axis=2)
    s_a = np.where(s_a == 0.0, 1.0, s_a)  # eq. 4.9
    color = (q[..., :3] * a[..., None]).sum(axis=2) / s_a[..., None]
    # fully transparent quads keep their plain average so bleeding has something to start from
    empty = a.sum(axis=2) == 0.0
    color[empty] = q[..., :3].mean(axis=2)[empty]
    out = np.empty((*q.shape[:2], 4), dtype=np.float32)
    out[..., :3] = color
    out[..., 3] = a.max(axis=2) if alpha == "max" else a.mean(axis=2)
    return out


def build_mips(base: np.ndarray) -> list[np.ndarray]:
    """The full pyramid down to 1 × 1, alpha the covered share, then colour bleeding."""
    return [level[0] for level in build_mips_stack(np.asarray(base)[None])]


def build_mips_stack(stack: np.ndarray, upper_first: bool = False) -> list[np.ndarray]:
    """build_mips of every image of an (n, h, w, 4) stack: levels of shape (n, h_k, w_k, 4).
    Each step is one compiled pass over the stack (numba; the numpy version, a dozen array
    passes per level, took 65-85 ms of a 2 × 8 conversion)."""
    base = np.ascontiguousarray(stack, dtype=np.float32)
    levels = [base.copy()]
    while levels[-1].shape[1] > 1 or levels[-1].shape[2] > 1:
        nxt = np.empty((*_next_size(levels[-1]), 4), np.float32)
        # alpha_weighted_reduce (alpha: mean): colour weighted by alpha, alpha averaged
        src = levels[-1]
        weight = np.ascontiguousarray(src[..., 3])
        if upper_first and src.shape[1] > 1:
            # of the two rows under a texel (rows run upward) the upper hides the lower by its
            # alpha: C = (a_u C_u + (1 − a_u) a_l C_l) / (a_u + (1 − a_u) a_l), as the blades'
            # upper parts hide their lower ones from any eye above the grass
            weight = weight.copy()
            weight[:, 0::2] *= 1.0 - src[:, 1::2, :, 3]
        _weighted_into(src[..., :3], weight, nxt[..., :3], nxt[..., 3])
        if upper_first:  # alpha stays the plain mean, the true covered share
            mean_alpha = np.empty((*nxt.shape[:3], 1), np.float32)
            _weighted_into(src[..., 3:], np.ones_like(weight), mean_alpha, nxt[..., 3])
            nxt[..., 3] = mean_alpha[..., 0]
        levels.append(nxt)
    return _bleed_stack(levels)


def bleed_colors(levels: list[np.ndarray]) -> list[np.ndarray]:
    """C'_i = A_i · C_i + (1 − A_i) · C'_{i+1} with nearest sampling of the next level (eq. 4.16),
    processed from the smallest level to the base."""
    stacks = [np.array(lvl, np.float32)[None] for lvl in levels]
    return [lvl[0] for lvl in _bleed_stack(stacks)]


def _bleed_stack(out: list[np.ndarray]) -> list[np.ndarray]:
    """bleed_colors in place on levels of (n, h_k, w_k, 4) stacks."""
    for i in range(len(out) - 2, -1, -1):
        _bleed_into(out[i], out[i + 1])
    return out


def _next_size(stack: np.ndarray) -> tuple[int, int, int]:
    """(n, h, w) of the next level of an (n, h, w, c) stack; sides must be even or 1."""
    n, h, w = stack.shape[:3]
    if (h > 1 and h % 2) or (w > 1 and w % 2):
        raise ValueError(f"mip sizes must be even or 1, got {w} × {h}")
    return n, max(h // 2, 1), max(w // 2, 1)


@numba.njit(cache=True)
def _pairs(size, i):
    """The two texels of the level above under texel i (a side of 1 repeats its texel)."""
    return (2 * i, 2 * i + 1) if size > 1 else (0, 0)


@numba.njit(cache=True)
def _bleed_into(cur, nxt):
    """C' = A · C + (1 − A) · C_next, the next level sampled nearest (eq. 4.16), in place."""
    one = np.float32(1.0)
    h, w = cur.shape[1], cur.shape[2]
    nh, nw = nxt.shape[1], nxt.shape[2]
    for k in range(cur.shape[0]):
        for y in range(h):
            ny = min(y * nh // h, nh - 1)
            for x in range(w):
                nx = min(x * nw // w, nw - 1)
                a = cur[k, y, x, 3]
                for c in range(3):
                    cur[k, y, x, c] = a * cur[k, y, x, c] + (one - a) * nxt[k, ny, nx, c]


def to_uint8(level: np.ndarray) -> np.ndarray:
    return (np.clip(level, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)


def weighted_chain(values: np.ndarray, alpha: np.ndarray, count: int) -> list[np.ndarray]:
    """`count` levels of the mip chain of a data layer ((n, h, w, c) values: normals,
    thresholds) averaged with the colour layer's raw alpha ((n, h, w); mean-reduced level by
    level, never rescaled) as weight, so empty texels do not pull the average toward 0."""
    out = [np.ascontiguousarray(values, dtype=np.float32)]
    weight = np.ascontiguousarray(alpha, dtype=np.float32)
    while len(out) < count:
        size = _next_size(out[-1])
        nxt, next_weight = (
            np.empty((*size, out[-1].shape[3]), np.float32),
            np.empty(size, np.float32),
        )
        _weighted_into(out[-1], weight, nxt, next_weight)
        out.append(nxt)
        weight = next_weight
    return out


@numba.njit(cache=True)
def _weighted_into(src, weight, dst, dst_weight):
    """One level of a chain weighted by `weight` (its plain average into dst_weight): each
    texel of dst the weighted mean of the four under it, their plain mean where all weights
    are 0 (eq. 4.9: something for the bleeding to start from); in float32, adding the four
    row by row (the order of the array version)."""
    quarter = np.float32(0.25)
    for k in range(src.shape[0]):
        for y in range(dst.shape[1]):
            y0, y1 = _pairs(src.shape[1], y)
            for x in range(dst.shape[2]):
                x0, x1 = _pairs(src.shape[2], x)
                a00, a01 = weight[k, y0, x0], weight[k, y0, x1]
                a10, a11 = weight[k, y1, x0], weight[k, y1, x1]
                s = ((a00 + a01) + a10) + a11
                for c in range(src.shape[3]):
                    c00, c01 = src[k, y0, x0, c], src[k, y0, x1, c]
                    c10, c11 = src[k, y1, x0, c], src[k, y1, x1, c]
                    if s > 0.0:
                        dst[k, y, x, c] = (((c00 * a00 + c01 * a01) + c10 * a10) + c11 * a11) / s
                    else:
                        dst[k, y, x, c] = (((c00 + c01) + c10) + c11) * quarter
                dst_weight[k, y, x] = s * quarter


def stacked_slice_mips(
    slices: np.ndarray, levels: int, upper_first: bool = False
) -> list[np.ndarray]:
    """Per-slice mip chains of (n, h, w, 4) colour slices, each level stacked along rows into one
    (n·h_k, w_k, 4) image, for `levels` levels (at most log2(h) + 1 so no slice shrinks below a
    row)."""
    stacked = build_mips_stack(slices, upper_first)[:levels]
    return [level.reshape(-1, *level.shape[2:]) for level in stacked]


def threshold_spread(threshold: np.ndarray, alpha: np.ndarray, count: int) -> np.ndarray:
    """(count,) float32: per mip level, how far the density thresholds of the blades under one
    texel spread — the standard deviation of the threshold over a texel's footprint, weighted by
    alpha like the threshold's own chain, averaged over the level's texels (weighted by their
    mean alpha). 0 at the base level (one blade a texel); a reduced texel keeps a share of its
    blades by it instead of all or none (core/lod.py: share)."""
    t = np.ascontiguousarray(threshold, dtype=np.float32)[..., None]
    a = np.ascontiguousarray(alpha, dtype=np.float32)
    means = weighted_chain(t, a, count)
    squares = weighted_chain(t * t, a, count)
    cover = weighted_chain(a[..., None], np.ones_like(a), count)
    out = np.zeros(count, np.float32)
    for k in range(1, count):
        sd = np.sqrt(np.maximum(squares[k] - means[k] ** 2, 0.0))[..., 0]
        w = cover[k][..., 0]
        out[k] = float((sd * w).sum() / max(w.sum(), 1e-12))
    return out


def row_depths(levels: list[np.ndarray], count: int) -> np.ndarray:
    """((len(levels), rows) float32) Of `count` vertical slices' mip levels, stacked along rows
    as stacked_slice_mips gives them (rows run upward): per level and row, the optical depth
    −ln(1 − ā) of the row's mean alpha ā (the covered share, 8 bits as the texture stores
    it), averaged over the slices, at the base level's row centres (linear between a coarser
    level's rows, as the texture is sampled). A reduced level averages alpha over rows whose
    depths differ; a ray crossing the slices at those heights meets the mean of their depths,
    which the base level's rows give (shaders/volume.glsl)."""
    rows = levels[0].shape[0] // count
    centres = (np.arange(rows) + 0.5) / rows
    out = np.empty((len(levels), rows), np.float32)
    for k, level in enumerate(levels):
        alpha = np.minimum(to_uint8(level[..., 3]) / 255.0, 0.999)
        per_row = level.shape[0] // count
        mean = (-np.log1p(-alpha.reshape(count, per_row, -1).mean(axis=2))).mean(axis=0)
        out[k] = np.interp(centres, (np.arange(per_row) + 0.5) / per_row, mean)
    return out


# -- a linearly filtered mip chain, updated over a rectangle -----------------------------------
def mip_sizes(width: int, height: int) -> list[tuple[int, int]]:
    """(width, height) of each mip level GL makes for a texture of this size, the base first."""
    sizes = [(width, height)]
    while sizes[-1] != (1, 1):
        w, h = sizes[-1]
        sizes.append((max(1, w // 2), max(1, h // 2)))
    return sizes


def _taps(source: int, target: int, lo: int, hi: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For target texels lo … hi − 1 along one axis: the two source texels a linear filter at
    each one's centre reads (clamped to the edge) and the second one's weight."""
    at = (np.arange(lo, hi) + 0.5) * (source / target) - 0.5
    first = np.floor(at)
    weight = (at - first).astype(np.float32)
    a = np.clip(first, 0, source - 1).astype(np.int64)
    b = np.clip(first + 1, 0, source - 1).astype(np.int64)
    return a, b, weight


def reduce_rect(
    source: np.ndarray, rect: tuple[int, int, int, int], size: tuple[int, int]
) -> tuple[tuple[int, int, int, int], np.ndarray]:
    """The next mip level's texels that read the changed `rect` (x, y, w, h) of `source`
    ((rows, columns, channels)), as GL's mipmap generation filters them: each the linear filter
    of `source` at its centre. `size` is the level's (rows, columns). Their rectangle and
    values (float32)."""
    rows, columns = size
    x, y, w, h = rect
    sy, sx = source.shape[0] / rows, source.shape[1] / columns
    x0, x1 = max(0, int(x // sx) - 1), min(columns, int(-(-(x + w) // sx)) + 1)
    y0, y1 = max(0, int(y // sy) - 1), min(rows, int(-(-(y + h) // sy)) + 1)
    ax, bx, fx = _taps(source.shape[1], columns, x0, x1)
    ay, by, fy = _taps(source.shape[0], rows, y0, y1)
    # only the source texels those read, in single precision
    r0, c0 = int(min(ay.min(), by.min())), int(min(ax.min(), bx.min()))
    r1, c1 = int(max(ay.max(), by.max())) + 1, int(max(ax.max(), bx.max())) + 1
    src = source[r0:r1, c0:c1].astype(np.float32)
    ay, by, ax, bx = ay - r0, by - r0, ax - c0, bx - c0
    fx, fy = fx[None, :, None], fy[:, None, None]
    top = src[ay][:, ax] * (1.0 - fx) + src[ay][:, bx] * fx
    bottom = src[by][:, ax] * (1.0 - fx) + src[by][:, bx] * fx
    return (x0, y0, x1 - x0, y1 - y0), top * (1.0 - fy) + bottom * fy
