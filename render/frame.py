"""The frame pipeline: ground, then each renderer's prepare / draw / finalize, into a 4× MSAA
framebuffer that is resolved into the caller's framebuffer.

With `measure=True` every pass is bracketed by ctx.finish() so its wall time is the GPU's time
for that technique (GL timer queries are not exact on llvmpipe); without it the frame is only
timed as a whole.
"""

from __future__ import annotations

import time

import moderngl
import numpy as np

from core.camera import Camera
from core.design_maps import DesignMaps
from core.grid import INSTANCE_DTYPE
from core.lighting import Lighting
from core.lod import LodConfig
from core.lod import select as lod_select
from core.patch import GrassPatch
from core.stats import FrameStats
from render.context import release_framebuffer
from render.conversion import PatchConverter
from render.design_maps import DesignMapTextures
from render.geometry import GeometryRenderer
from render.ground import GroundRenderer
from render.image import ImageRenderer
from render.props import PropRenderer
from render.slices import SliceTextures
from render.uniforms import FrameUniforms
from render.volume import VolumeRenderer

MODES = ("geometry", "volume", "image", "lod")


class FramePipeline:
    def __init__(self, ctx: moderngl.Context, samples: int = 4) -> None:
        self.ctx = ctx
        self.samples = max(0, min(samples, ctx.max_samples))
        self.geometry = GeometryRenderer(ctx)
        self.volume = VolumeRenderer(ctx)
        self.image = ImageRenderer(ctx)
        self.ground = GroundRenderer(ctx)
        self.props = PropRenderer(ctx)
        # "lod": zones by distance (self.lod); otherwise one representation draws every cell
        self.only = "geometry"
        self.lod = LodConfig()
        self.view = "shaded"  # shaded | techniques
        self.slices = 8  # vertical slices per direction for the volume representation
        self._converter: PatchConverter | None = None
        self._converted_for: GrassPatch | None = None
        self.lighting = Lighting()
        self.design = DesignMapTextures(ctx, DesignMaps(1))  # neutral until a scene brings maps
        self._instances = np.zeros(0, INSTANCE_DTYPE)
        self._targets: dict[tuple[int, int, int], moderngl.Framebuffer] = {}

    # -- scene state -------------------------------------------------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        self.geometry.set_patch(patch)
        if self.only != "geometry":
            self._convert()

    def set_only(self, only: str) -> None:
        if only not in MODES:
            raise ValueError(f"unknown representation {only!r}; use {', '.join(MODES)}")
        self.only = only
        if only != "geometry":
            self._convert()
        if only != "lod":  # a single representation draws every cell again
            for renderer in (self.geometry, self.volume, self.image):
                renderer.set_instances(self._instances)

    def _convert(self) -> None:
        """Slices of the current patch for the volume renderer (thesis 4.2), once per patch."""
        patch = self.geometry.patch
        if patch is None or self._converted_for is patch:
            return
        if self._converter is None:
            self._converter = PatchConverter(self.ctx)
        sliced = self._converter.convert(patch, self.slices)
        self.volume.set_slices(SliceTextures.upload(self.ctx, sliced))
        self.image.textures = self.volume.textures
        self._converted_for = patch

    def set_props(self, props: np.ndarray) -> None:
        """Boxes standing in the grass (core/props.py), drawn with the ground."""
        self.props.set_props(props)

    def set_design_maps(self, maps: DesignMaps) -> None:
        """The design-map stack every renderer samples; later edits upload their rectangles."""
        self.design.release()
        self.design = DesignMapTextures(self.ctx, maps)

    def set_instances(self, instances: np.ndarray) -> None:
        if instances.dtype != INSTANCE_DTYPE:
            raise TypeError("instances must be an INSTANCE_DTYPE array")
        self._instances = instances
        self.geometry.set_instances(instances)
        self.volume.set_instances(instances)
        self.image.set_instances(instances)
        if instances.size:
            o = instances["origin"]
            self.ground.grass_rect = (
                float(o[:, 0].min()),
                float(o[:, 1].min()),
                float(o[:, 0].max() + 1),
                float(o[:, 1].max() + 1),
            )

    def set_density(self, density: float) -> None:
        self.geometry.density = float(density)
        self.volume.density = float(density)
        self.image.density = float(density)

    # -- drawing -----------------------------------------------------------------------------
    def _target(self, size: tuple[int, int], samples: int) -> moderngl.Framebuffer:
        key = (*size, samples)
        if key not in self._targets:
            for old in [k for k in self._targets if k[:2] != size]:  # a resize drops old sizes
                _release_fbo(self._targets.pop(old))
            color = self.ctx.renderbuffer(size, 4, samples=samples)
            depth = self.ctx.depth_renderbuffer(size, samples=samples)
            self._targets[key] = self.ctx.framebuffer(color, depth)
        return self._targets[key]

    def render(
        self,
        camera: Camera,
        out: moderngl.Framebuffer,
        size: tuple[int, int],
        measure: bool = False,
        preview: bool = False,
    ) -> FrameStats:
        """Draw one frame into `out` (size w × h) and return its statistics.

        `preview` draws without multisampling (no alpha-to-coverage, harder blade edges), several
        times faster on llvmpipe: the viewport uses it while the camera is being dragged.
        """
        ctx = self.ctx
        w, h = size
        stats = FrameStats(width=w, height=h)
        patch = self.geometry.patch
        visible = 0
        if patch is not None:
            visible = int(np.count_nonzero(patch.thresholds <= self.geometry.density))

        t0 = time.perf_counter()
        tq = time.perf_counter()
        frame = FrameUniforms(
            view_proj=camera.projection(w / max(h, 1)) @ camera.view(),
            eye=camera.eye,
            lighting=self.lighting,
            technique_view=self.view == "techniques",
            viewport_height=h,
            fov_y=camera.fov_y,
        )
        stats.t_q_ms = (time.perf_counter() - tq) * 1000.0

        fbo = self._target(size, 0 if preview else self.samples)
        fbo.use()
        ctx.viewport = (0, 0, w, h)
        sky = self.lighting.sky_color
        fbo.clear(sky[0], sky[1], sky[2], 1.0, depth=1.0)

        def timed(fn) -> float:
            if measure:
                ctx.finish()
            start = time.perf_counter()
            fn()
            if measure:
                ctx.finish()
            return (time.perf_counter() - start) * 1000.0

        self.design.use()
        stats.t_m_ms = timed(lambda: (self.ground.draw(frame), self.props.draw(frame)))

        if self.only == "lod":
            tq = time.perf_counter()
            parts = lod_select(self._instances, camera.eye, self.lod)
            self.geometry.set_instances(parts["geometry"])
            self.volume.set_instances(parts["volume"])
            self.image.set_instances(parts["image"])
            stats.t_q_ms += (time.perf_counter() - tq) * 1000.0
            counts = {r: int(parts[r].size) for r in parts}
        else:
            counts = {
                r: (self._instances.size if r == self.only else 0)
                for r in ("geometry", "volume", "image")
            }
        stats.c_g, stats.c_v, stats.c_i = counts["geometry"], counts["volume"], counts["image"]
        if patch is not None:
            stats.blades = visible * stats.c_g
            stats.triangles = stats.blades * patch.params.subdivisions * 2
        # The volume blends its partly covered fragments over what is already drawn, so it goes
        # last: behind its far edge the image-based grass must be there already, not the soil.
        for renderer, count, key in (
            (self.geometry, stats.c_g, "t_g_ms"),
            (self.image, stats.c_i, "t_i_ms"),
            (self.volume, stats.c_v, "t_v_ms"),
        ):
            if count:
                setattr(stats, key, timed(lambda r=renderer: _passes(r, frame)))
        ctx.copy_framebuffer(out, fbo)
        if measure:
            ctx.finish()
        stats.t_a_ms = (time.perf_counter() - t0) * 1000.0
        return stats

    def release(self) -> None:
        self.geometry.release()
        self.volume.release()
        self.image.release()
        self.ground.release()
        self.props.release()
        self.design.release()
        if self._converter is not None:
            self._converter.release()
        for fbo in self._targets.values():
            _release_fbo(fbo)
        self._targets.clear()


def _passes(renderer, frame: FrameUniforms) -> None:
    """A renderer's three passes (thesis ch. 5): prepare, draw, finalize."""
    renderer.prepare(frame)
    renderer.draw()
    renderer.finalize()


def _release_fbo(fbo: moderngl.Framebuffer) -> None:
    release_framebuffer(fbo, *fbo.color_attachments, fbo.depth_attachment)
