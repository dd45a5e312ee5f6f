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
from core.params import SliceParams
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

# "lod": zones by distance; "compare": the three side by side (the thesis's viewer tool);
# otherwise one representation draws every cell
MODES = ("geometry", "volume", "image", "lod", "compare")
SINGLE = ("geometry", "volume", "image")


class FramePipeline:
    def __init__(self, ctx: moderngl.Context, samples: int = 4) -> None:
        self.ctx = ctx
        self.samples = max(0, min(samples, ctx.max_samples))
        self.geometry = GeometryRenderer(ctx)
        self.volume = VolumeRenderer(ctx)
        self.image = ImageRenderer(ctx)
        self.ground = GroundRenderer(ctx)
        self.props = PropRenderer(ctx)
        self.only = "geometry"  # one of MODES
        self.lod = LodConfig()
        self.view = "shaded"  # shaded | techniques
        self.slice_params = SliceParams()
        # True: slices are converted here, at once, when a mode needs them (command line, tests).
        # The viewport sets False and converts step by step (widgets/slice_builder.py).
        self.auto_convert = True
        self._converter: PatchConverter | None = None
        self._slices_patch: GrassPatch | None = None  # what the current slices were made from
        self._slices_params: SliceParams | None = None
        self.lighting = Lighting()
        self.design = DesignMapTextures(ctx, DesignMaps(1))  # neutral until a scene brings maps
        self._instances = np.zeros(0, INSTANCE_DTYPE)
        self._targets: dict[tuple[int, int, int], moderngl.Framebuffer] = {}

    # -- scene state -------------------------------------------------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        self.geometry.set_patch(patch)
        self._convert()

    def set_only(self, only: str) -> None:
        if only not in MODES:
            raise ValueError(f"unknown representation {only!r}; use {', '.join(MODES)}")
        self.only = only
        self._convert()
        if only != "lod":  # a single representation draws every cell again
            for renderer in (self.geometry, self.volume, self.image):
                renderer.set_instances(self._instances)

    def set_slice_params(self, params: SliceParams) -> None:
        self.slice_params = params
        self._convert()

    @property
    def needs_slices(self) -> bool:
        """The mode draws slices and those of the current patch and parameters are missing."""
        patch = self.geometry.patch
        return (
            self.only != "geometry"
            and patch is not None
            and (self._slices_patch is not patch or self._slices_params != self.slice_params)
        )

    @property
    def converter(self) -> PatchConverter:
        if self._converter is None:
            self._converter = PatchConverter(self.ctx)
        return self._converter

    def set_slice_textures(
        self, textures: SliceTextures, patch: GrassPatch, params: SliceParams
    ) -> None:
        """Slices converted elsewhere (step by step) for `patch` with `params`."""
        self.volume.set_slices(textures)
        self.image.textures = textures
        self._slices_patch, self._slices_params = patch, params

    def _convert(self) -> None:
        """Slices of the current patch for the volume and image renderers (thesis 4.2)."""
        if not self.auto_convert or not self.needs_slices:
            return
        patch, sp = self.geometry.patch, self.slice_params
        assert patch is not None
        sliced = self.converter.convert(patch, sp.slices, (sp.width, sp.height), sp.top)
        self.set_slice_textures(SliceTextures.upload(self.ctx, sliced), patch, sp)

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
        t0 = time.perf_counter()
        fbo = self._target(size, 0 if preview else self.samples)
        fbo.use()
        sky = self.lighting.sky_color
        fbo.clear(sky[0], sky[1], sky[2], 1.0, depth=1.0)
        if self.only == "compare":  # three columns, one representation each
            edges = [round(w * k / 3) for k in range(4)]
            for k, mode in enumerate(SINGLE):
                region = (edges[k], 0, edges[k + 1] - edges[k], h)
                self._draw(camera, region, mode, stats, measure)
        else:
            self._draw(camera, (0, 0, w, h), self.only, stats, measure)
        ctx.viewport = (0, 0, w, h)
        _opaque_alpha(fbo)
        ctx.copy_framebuffer(out, fbo)
        if measure:
            ctx.finish()
        stats.t_a_ms = (time.perf_counter() - t0) * 1000.0
        return stats

    def _draw(
        self,
        camera: Camera,
        region: tuple[int, int, int, int],
        mode: str,
        stats: FrameStats,
        measure: bool,
    ) -> None:
        """Ground, props and grass of one view into `region` of the bound framebuffer; the
        statistics add up over the regions of a frame."""
        ctx = self.ctx
        _, _, w, h = region
        tq = time.perf_counter()
        frame = FrameUniforms(
            view_proj=camera.projection(w / max(h, 1)) @ camera.view(),
            eye=camera.eye,
            lighting=self.lighting,
            technique_view=self.view == "techniques",
            viewport_height=h,
            fov_y=camera.fov_y,
        )
        stats.t_q_ms += (time.perf_counter() - tq) * 1000.0
        ctx.viewport = region

        def timed(fn) -> float:
            if measure:
                ctx.finish()
            start = time.perf_counter()
            fn()
            if measure:
                ctx.finish()
            return (time.perf_counter() - start) * 1000.0

        self.design.use()
        stats.t_m_ms += timed(lambda: (self.ground.draw(frame), self.props.draw(frame)))

        if mode == "lod":
            tq = time.perf_counter()
            parts = lod_select(self._instances, camera.eye, self.lod)
            self.geometry.set_instances(parts["geometry"])
            self.volume.set_instances(parts["volume"])
            self.image.set_instances(parts["image"])
            stats.t_q_ms += (time.perf_counter() - tq) * 1000.0
            counts = {r: int(parts[r].size) for r in parts}
        else:
            counts = {r: (self._instances.size if r == mode else 0) for r in SINGLE}
        patch = self.geometry.patch
        if patch is not None:
            visible = int(np.count_nonzero(patch.thresholds <= self.geometry.density))
            stats.blades += visible * counts["geometry"]
            stats.triangles = stats.blades * patch.params.subdivisions * 2
        stats.c_g += counts["geometry"]
        stats.c_v += counts["volume"]
        stats.c_i += counts["image"]
        # The volume blends its partly covered fragments over what is already drawn, so it goes
        # last: behind its far edge the image-based grass must be there already, not the soil.
        for renderer, key, name in (
            (self.geometry, "t_g_ms", "geometry"),
            (self.image, "t_i_ms", "image"),
            (self.volume, "t_v_ms", "volume"),
        ):
            if counts[name]:
                elapsed = timed(lambda r=renderer: _passes(r, frame))
                setattr(stats, key, getattr(stats, key) + elapsed)

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


def _opaque_alpha(fbo: moderngl.Framebuffer) -> None:
    """Set every pixel's alpha to 1. Alpha-to-coverage and the alpha test leave the fragment's
    alpha in the image; a window compositor (Qt draws the viewport's framebuffer over the window)
    would show the background through the grass."""
    fbo.color_mask = (False, False, False, True)
    fbo.depth_mask = False
    fbo.use()
    fbo.clear(0.0, 0.0, 0.0, 1.0)
    fbo.color_mask = (True, True, True, True)
    fbo.depth_mask = True
    fbo.use()


def _release_fbo(fbo: moderngl.Framebuffer) -> None:
    release_framebuffer(fbo, *fbo.color_attachments, fbo.depth_attachment)
