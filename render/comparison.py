"""The LOD frame against an all-geometry reference of the same camera, drawn by one pipeline:
the one comparison behind `sward quality` (app/quality.py) and the designer's Quality view
(render/render_server.py). The figures themselves are core/quality.py's."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np

from core.quality import Comparison, figures
from core.stats import FrameStats
from core.view_mode import ViewMode
from render import context, reference_cache
from render.frame import FramePipeline
from render.grass_type import technique_colors


@contextlib.contextmanager
def drawn_as(pipeline: FramePipeline, mode: str | None = None, view: str = "shaded") -> Iterator:
    """The pipeline draws in `mode` (None: as it is) and `view` meanwhile, then as before.
    All-geometry is the reference every representation is measured against: its blades are
    drawn with all their segments (core/segments.py)."""
    old_mode, old_view, old_segments = pipeline.mode, pipeline.view, pipeline.segment_lod
    try:
        pipeline.view = view
        if mode is not None:
            pipeline.set_mode(mode)
            pipeline.segment_lod = old_segments and mode != ViewMode.GEOMETRY
        yield pipeline
    finally:
        pipeline.view = old_view
        pipeline.segment_lod = old_segments
        if mode is not None:
            pipeline.set_mode(old_mode)


@dataclass
class LodAgainstGeometry:
    lod: np.ndarray  # (h, w, 3) uint8, the LOD frame shaded
    reference: np.ndarray  # the all-geometry frame
    lod_stats: FrameStats
    reference_stats: FrameStats
    comparison: Comparison  # the LOD frame against the reference
    regions: dict[str, np.ndarray]  # each representation's screen region (quarter resolution)
    found: dict  # core/quality.figures, with lod_ms, geometry_ms and speedup

    def heat_map(self) -> np.ndarray:
        """The difference at quarter resolution scaled back up, (h, w, 3) uint8."""
        from core.quality import heat_map

        return heat_map(self.comparison.quarter_map).repeat(4, axis=0).repeat(4, axis=1)


def lod_against_geometry(
    pipeline: FramePipeline,
    camera,
    fbo,
    size: tuple[int, int],
    abort: Callable[[], bool] | None = None,
    lod: tuple[np.ndarray, FrameStats] | None = None,
    document=None,
) -> LodAgainstGeometry:
    """Draw the frame of the pipeline's mode (unless `lod` gives it, image and statistics),
    the same in the representations' colours (their regions) and all-geometry; `abort` may
    stop any pass. With the `document` drawn, the all-geometry frame is the one kept for it
    (render/reference_cache.py) where there is one, or drawn and kept: the LOD settings do
    not change it, so a person who changes them sees the next comparison in a fraction of the
    time."""

    def draw(measure: bool) -> tuple[np.ndarray, FrameStats]:
        stats = pipeline.render(camera, fbo, size, measure, False, abort)
        return context.read_rgb(fbo, size, 3), stats

    with drawn_as(pipeline):
        lod_image, lod_stats = lod if lod is not None else draw(True)
    with drawn_as(pipeline, view="techniques"):
        techniques, _ = draw(False)
    name = None if document is None else reference_cache.key(document, camera, size, pipeline.time)
    kept = None if name is None else reference_cache.load_timed(name, size)
    if kept is not None and kept[1] is not None:
        reference, reference_stats = (
            kept[0],
            FrameStats(t_a_ms=kept[1], width=size[0], height=size[1]),
        )
    else:
        with drawn_as(pipeline, ViewMode.GEOMETRY):
            reference, reference_stats = draw(True)
        if name is not None:
            reference_cache.save(name, reference, reference_stats.t_a_ms)
    found, comparison, regions = figures(reference, lod_image, techniques, technique_colors())
    found.update(
        lod_ms=lod_stats.t_a_ms,
        geometry_ms=reference_stats.t_a_ms,
        reference_kept=kept is not None and kept[1] is not None,
        speedup=reference_stats.t_a_ms / max(lod_stats.t_a_ms, 1e-3),
    )
    return LodAgainstGeometry(
        lod_image, reference, lod_stats, reference_stats, comparison, regions, found
    )
