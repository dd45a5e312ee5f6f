"""How far the LOD frame is from an all-geometry reference (issue: the LOD image matches
all-geometry): the figures `sward quality` reports, on images alone (no GL).

- FLIP at full and at quarter resolution (core/image_diff.py);
- the mean colour difference of 8 × 8 pixel blocks (a representation that is darker or paler
  over an area shows here even where FLIP's blade-level noise hides it);
- the floor: the same figure between two reference frames a blade's width apart, which is what
  blade detail alone differs by — a LOD frame is as good as it gets at about the floor;
- the figure over each technique's screen region, from a frame drawn in the technique colours
  (geometry red, volume yellow, image-based blue);
- popping along a camera path: the largest frame-to-frame change of the LOD sequence over the
  largest of the reference sequence.

Images are (h, w, 3) uint8 arrays or floats in 0 … 1, top row first."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from core.image_diff import QUARTER, downsample, flip, to_float

BLOCK = 8  # pixels a side of the blocks whose mean colours are compared
TECHNIQUES = ("geometry", "volume", "image")
_GRASS_CHANGE = 0.03  # a pixel the technique view recolours by more than this is grass


def block_color_difference(reference: np.ndarray, test: np.ndarray, block: int = BLOCK) -> float:
    """Mean over BLOCK × BLOCK blocks of the length of the difference of their mean RGB (0 … √3)."""
    a, b = downsample(reference, block), downsample(test, block)
    return float(np.linalg.norm(a - b, axis=-1).mean())


def technique_regions(
    shaded: np.ndarray, techniques: np.ndarray, colors: dict[str, list[tuple[float, float, float]]]
) -> dict[str, np.ndarray]:
    """Per technique, the pixels its grass covers: where the technique view differs from the
    shaded frame (the view recolours grass only), by the nearest chromaticity among `colors`
    (technique -> the colours its levels are drawn in, render/)."""
    s, t = to_float(shaded), to_float(techniques)
    if s.shape != t.shape:
        raise ValueError(f"images differ in size: {s.shape[:2]} and {t.shape[:2]}")
    grass = np.abs(s - t).max(axis=-1) > _GRASS_CHANGE
    names = [name for name in TECHNIQUES for _ in colors.get(name, [])]
    ref = np.array([c for name in TECHNIQUES for c in colors.get(name, [])], np.float32)
    ref /= ref.sum(axis=-1, keepdims=True)
    chroma = t / np.maximum(t.sum(axis=-1, keepdims=True), 1e-6)
    nearest = np.argmin(((chroma[..., None, :] - ref) ** 2).sum(axis=-1), axis=-1)
    owner = np.array([TECHNIQUES.index(n) for n in names])[nearest]
    return {name: grass & (owner == k) for k, name in enumerate(TECHNIQUES)}


def quarter_mask(mask: np.ndarray) -> np.ndarray:
    """A pixel mask at quarter resolution: blocks mostly inside the mask."""
    m = mask[..., None].astype(np.float32).repeat(3, axis=-1)
    return downsample(m, QUARTER)[..., 0] > 0.5


@dataclass(frozen=True)
class Comparison:
    """A test frame against a reference: FLIP full and quarter, block colour difference, and
    the quarter-resolution FLIP map (for region figures and heat maps)."""

    flip_full: float
    flip_quarter: float
    block_color: float
    quarter_map: np.ndarray

    @classmethod
    def of(cls, reference: np.ndarray, test: np.ndarray) -> Comparison:
        full, _ = flip(reference, test)
        quarter, qmap = flip(reference, test, QUARTER)
        qmap = qmap.reshape(qmap.shape[0], qmap.shape[1])  # flip gives (h, w, 1)
        return cls(full, quarter, block_color_difference(reference, test), qmap)

    def region(self, mask_quarter: np.ndarray) -> float | None:
        """Mean quarter-resolution FLIP over a region (None where it is empty)."""
        h, w = self.quarter_map.shape[:2]
        m = mask_quarter[:h, :w]
        return float(self.quarter_map[m].mean()) if m.any() else None

    def to_dict(self) -> dict:
        return {
            "flip_full": self.flip_full,
            "flip_quarter": self.flip_quarter,
            "block_color": self.block_color,
        }


def popping(lod_frames: list[np.ndarray], reference_frames: list[np.ndarray]) -> dict:
    """The largest quarter-resolution FLIP between consecutive frames of the LOD sequence, the
    same of the reference sequence, and their ratio (1: the LOD frames change from frame to
    frame no more than the grass itself does)."""
    if len(lod_frames) != len(reference_frames) or len(lod_frames) < 2:
        raise ValueError("popping needs two sequences of the same length, two frames or more")

    def largest(frames):
        return max(flip(a, b, QUARTER)[0] for a, b in itertools.pairwise(frames))

    lod, ref = largest(lod_frames), largest(reference_frames)
    return {"lod_max_change": lod, "reference_max_change": ref, "popping": lod / max(ref, 1e-9)}


def figures(
    reference: np.ndarray,
    lod: np.ndarray,
    techniques: np.ndarray,
    colors: dict[str, list[tuple[float, float, float]]],
) -> tuple[dict, Comparison, dict[str, np.ndarray]]:
    """The LOD frame against its reference, over the frame and over each technique's region
    (from `techniques`, the LOD frame in the technique colours); the comparison itself and the
    regions (quarter resolution)."""
    lod_vs = Comparison.of(reference, lod)
    regions = technique_regions(lod, techniques, colors)
    quarters = {name: quarter_mask(mask) for name, mask in regions.items()}
    per_technique = {
        name: {"pixels": int(regions[name].sum()), "flip_quarter": lod_vs.region(q)}
        for name, q in quarters.items()
    }
    return {"lod": lod_vs.to_dict(), "techniques": per_technique}, lod_vs, quarters


def heat_map(error: np.ndarray) -> np.ndarray:
    """An error map (0 … 1) as an RGB uint8 image: black through red and yellow to white."""
    e = np.clip(np.asarray(error, np.float32), 0.0, 1.0)
    rgb = np.stack([np.clip(3 * e, 0, 1), np.clip(3 * e - 1, 0, 1), np.clip(3 * e - 2, 0, 1)], -1)
    return np.rint(rgb * 255).astype(np.uint8)


# -- hand-over steps -------------------------------------------------------------------------
# Where two LOD levels meet, a level drawn brighter or paler than its neighbour shows as a step
# of brightness along the boundary (a staircase where the boundary follows macro-cells). Within
# one level neighbouring blocks differ by the grass's own texture and the slow change with
# distance; across a boundary they should differ by no more.
PURE = 0.75  # a block belongs to a level when this share of its pixels shows that level


def level_labels(shaded: np.ndarray, techniques: np.ndarray, colors: list) -> np.ndarray:
    """Per pixel, the index into `colors` (the technique view's colour of each level) of the
    level drawing it, or -1 where no grass is (the technique view recolours grass only)."""
    s, t = to_float(shaded), to_float(techniques)
    grass = np.abs(s - t).max(axis=-1) > _GRASS_CHANGE
    ref = np.asarray(colors, np.float32)
    ref = ref / ref.sum(axis=-1, keepdims=True)
    chroma = t / np.maximum(t.sum(axis=-1, keepdims=True), 1e-6)
    nearest = np.argmin(((chroma[..., None, :] - ref) ** 2).sum(axis=-1), axis=-1)
    return np.where(grass, nearest, -1)


def _block_shares(labels: np.ndarray, count: int, block: int) -> np.ndarray:
    """Per block, the share of its pixels each of `count` levels draws: (rows, columns, count)."""
    h, w = labels.shape[0] // block * block, labels.shape[1] // block * block
    grid = labels[:h, :w].reshape(h // block, block, w // block, block).transpose(0, 2, 1, 3)
    tiles = grid.reshape(h // block, w // block, block * block)
    return np.stack([(tiles == k).mean(axis=-1) for k in range(count)], axis=-1)


def _luminance(image: np.ndarray, block: int) -> np.ndarray:
    rgb = downsample(to_float(image), block)
    return rgb @ np.array([0.2126, 0.7152, 0.0722], np.float32)


def level_steps(
    shaded: np.ndarray,
    techniques: np.ndarray,
    colors: list,
    reference: np.ndarray | None = None,
    block: int = BLOCK,
) -> dict:
    """Mean brightness step (0 … 1) between neighbouring blocks (right and below) drawn by one
    and the same level (`inside`: 90 % of each block's grass) and between neighbouring grass
    blocks where levels meet or hand over (`across`: different levels, or either block drawn
    by two), their pairs counted, and across / inside. With `reference` (the all-geometry frame), the same across pairs' step
    there (`reference_across`) and across / that."""
    shares = _block_shares(level_labels(shaded, techniques, colors), len(colors), block)
    grass = shares.sum(axis=-1) >= PURE
    pure = grass & (shares.max(axis=-1) >= 0.9 * shares.sum(axis=-1))
    lum = _luminance(shaded, block)[: shares.shape[0], : shares.shape[1]]
    ref = None
    if reference is not None:
        ref = _luminance(reference, block)[: shares.shape[0], : shares.shape[1]]
    inside, across, ref_across = [], [], []
    for a, b in (((slice(None), slice(None, -1)), (slice(None), slice(1, None))),
                 ((slice(None, -1), slice(None)), (slice(1, None), slice(None)))):  # fmt: skip
        # inside: both blocks drawn by one level, the same one; across: both grass, and the
        # two are drawn by different levels, or one of them by two levels at once (a
        # hand-over, whose steps show where it follows (macro-)cells)
        same = pure[a] & pure[b] & (shares[a].argmax(axis=-1) == shares[b].argmax(axis=-1))
        boundary = grass[a] & grass[b] & ~same
        boundary &= ~(pure[a] & pure[b]) | (shares[a].argmax(axis=-1) != shares[b].argmax(axis=-1))
        step = np.abs(lum[a] - lum[b])
        inside.append(step[same])
        across.append(step[boundary])
        if ref is not None:
            ref_across.append(np.abs(ref[a] - ref[b])[boundary])
    inside_all, across_all = np.concatenate(inside), np.concatenate(across)
    out: dict = {"inside_pairs": int(inside_all.size), "across_pairs": int(across_all.size)}
    out["inside"] = float(inside_all.mean()) if inside_all.size else None
    out["across"] = float(across_all.mean()) if across_all.size else None
    # the steps a person sees are the few large ones along a staircase's edges: the 95th
    # percentile of each set as well
    out["inside_p95"] = float(np.percentile(inside_all, 95)) if inside_all.size else None
    out["across_p95"] = float(np.percentile(across_all, 95)) if across_all.size else None
    out["p95_across_over_inside"] = (
        None
        if out["inside_p95"] is None or out["across_p95"] is None
        else out["across_p95"] / max(out["inside_p95"], 1e-9)
    )
    out["across_over_inside"] = (
        None
        if not (inside_all.size and across_all.size)
        else out["across"] / max(out["inside"], 1e-9)
    )
    if ref is not None:
        r = np.concatenate(ref_across)
        out["reference_across"] = float(r.mean()) if r.size else None
        out["across_over_reference"] = (
            None if not (r.size and across_all.size) else out["across"] / max(float(r.mean()), 1e-9)
        )
    return out


def bare_blocks(
    shaded: np.ndarray, soil_magenta: np.ndarray, techniques: np.ndarray, block: int = BLOCK
) -> dict:
    """Where the soil shows through the grass: of a frame, the same frame with the soil under
    the grass drawn magenta, and the frame in the technique colours, the share of terrain
    blocks more than half of whose area shows soil. A pixel's soil share is how far it moved
    towards magenta (blue minus green, 0 … 1); terrain is what the magenta soil or the
    technique colours change (not the sky, nor the bare ground beyond the grassed cells)."""
    a, b, t = to_float(shaded), to_float(soil_magenta), to_float(techniques)
    moved = np.clip((b[..., 2] - b[..., 1]) - (a[..., 2] - a[..., 1]), 0.0, 1.0)
    terrain = (np.abs(a - b).max(axis=-1) > 0.0) | (np.abs(a - t).max(axis=-1) > _GRASS_CHANGE)
    h, w = (moved.shape[0] // block) * block, (moved.shape[1] // block) * block

    def blocks(x):
        return x[:h, :w].reshape(h // block, block, w // block, block).mean(axis=(1, 3))

    soil, land = blocks(moved), blocks(terrain.astype(np.float32))
    counted = land >= 0.5
    share = float((soil[counted] > 0.5).mean()) if counted.any() else 0.0
    return {"bare_blocks": share, "terrain_blocks": int(counted.sum())}


def screen_path(
    world: np.ndarray, view_proj: np.ndarray, size: tuple[int, int]
) -> tuple[np.ndarray, np.ndarray]:
    """World points along a line ((n, 3), in order) as drawn in a frame of `size` (width,
    height; row 0 at the top): those in front of the camera and on screen, about a pixel apart,
    nearest first, and the unit screen direction across the line at each."""
    w, h = size
    clip = np.c_[world, np.ones(len(world))] @ view_proj.T
    front = clip[:, 3] > 1e-6
    ndc = clip[front, :2] / clip[front, 3:4]
    xy = np.c_[(ndc[:, 0] + 1.0) * 0.5 * w, (1.0 - ndc[:, 1]) * 0.5 * h]
    depth = clip[front, 3]
    inside = (xy[:, 0] >= 0) & (xy[:, 0] < w) & (xy[:, 1] >= 0) & (xy[:, 1] < h)
    xy, depth = xy[inside], depth[inside]
    if len(xy) < 2:
        return np.zeros((0, 2)), np.zeros((0, 2))
    if depth[0] > depth[-1]:
        xy = xy[::-1]
    kept, last = [0], xy[0]
    for i in range(1, len(xy)):  # a pixel apart (a few thousand points, once per check)
        if np.hypot(*(xy[i] - last)) >= 1.0:
            kept.append(i)
            last = xy[i]
    xy = xy[kept]
    if len(xy) < 2:
        return np.zeros((0, 2)), np.zeros((0, 2))
    along = np.gradient(xy, axis=0)
    along /= np.maximum(np.linalg.norm(along, axis=1, keepdims=True), 1e-9)
    return xy, np.c_[-along[:, 1], along[:, 0]]


def line_gaps(image: np.ndarray, points: np.ndarray, across: np.ndarray, window: int = 15) -> dict:
    """How continuous a painted line is in a frame: `points` (n, 2) pixel positions (x, y)
    along its drawn path about a pixel apart, `across` (n, 2) the unit screen direction across
    it. At each point the line's contrast is the brightest luminance within 2 pixels across
    less the mean 6 pixels either side; a gap is a point whose contrast falls below half of
    what the line shows around it (the 75th percentile over `window` points), where that
    stands out of the grass's own variation (twice the median difference of the two sides),
    along at least half the line (else "gaps" is None). A line broken into
    dots has about half its points in gaps; one that fades with distance has none."""
    lum = to_float(image).mean(axis=-1)
    h, w = lum.shape

    def at(offset: float) -> np.ndarray:
        p = np.rint(points + offset * across).astype(np.int64)
        inside = (p[:, 0] >= 0) & (p[:, 0] < w) & (p[:, 1] >= 0) & (p[:, 1] < h)
        out = np.full(len(points), np.nan)
        out[inside] = lum[p[inside, 1], p[inside, 0]]
        return out

    near = np.stack([at(o) for o in (-2, -1, 0, 1, 2)])
    line = np.where(
        np.isfinite(near).any(axis=0), np.nanmax(np.nan_to_num(near, nan=-1.0), axis=0), np.nan
    )
    left, right = at(-6.0), at(6.0)
    contrast = line - 0.5 * (left + right)
    valid = np.isfinite(contrast)
    contrast, grass = contrast[valid], np.abs(left - right)[valid]
    if contrast.size < window:
        return {"samples": int(contrast.size), "gaps": None}

    def around(x: np.ndarray, q: float) -> np.ndarray:
        padded = np.pad(x, window // 2, mode="edge")
        return np.percentile(np.lib.stride_tricks.sliding_window_view(padded, window), q, axis=1)

    level = around(contrast, 75)
    # the line shows where it stands out of the grass's own variation beside it
    shown = level > np.maximum(2.0 * around(grass, 50), 3.0 / 255.0)
    gaps = shown & (contrast < 0.5 * level)
    if shown.mean() < 0.5:  # too faint along most of its path to tell a gap from the grass
        return {"samples": int(contrast.size), "gaps": None, "shown": float(shown.mean())}
    return {
        "samples": int(contrast.size),
        "gaps": float(gaps.sum() / max(shown.sum(), 1)),
        "shown": float(shown.mean()),
    }


def stripe_contrast(lod: np.ndarray, reference: np.ndarray, mask: np.ndarray) -> float | None:
    """How much pattern a frame shows at the scale of stripes (2 to 8 pixels) against the
    reference, over `mask`: the standard deviation of the luminance of 2 × 2 blocks less that
    of the 8 × 8 block they lie in, the frame's over the reference's, where whole 8 × 8 blocks
    lie in the mask (a region's own edge is no stripe). Regular stripes across a slope raise
    it; a representation smoother than the blades lowers it. None where too few blocks."""

    def band(image: np.ndarray) -> np.ndarray:
        fine = downsample(image, 2).mean(axis=-1)
        coarse = downsample(image, 8).mean(axis=-1).repeat(4, axis=0).repeat(4, axis=1)
        return fine[: coarse.shape[0], : coarse.shape[1]] - coarse

    cover = downsample(np.repeat(mask[..., None].astype(np.float32), 3, axis=-1), 8)[..., 0]
    inside = (cover > 0.99).repeat(4, axis=0).repeat(4, axis=1)
    if inside.sum() < 64:
        return None
    a, b = band(lod)[inside], band(reference)[inside]
    return float(a.std() / max(float(b.std()), 1e-6))
