"""The frame pipeline: ground, then each renderer's prepare / draw / finalize, into a 4× MSAA
framebuffer that is resolved into the caller's framebuffer.

With `measure=True` every pass is bracketed by ctx.finish() so its wall time is the GPU's time
for that technique (GL timer queries are not exact on llvmpipe); without it the frame is only
timed as a whole.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import moderngl
import numpy as np

from core import traversal
from core.camera import Camera
from core.design_maps import DesignMaps
from core.draw_list import draw_list
from core.frustum import Frustum
from core.grid import INSTANCE_DTYPE
from core.lighting import Lighting
from core.lod import REPRESENTATIONS, LodConfig
from core.occupancy import DensityOccupancy
from core.params import SliceParams
from core.patch import GrassPatch
from core.stats import FrameStats
from core.terrain import Terrain
from core.view_mode import ViewMode
from core.wind import Wind
from render.conversion import PatchConverter
from render.design_maps import DesignMapTextures, union
from render.frame_draw import blades_drawn, draw_view
from render.grass_type import GrassTypeRenderer
from render.ground import GroundRenderer
from render.overlay import OverlayRenderer
from render.present import HALF, Presenter, release_fbo
from render.props import PropRenderer
from render.slices import SliceTextures
from render.tiling import TilingNoise
from render.uniforms import FrameUniforms
from render.wind import WindNoise


class FramePipeline:
    def __init__(self, ctx: moderngl.Context, samples: int = 4) -> None:
        self.ctx = ctx
        self.samples = max(0, min(samples, ctx.max_samples))
        # the traversal's compiled walk loads beside the set-up, not in the first frame
        threading.Thread(target=traversal.warm, name="sward-warm-walk").start()
        # one renderer set per grass type (thesis 6.4.5); the first is the patch being designed
        self.grass_types: list[GrassTypeRenderer] = [
            GrassTypeRenderer(ctx, 0)
        ]  # set_grass_types replaces it
        self.ground = GroundRenderer(ctx)
        self.props = PropRenderer(ctx)
        self.overlay = OverlayRenderer(ctx)  # brush outline, LOD rings: drawn last, untimed
        self.mode = ViewMode.GEOMETRY
        self.view = "shaded"  # shaded | techniques | wind
        self.slice_params = SliceParams()
        self.density = 1.0  # the document's global density (set_density)
        # True: slices are converted here, at once, when a mode needs them (command line, tests).
        # The draft render process sets False and converts after its first draft
        # (render/render_server.py).
        self.auto_convert = True
        self._converter: PatchConverter | None = None
        self.light = Lighting()
        self.map_textures = DesignMapTextures(
            ctx, DesignMaps(1)
        )  # neutral until a scene brings maps
        # cells without grass per grass type, skipped before drawing (core/occupancy.py)
        self._occupancy: DensityOccupancy | None = None
        self.skip_bare_cells = True
        self._density_dirty: tuple[int, int, int, int] | None = None
        self.map_textures.maps.changed.connect(self._on_map_changed)
        self._instances = np.zeros(0, INSTANCE_DTYPE)
        self.terrain: Terrain | None = None  # set: cells come from the quadtree traversal
        self.tiling = TilingNoise(ctx)  # the terrain's mirror bits per cell, for macro-cells
        self.wind = Wind()  # the document's (render/binding.py)
        self.time = 0.0  # seconds: the moment of the wind a frame draws
        self.lod_scale = 1.0  # every zone's distances times this (adaptive LOD, core/hold.py)
        self.wind_noise = WindNoise(ctx)
        self.culling = True
        self._targets: dict[tuple[int, int, int], moderngl.Framebuffer] = {}
        self.present = Presenter(ctx)
        self._abort: Callable[[], bool] | None = None
        self.segment_lod = True  # blades far away drawn with fewer segments (core/segments.py)

    # -- scene state (render/binding.py keeps it in step with the document) -------------------
    def set_grass_types(self, types: list[tuple[LodConfig, int]]) -> None:
        """One renderer set per grass type: (LOD levels, density-map channel); patches follow."""
        for grass in self.grass_types:
            grass.release()
        self.grass_types = []
        for lod, channel in types:
            grass = GrassTypeRenderer(self.ctx, channel)
            grass.lod = lod
            grass.set_instances(self._instances)
            grass.set_density(self.density)
            self.grass_types.append(grass)

    def set_mode(self, mode: str) -> None:
        """How the cells are drawn: a ViewMode (core/view_mode.py)."""
        self.mode = ViewMode.parse(mode)
        self._convert()

    def set_patch(self, index: int, patch: GrassPatch) -> None:
        """A new patch for one grass type (0: the first)."""
        self.grass_types[index].geometry.set_patch(patch)
        self._convert()

    def set_lod(self, index: int, lod: LodConfig) -> None:
        """The LOD levels of one grass type, patch and slices kept."""
        self.grass_types[index].lod = lod
        self._convert()

    def set_slice_params(self, params: SliceParams) -> None:
        if params == self.slice_params:
            return
        self.slice_params = params
        self._convert()

    def stale_light_sums(self) -> bool:
        """Whether a draft drew a grass type with the light sums of its patch before an edit,
        or with none."""
        return any(grass.stale_light_sums() for grass in self.grass_types)

    def refresh_light_sums(self, wait: bool = True) -> None:
        for grass in self.grass_types:
            grass.refresh_light_sums(wait)

    def missing(self) -> list[tuple[int, int]]:
        """(grass type, slice count) pairs the current mode needs and nobody converted yet."""
        return [
            (i, n)
            for i, grass in enumerate(self.grass_types)
            for n in grass.missing_slices(self.mode, self.slice_params)
        ]

    @property
    def needs_slices(self) -> bool:
        return bool(self.missing())

    @property
    def converter(self) -> PatchConverter:
        if self._converter is None:
            self._converter = PatchConverter(self.ctx)
        return self._converter

    def set_slice_textures(
        self, textures: SliceTextures, patch: GrassPatch, params: SliceParams, grass_type: int = 0
    ) -> None:
        """Slices converted elsewhere (step by step) for `patch` with `params`."""
        self.grass_types[grass_type].set_slice_textures(
            textures, patch, params, self.slice_params.slices
        )

    def _convert(self) -> None:
        """Slices of every grass type's patch for the volume and image renderers (4.2)."""
        if not self.auto_convert:
            return
        for grass in self.grass_types:
            grass.convert(self.converter, self.mode, self.slice_params)

    def set_props(self, props: np.ndarray) -> None:
        """Boxes standing in the grass (core/props.py), drawn with the ground."""
        self.props.set_props(props)

    def set_design_maps(self, maps: DesignMaps) -> None:
        """The design-map stack every renderer samples; later edits upload their rectangles."""
        self.map_textures.maps.changed.disconnect(self._on_map_changed)
        self.map_textures.release()
        self.map_textures = DesignMapTextures(self.ctx, maps)
        if self.terrain is not None and self.terrain.height_scale > 0:  # the ground mesh's
            self.map_textures.ground_ahead()
        maps.changed.connect(self._on_map_changed)
        self._occupancy = None

    def _on_map_changed(self, name: str, rect) -> None:
        if name == "density" and self._occupancy is not None:
            self._density_dirty = union(self._density_dirty, rect)

    def occupancy(self) -> DensityOccupancy | None:
        """Which cells can show grass of each type, brought up to date with the density map."""
        if self.terrain is None or not self.skip_bare_cells:
            return None
        t = self.terrain
        if self._occupancy is None or (self._occupancy.columns, self._occupancy.rows) != (
            t.columns,
            t.rows,
        ):
            self._occupancy = DensityOccupancy(
                t.columns, t.rows, self.map_textures.maps.layer("density")
            )
            self._density_dirty = None
        elif self._density_dirty is not None:
            self._occupancy.update(self.map_textures.maps.layer("density"), self._density_dirty)
            self._density_dirty = None
        return self._occupancy

    def set_terrain(self, terrain: Terrain) -> None:
        """Cells from a terrain's quadtree: every frame one traversal selects, culls and groups
        them into macro-cells per LOD level (core/traversal.py). Nothing is uploaded here: each
        frame uploads the cells it draws (a 4096² terrain has 16.7 million cells, 940 MB as
        instances, of which a frame draws a few thousand)."""
        self._set_fixed(np.zeros(0, INSTANCE_DTYPE))
        self.terrain = terrain
        self.tiling.set_seed(terrain.mirror_seed)
        self.ground.grass_rect = terrain.rect

    def set_instances(self, instances: np.ndarray) -> None:
        """A fixed set of cells, each classified by distance every frame (no quadtree)."""
        if instances.dtype != INSTANCE_DTYPE:
            raise TypeError("instances must be an INSTANCE_DTYPE array")
        self.terrain = None
        self.tiling.set_seed(None)  # single cells: each instance carries its own bits
        self._set_fixed(instances)
        if instances.size:
            lo = instances["origin"]
            hi = lo + instances["size"]
            self.ground.grass_rect = (
                float(lo[:, 0].min()),
                float(lo[:, 1].min()),
                float(hi[:, 0].max()),
                float(hi[:, 1].max()),
            )

    def _set_fixed(self, instances: np.ndarray) -> None:
        self._instances = instances
        for grass in self.grass_types:
            grass.set_instances(instances)

    def set_density(self, density: float) -> None:
        """The document's global density, 0 … 1, for every grass type."""
        self.density = density
        for grass in self.grass_types:
            grass.set_density(density)

    # -- drawing -----------------------------------------------------------------------------
    def _target(self, size: tuple[int, int], samples: int) -> moderngl.Framebuffer:
        key = (*size, samples)
        if key not in self._targets:
            for old in [k for k in self._targets if k[:2] != size]:  # a resize drops old sizes
                release_fbo(self._targets.pop(old))
            color = self.ctx.texture(size, 4, samples=samples)  # read by Presenter.resolve
            depth = self.ctx.depth_renderbuffer(size, samples=samples)
            self._targets[key] = self.ctx.framebuffer(color, depth)
        return self._targets[key]

    def render(
        self,
        camera: Camera,
        out: moderngl.Framebuffer,
        size: tuple[int, int],
        measure: bool = False,
        half_resolution: bool = False,
        abort: Callable[[], bool] | None = None,
        draft: bool | None = None,
    ) -> FrameStats:
        """Draw one frame into `out` (size w × h) and return its statistics.

        `half_resolution` draws at half the width and height without multisampling (no
        alpha-to-coverage, harder blade edges) and scales the frame up: several times faster on
        llvmpipe.
        `abort` is asked before each pass; when it says yes the frame is dropped (FrameAborted):
        the render process stops a frame that newer input has made stale. `draft` (by default
        as `half_resolution`): the far representations may light a new patch with the light sums of the
        one before an edit (render/facing.py; stale_light_sums says so).
        """
        self._abort = abort
        ctx = self.ctx
        w, h = size
        stats = FrameStats(width=w, height=h)
        t0 = time.perf_counter()
        if half_resolution:
            dw, dh = max(1, w // HALF), max(1, h // HALF)
        else:
            dw, dh = w, h
        if self.mode == ViewMode.COMPARE:  # three columns, one representation each
            edges = [round(dw * k / 3) for k in range(4)]
            views = [
                ((edges[k], 0, edges[k + 1] - edges[k], dh), mode)
                for k, mode in enumerate(REPRESENTATIONS)
            ]
        else:
            views = [((0, 0, dw, dh), self.mode)]
        # The query first (thesis ch. 6, then ch. 5): what every view draws is selected before
        # this frame's GPU work, so the CPU's part does not wait behind it.
        draft = half_resolution if draft is None else draft
        stats.draft = draft
        queries = [self._query(camera, region, mode, stats, draft) for region, mode in views]
        t_clear = time.perf_counter()
        fbo = self.present.target((dw, dh)) if half_resolution else self._target(size, self.samples)
        fbo.use()
        sky = self.light.sky_color
        fbo.clear(sky[0], sky[1], sky[2], 1.0, depth=1.0)
        if measure:
            ctx.finish()
        stats.t_o_ms = (time.perf_counter() - t_clear) * 1000.0
        for (region, _), query in zip(views, queries, strict=True):
            draw_view(self, region, query, stats, measure)
        t1 = time.perf_counter()
        if half_resolution:
            self.present.scale_up(fbo, out, size)
        else:
            self.present.resolve(fbo, out, self.samples)
        if measure:
            ctx.finish()
        end = time.perf_counter()
        stats.t_o_ms += (end - t1) * 1000.0
        stats.t_a_ms = (end - t0) * 1000.0
        return stats

    def geometry_triangles(self, camera: Camera, size: tuple[int, int], mode: str) -> int:
        """The blade triangles a frame of `mode` would draw at this camera, from its query alone
        (nothing drawn): what `sward quality` weighs before drawing an all-geometry reference."""
        stats = FrameStats(width=size[0], height=size[1])
        _, cells = self._query(camera, (0, 0, *size), mode, stats)
        total = 0
        for grass, selected in zip(self.grass_types, cells, strict=True):
            count = int(selected.batches.get(("geometry", 0), np.zeros(0)).size)
            total += blades_drawn(grass, count)[1]
        return total

    def _query(
        self,
        camera: Camera,
        region: tuple[int, int, int, int],
        mode: str,
        stats: FrameStats,
        draft: bool = False,
    ) -> tuple[FrameUniforms, list]:
        """One view's frame uniforms and, per grass type, the cells it draws (t_q)."""
        _, _, w, h = region
        tq = time.perf_counter()
        frame = FrameUniforms(
            view_proj=camera.projection(w / max(h, 1)) @ camera.view(),
            eye=camera.eye,
            light=self.light,
            technique_view=self.view == "techniques",
            wind_view=self.view == "wind",
            viewport_height=h,
            fov_y=camera.fov_y,
            height_scale=self.terrain.height_scale if self.terrain is not None else 0.0,
            tiling=self.tiling.seed is not None,
            wind=self.wind,
            time=self.time,
            draft=draft,
            light_maps=self.map_textures.light_maps,
            trample_lean=self.map_textures.trample_lean,
        )
        stats.t_q_ms += (time.perf_counter() - tq) * 1000.0
        frustum = Frustum.from_camera(camera, w / max(h, 1)) if self.culling else None
        tq = time.perf_counter()
        occupancy = self.occupancy()
        cells = [
            draw_list(
                mode,
                grass.lod.for_view(h, camera.fov_y)
                .scaled(self.lod_scale)
                .with_blade_reach(self.wind.reach),
                camera.eye,
                self.terrain,
                self._instances,
                frustum,
                self.slice_params.slices,
                occupancy,
                grass.density_channel,
            )
            for grass in self.grass_types
        ]
        stats.t_q_ms += (time.perf_counter() - tq) * 1000.0
        return frame, cells

    def release(self) -> None:
        for grass in self.grass_types:
            grass.release()
        self.ground.release()
        self.props.release()
        self.overlay.release()
        self.map_textures.maps.changed.disconnect(self._on_map_changed)
        self.map_textures.release()
        self.tiling.release()
        self.wind_noise.release()
        if self._converter is not None:
            self._converter.release()
        for fbo in self._targets.values():
            release_fbo(fbo)
        self._targets.clear()
        self.present.release()
