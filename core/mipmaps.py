"""Mip maps for semi-transparent slices (thesis 4.2.2-4.2.3), on float arrays.

OpenGL's box filter averages alpha, so thin blades fade away in the reduced levels (Fig. 4.8).
Instead each level takes
- colour weighted by alpha (eqs. 4.9-4.10),
- alpha rescaled so that the share of texels passing the alpha test equals the base level's
  (eqs. 4.11-4.15, Castaño 2010). The thesis takes the max of the four texels (eq. 4.12) before
  rescaling; on thin blades the max saturates within three levels (every texel 1, measured in
  tests/core/test_mipmaps.py) and no rescale can bring the coverage back. So, as Castaño does,
  the pyramid carries the plain average of alpha — the true share of the footprint that is
  covered — and the rescale turns that back into the base level's coverage,
and after the pyramid is built, colour bleeding fills the transparent part of every texel with
the colour of the next level (eq. 4.16), from the smallest level down, so bilinear filtering at
blade edges mixes in blade colour instead of the background (no grey halo, Fig. 4.9).

Images are float32 arrays (h, w, 4) with values in 0 … 1, rows first.
"""

from __future__ import annotations

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


def _sum4(image: np.ndarray) -> np.ndarray:
    """(..., h, w, c) → (..., h/2, w/2, c): the sum of the four texels under each texel of the
    next level, for a stack of images at once (strided views, no transposed copies)."""
    h, w = image.shape[-3:-1]
    if (h > 1 and h % 2) or (w > 1 and w % 2):
        raise ValueError(f"mip sizes must be even or 1, got {w} × {h}")
    if h == 1:
        image = np.repeat(image, 2, axis=-3)
    if w == 1:
        image = np.repeat(image, 2, axis=-2)
    return (
        image[..., 0::2, 0::2, :]
        + image[..., 0::2, 1::2, :]
        + image[..., 1::2, 0::2, :]
        + image[..., 1::2, 1::2, :]
    )


def _weighted_reduce_stack(stack: np.ndarray) -> np.ndarray:
    """alpha_weighted_reduce (alpha: mean) of every image of an (n, h, w, 4) stack at once."""
    a = stack[..., 3:4]
    s_a = _sum4(a)
    weighted = _sum4(stack[..., :3] * a) / np.where(s_a == 0.0, 1.0, s_a)
    color = np.where(s_a == 0.0, _sum4(stack[..., :3]) * 0.25, weighted)
    return np.concatenate([color, s_a * 0.25], axis=-1).astype(np.float32)


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


def coverage(alpha: np.ndarray, alpha_ref: float) -> float:
    """Share of texels passing the alpha test a > a_r (eq. 4.11)."""
    return float(np.mean(alpha > alpha_ref))


def coverage_scale(alpha: np.ndarray, target: float, alpha_ref: float) -> float:
    """scale = a_r / a'_r, with a'_r the test value that lets the share of texels closest to
    `target` pass (eqs. 4.13-4.14); a texel passes where scale · a > a_r ⟺ a > a'_r."""
    values = np.unique(alpha[alpha > 0.0])
    if target <= 0.0 or values.size == 0:
        return 1.0
    flat = np.sort(alpha.ravel())
    # share of texels with a >= values[k], for every k
    passing = 1.0 - np.searchsorted(flat, values, side="left") / flat.size
    k = int(np.argmin(np.abs(passing - target)))
    below = values[k - 1] if k > 0 else 0.0
    a_r_new = 0.5 * (below + values[k])  # between two alpha values: a > a'_r ⟺ a >= values[k]
    return alpha_ref / a_r_new


def build_mips(base: np.ndarray, alpha_ref: float = 0.5) -> list[np.ndarray]:
    """The full pyramid down to 1 × 1, coverage-preserving alpha, then colour bleeding."""
    return [level[0] for level in build_mips_stack(np.asarray(base)[None], alpha_ref)]


def build_mips_stack(stack: np.ndarray, alpha_ref: float = 0.5) -> list[np.ndarray]:
    """build_mips of every image of an (n, h, w, 4) stack: levels of shape (n, h_k, w_k, 4).
    The reductions and the bleeding run on the whole stack; only the coverage rescale, which
    ranks each image's alpha values, goes image by image."""
    base = np.asarray(stack, dtype=np.float32)
    targets = [coverage(b[..., 3], alpha_ref) for b in base]
    raw = [base]
    while raw[-1].shape[1] > 1 or raw[-1].shape[2] > 1:
        raw.append(_weighted_reduce_stack(raw[-1]))
    levels = [base.copy()]
    for level in raw[1:]:
        scale = np.array(
            [
                coverage_scale(lv[..., 3], t, alpha_ref)
                for lv, t in zip(level, targets, strict=True)
            ],
            np.float32,
        )
        level[..., 3] = np.clip(level[..., 3] * scale[:, None, None], 0.0, 1.0)
        levels.append(level)
    return _bleed_stack(levels)


def bleed_colors(levels: list[np.ndarray]) -> list[np.ndarray]:
    """C'_i = A_i · C_i + (1 − A_i) · C'_{i+1} with nearest sampling of the next level (eq. 4.16),
    processed from the smallest level to the base."""
    return [lvl[0] for lvl in _bleed_stack([lvl.copy()[None] for lvl in levels])]


def _bleed_stack(out: list[np.ndarray]) -> list[np.ndarray]:
    """bleed_colors in place on levels of (n, h_k, w_k, 4) stacks."""
    for i in range(len(out) - 2, -1, -1):
        cur, nxt = out[i], out[i + 1]
        n, h, w = cur.shape[:3]
        nh, nw = nxt.shape[1:3]
        if h % nh == 0 and w % nw == 0:  # a pyramid: each texel of nxt covers ry × rx of cur
            ry, rx = h // nh, w // nw
            blocks = cur.reshape(n, nh, ry, nw, rx, 4)
            up = nxt[:, :, None, :, None, :3]
            a = blocks[..., 3:4]
            blocks[..., :3] = a * blocks[..., :3] + (1.0 - a) * up
            continue
        ys = np.minimum(np.arange(h) * nh // h, nh - 1)
        xs = np.minimum(np.arange(w) * nw // w, nw - 1)
        up = nxt[:, ys][:, :, xs, :3]
        a = cur[..., 3:4]
        cur[..., :3] = a * cur[..., :3] + (1.0 - a) * up
    return out


def to_uint8(level: np.ndarray) -> np.ndarray:
    return (np.clip(level, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)


def weighted_chain(values: np.ndarray, alphas: list[np.ndarray]) -> list[np.ndarray]:
    """Mip chain of a data layer (normals, thresholds: (h, w, c)) averaged with the colour
    layer's raw alpha as weight, so empty texels do not pull the average toward 0. `alphas` are
    the base alpha and the (unscaled, mean) alphas of the levels below it. A leading stack axis
    ((n, h, w, c) values, (n, h, w) alphas) is carried along."""
    out = [np.asarray(values, dtype=np.float32)]
    for level in range(1, len(alphas)):
        a = alphas[level - 1][..., None]
        s_a = _sum4(a)
        mean = _sum4(out[-1]) * 0.25
        weighted = _sum4(out[-1] * a) / np.where(s_a == 0, 1.0, s_a)
        out.append(np.where(s_a > 0, weighted, mean).astype(np.float32))
    return out


def mean_alpha_chain(alpha: np.ndarray, count: int) -> list[np.ndarray]:
    """The plain box-filtered alpha of `count` levels (the weights for weighted_chain); a
    leading stack axis is carried along."""
    out: list[np.ndarray] = [np.asarray(alpha, dtype=np.float32)]
    while len(out) < count:
        out.append((_sum4(out[-1][..., None]) * np.float32(0.25))[..., 0])
    return out


def stacked_slice_mips(slices: np.ndarray, levels: int, alpha_ref: float = 0.5) -> list[np.ndarray]:
    """Per-slice mip chains of (n, h, w, 4) colour slices, each level stacked along rows into one
    (n·h_k, w_k, 4) image, for `levels` levels (at most log2(h) + 1 so no slice shrinks below a
    row)."""
    stacked = build_mips_stack(slices, alpha_ref)[:levels]
    return [level.reshape(-1, *level.shape[2:]) for level in stacked]
