"""One view of a frame drawn (render/frame.py FramePipeline.render): each grass type's selected
cells uploaded, then the passes in their order — geometry and image-based grass, the ground and
props, the volume last (it blends over what is drawn) — each timed into the frame's statistics
when measured."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from core.stats import FrameStats
from core.wind import MAX_LEAN
from render.shadows import draw_blade_shadows, ground_shadows
from render.uniforms import FrameUniforms
from render.volume_order import DEPTH_BANDS, beneath_heights, distance_bands, stacked_parts

if TYPE_CHECKING:
    from render.frame import FramePipeline

# geometry and image-based passes first, the volume after the ground (it blends over it)
ORDER = {"geometry": 0, "image": 1, "volume": 2}


class FrameAborted(Exception):
    """A frame given up before it was finished (FramePipeline.render's `abort`)."""


def draw_view(
    p: FramePipeline,
    region: tuple[int, int, int, int],
    query: tuple[FrameUniforms, list],
    stats: FrameStats,
    measure: bool,
) -> None:
    """Ground, props and grass of one view into `region` of the bound framebuffer; the
    statistics add up over the regions of a frame."""
    ctx = p.ctx
    frame, cells = query
    ctx.viewport = region

    def timed(fn: Callable[[], object]) -> float:
        if measure:
            ctx.finish()
        start = time.perf_counter()
        fn()
        if measure:
            ctx.finish()
        return (time.perf_counter() - start) * 1000.0

    p.map_textures.use(sorted({g.density_channel for g in p.grass_types}))
    p.tiling.use()
    p.wind_noise.use()
    drawn = _upload(p, frame, cells, stats)
    passes, volumes = _passes_in_order(p, drawn)
    for representation, renderer in passes:
        _check_abort(p)
        stats.add_time(representation, timed(lambda r=renderer: run_passes(r, frame)))
    # what the ground beyond the blades loses of the sun to their shadows (render/shadows.py)
    p.ground.shadows = ground_shadows(p, frame, cells)
    # The ground and the props after the blades and the image-based grass, whose samples are
    # opaque where they cover (alpha to coverage, no blending): the ground's fragments behind
    # them fail the depth test before they are shaded. Before the volume, which blends over it.
    stats.t_m_ms += timed(lambda: (p.ground.draw(frame, p.map_textures), p.props.draw(frame)))
    # the blades' shadows over the ground, hidden behind the blades by the depth test
    if p.ground.shadows is not None:
        stats.t_s_ms += timed(lambda: draw_blade_shadows(p, frame, drawn))
    count = DEPTH_BANDS if len(volumes) > 1 else 1
    for row in distance_bands([r.distances for r, _ in volumes], count):
        for (renderer, band), part in zip(volumes, row, strict=True):
            if part.stop > part.start:
                _check_abort(p)
                renderer.set_instances(renderer.cells[part], renderer.carriers_of(part))
                renderer.band = band
                stats.t_v_ms += timed(lambda r=renderer: run_passes(r, frame))
    p.overlay.draw(frame)


def _upload(p: FramePipeline, frame: FrameUniforms, cells: list, stats: FrameStats) -> list:
    """Each grass type's selected cells to its renderers (t_u); the instances each level
    draws counted into `stats`. Per grass type: {(representation, slices): (renderer, n)}."""
    drawn = []
    occupancy = p.occupancy()  # up to date with the density map, or None when not used
    pixel = 2.0 * math.tan(math.radians(frame.fov_y) / 2.0) / max(frame.viewport_height, 1)
    for index, (grass, selected) in enumerate(zip(p.grass_types, cells, strict=True)):
        grass.image.view = (frame.eye, pixel, p.terrain)  # its slices' grids
        tolerance = grass.lod.segment_tolerance if p.segment_lod else 0.0
        lean = min(frame.wind.largest_lean + frame.trample_lean, MAX_LEAN)  # the most they bend
        segments = (frame.eye, pixel, lean, frame.draft, tolerance)
        grass.geometry.view = segments if tolerance > 0 else None
        start = time.perf_counter()
        batches = grass.upload(selected, frame.eye, p.terrain, occupancy)
        stats.t_u_ms += (time.perf_counter() - start) * 1000.0
        drawn.append(batches)
        for (representation, slices), (_renderer, count) in batches.items():
            stats.levels.append((index, representation, slices, count))
            stats.add_instances(representation, count)
            if representation == "geometry":
                blades, _whole = blades_drawn(grass, count)
                stats.blades += blades
                stats.triangles += grass.geometry.triangles()
    return drawn


def _passes_in_order(p: FramePipeline, drawn: list) -> tuple[list, list]:
    """The geometry and image-based passes that draw something, in their order, and the
    volume's (renderer, band of heights) in theirs (render/volume_order.py): the volume blends
    its partly covered fragments over what is already drawn, so it goes last, and behind its
    far edge the image-based grass must be there already, not the soil."""
    stack_layers(p.grass_types)
    beneath = beneath_heights(
        [g.image.layer_height() for g in p.grass_types],
        [g.image.textures.height if g.image.textures else 0.0 for g in p.grass_types],
    )
    parts = stacked_parts(beneath)
    passes, volumes = [], []
    for index, batches in enumerate(drawn):
        for (representation, slices), (renderer, count) in batches.items():
            if representation != "volume":
                if count:
                    passes.append(((ORDER[representation], -slices), representation, renderer))
            elif count:
                for turn, band in parts[index]:
                    volumes.append(((turn, -slices), renderer, band))
    passes.sort(key=lambda entry: entry[0])
    volumes.sort(key=lambda entry: entry[0])
    return [(rep, r) for _, rep, r in passes], [(r, band) for _, r, band in volumes]


def _check_abort(p: FramePipeline) -> None:
    if p._abort is not None and p._abort():
        raise FrameAborted


def stack_layers(grass_types: list) -> None:
    """Tell each type's image-based and volume renderers which types' slices lie below its
    own (of two as high, the earlier lies below: render/volume_order.py). The volume's
    horizontal layer holds its type's top view and would cover the grass beneath with it
    (tests/render/test_grass_types.py): it thins as that grass's density rises."""
    heights = [grass.image.layer_height() for grass in grass_types]
    for index, (grass, own) in enumerate(zip(grass_types, heights, strict=True)):
        under = [
            other
            for k, (other, height) in enumerate(zip(grass_types, heights, strict=True))
            if own is not None and height is not None and (height, k) < (own, index)
        ]
        grass.image.under_channels = tuple(other.density_channel for other in under)
        tallest = max(under, key=lambda other: other.image.textures.height, default=None)
        grass.image.under = tallest.image.textures.canopy if tallest is not None else None
        for volume in grass.volumes.values():
            volume.under_channels = grass.image.under_channels


def blades_drawn(grass, count: int) -> tuple[int, int]:
    """The blades `count` geometry instances of a grass type draw, and the triangles they draw
    with all their segments (an all-geometry reference's)."""
    patch = grass.patch
    if patch is None or not count:
        return 0, 0
    visible = int(np.count_nonzero(patch.thresholds <= grass.geometry.density))
    return visible * count, visible * count * patch.params.subdivisions * 2


def run_passes(renderer, frame: FrameUniforms) -> None:
    """A renderer's three passes (thesis ch. 5): prepare, draw, finalize."""
    renderer.prepare(frame)
    renderer.draw()
    renderer.finalize()
