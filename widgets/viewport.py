"""The live viewport: a QOpenGLWidget that drives the moderngl frame pipeline.

Left drag orbits, right or middle drag pans, the wheel zooms. F toggles fly mode, in which
W A S D move and Q E sink and rise. Frames are drawn on demand (after an edit or a camera move);
while the camera or the brush moves they are drawn at half resolution without MSAA (preview),
then once more at full quality.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np
from PySide6.QtCore import QPoint, Qt, QTimer, Signal
from PySide6.QtGui import QSurfaceFormat
from PySide6.QtOpenGLWidgets import QOpenGLWidget

from core.camera import Camera
from core.design_maps import DesignMaps
from core.lighting import Lighting
from core.lod import LodConfig
from core.params import SliceParams
from core.patch import GrassPatch
from core.picking import ground_circle, ground_hit, pixel_ray, world_to_texel, zone_rings
from core.stats import FrameStats
from core.terrain import Terrain
from render import context
from render.context import release_framebuffer
from render.frame import FramePipeline
from widgets.slice_builder import SliceBuilder


def gl_format() -> QSurfaceFormat:
    fmt = QSurfaceFormat()
    fmt.setVersion(3, 3)
    fmt.setProfile(QSurfaceFormat.OpenGLContextProfile.CoreProfile)
    fmt.setDepthBufferSize(24)
    return fmt


# LOD zone rings (thesis Figs. 7.1-7.6 colours): geometry red, volume yellow, image-based blue
ZONE_COLORS = {
    "geometry": (1.0, 0.25, 0.2, 0.95),
    "volume": (1.0, 0.85, 0.1, 0.95),
    "image": (0.3, 0.5, 1.0, 0.95),
}
BRUSH_COLOR = (1.0, 1.0, 1.0, 0.9)


class GrassViewport(QOpenGLWidget):
    frame_rendered = Signal(object)  # FrameStats
    camera_changed = Signal()
    # painting (tool "paint"): map texel (column, row) under the cursor, keyboard modifiers
    paint_pressed = Signal(float, float, object)
    paint_moved = Signal(float, float)
    paint_released = Signal()

    FLY_KEYS: ClassVar[frozenset] = frozenset(
        {Qt.Key.Key_W, Qt.Key.Key_A, Qt.Key.Key_S, Qt.Key.Key_D, Qt.Key.Key_Q, Qt.Key.Key_E}
    )

    def __init__(self, camera: Camera, parent=None) -> None:
        super().__init__(parent)
        self.setFormat(gl_format())
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.setMinimumSize(320, 240)
        self.camera = camera
        self.ctx = None
        self.pipeline: FramePipeline | None = None
        self._patch: GrassPatch | None = None
        self._instances: np.ndarray | None = None
        self._terrain: Terrain | None = None
        self._density = 1.0
        self._mode = "lod"
        self._view = "shaded"
        self._lod = LodConfig()
        self._slice_params = SliceParams()
        self._maps: DesignMaps | None = None
        self._props: np.ndarray | None = None
        self._lighting: Lighting | None = None
        self._grass_types: list = []
        self.slices = SliceBuilder(self)
        self._drag: QPoint | None = None
        self._button = Qt.MouseButton.NoButton
        self.fly_mode = False
        self._held: set[int] = set()
        self._fly_timer = QTimer(self)
        self._fly_timer.setInterval(30)
        self._fly_timer.timeout.connect(self._fly_step)
        self.last_stats = FrameStats()
        self.continuous = False  # draw frame after frame (profiling)
        self.max_image_size = 0  # largest image side render_image can draw (after initializeGL)
        self.tool = "camera"  # camera | paint
        self.brush_size = 24.0  # texels, for the outline
        self.show_zones = False  # LOD zone rings on the ground
        self._painting = False
        self._hover: tuple[float, float] | None = None  # world x, z under the cursor
        self._settle = QTimer(self)  # full-quality frame once the cursor rests
        self._settle.setSingleShot(True)
        self._settle.setInterval(300)
        self._settle.timeout.connect(self.update)

    # -- scene state (may arrive before the GL context exists) ------------------------------
    def set_patch(self, patch: GrassPatch) -> None:
        self._patch = patch
        self._upload(lambda pipeline: pipeline.set_patch(patch))
        self.slices.schedule()

    def set_mode(self, mode: str) -> None:
        """lod | geometry | volume | image | compare (render/frame.py MODES)."""
        self._mode = mode
        self._upload(lambda pipeline: pipeline.set_only(mode))
        self.slices.schedule()

    @property
    def mode(self) -> str:
        return self._mode

    def set_view(self, view: str) -> None:
        """shaded | techniques."""
        self._view = view
        if self.pipeline is not None:
            self.pipeline.view = view
        self.update()

    def set_lod(self, lod: LodConfig) -> None:
        self._lod = lod
        if self.pipeline is not None:
            self.pipeline.set_lod(lod)
        self.slices.schedule()  # a new volume level may need slices of another count
        self.update()

    def set_grass_patch(self, index: int, patch: GrassPatch) -> None:
        """A new patch for a further grass type (1 …); its slices are converted again."""
        _, lod, channel = self._grass_types[index - 1]
        self._grass_types[index - 1] = (patch, lod, channel)
        self._upload(lambda pipeline: pipeline.set_layer_patch(index, patch))
        self.slices.schedule()

    def set_layer_lod(self, index: int, lod: LodConfig) -> None:
        """The LOD levels of one grass type (0: the designed patch)."""
        if index == 0:
            self.set_lod(lod)
            return
        patch, _, channel = self._grass_types[index - 1]
        self._grass_types[index - 1] = (patch, lod, channel)
        if self.pipeline is not None:
            self.pipeline.set_layer_lod(index, lod)
        self.slices.schedule()
        self.update()

    def set_slice_params(self, params: SliceParams) -> None:
        self._slice_params = params
        if self.pipeline is not None:
            self.pipeline.set_slice_params(params)
        self.slices.schedule()
        self.update()

    def set_props(self, props: np.ndarray) -> None:
        self._props = props
        self._upload(lambda pipeline: pipeline.set_props(props))

    def set_grass_types(self, types: list) -> None:
        """Further grass types: (patch, LOD levels, density channel) each."""
        self._grass_types = list(types)
        self._upload(lambda pipeline: pipeline.set_grass_types(types))
        self.slices.schedule()

    def set_lighting(self, lighting: Lighting) -> None:
        """Sun, ambient light and fog (core/lighting.py)."""
        self._lighting = lighting
        if self.pipeline is not None:
            self.pipeline.lighting = lighting
        self.update()

    def set_design_maps(self, maps: DesignMaps) -> None:
        self._maps = maps
        self._upload(lambda pipeline: pipeline.set_design_maps(maps))

    def set_instances(self, instances: np.ndarray) -> None:
        self._instances = instances
        self._terrain = None
        self._upload(lambda pipeline: pipeline.set_instances(instances))

    def set_terrain(self, terrain: Terrain) -> None:
        self._terrain = terrain
        self._instances = None
        self._upload(lambda pipeline: pipeline.set_terrain(terrain))

    def _upload(self, fn) -> None:
        """Run a GL upload with this widget's context current (later, in initializeGL, if
        the context does not exist yet), then schedule a frame."""
        if self.pipeline is not None:
            self.makeCurrent()
            fn(self.pipeline)
            self.doneCurrent()
        self.update()

    def set_density(self, density: float) -> None:
        self._density = density
        if self.pipeline is not None:
            self.pipeline.set_density(density)
        self.update()

    def set_camera(self, camera: Camera) -> None:
        self.camera = camera
        self.camera_changed.emit()
        self.update()

    # -- painting ----------------------------------------------------------------------------
    def set_tool(self, tool: str) -> None:
        """camera: left drag orbits; paint: left drag paints, right drag orbits, middle pans."""
        self.tool = tool
        self.setMouseTracking(tool == "paint")
        self.setCursor(
            Qt.CursorShape.CrossCursor if tool == "paint" else Qt.CursorShape.ArrowCursor
        )
        if tool != "paint":
            self._hover = None
        self._update_outline()

    def set_brush_size(self, texels: float) -> None:
        self.brush_size = texels
        self._update_outline()

    def set_show_zones(self, on: bool) -> None:
        self.show_zones = on
        if not on and self.pipeline is not None:
            self.pipeline.overlay.set_lines("zones", [])
        self.update()

    def ground_at(self, x: float, y: float) -> np.ndarray | None:
        """The world point of the ground under widget position (x, y), or None."""
        if self._terrain is None:
            return None
        ray = pixel_ray(self.camera, x, y, max(self.width(), 1), max(self.height(), 1))
        # the height map as painted so far: the terrain follows it only after the stroke
        heights = None
        if self._maps is not None and self._terrain.height_scale > 0:
            heights = self._maps.layer("height")[..., 0]
        return ground_hit(self._terrain, *ray, heights=heights)

    def texel_at(self, x: float, y: float) -> tuple[float, float] | None:
        """The design-map texel (column, row) under widget position (x, y), or None."""
        hit = self.ground_at(x, y)
        if hit is None or self._maps is None:
            return None
        self._hover = (float(hit[0]), float(hit[2]))
        return world_to_texel(self._terrain, self._maps.size, self._hover[0], self._hover[1])

    def _update_outline(self) -> None:
        lines = []
        if self.tool == "paint" and self._hover is not None and self._maps is not None:
            radius = 0.5 * self.brush_size * self._terrain.columns / self._maps.size[0]
            lines.append((ground_circle(self._terrain, *self._hover, radius), BRUSH_COLOR))
        if self.pipeline is not None:
            self.pipeline.overlay.set_lines("brush", lines)
        self.update()

    # -- GL ----------------------------------------------------------------------------------
    def initializeGL(self) -> None:
        self.ctx = context.wrap_current()
        # asked here, with this widget's context current (ctx.info asks whichever one is)
        self.max_image_size = int(self.ctx.info["GL_MAX_RENDERBUFFER_SIZE"])
        pipeline = FramePipeline(self.ctx)
        pipeline.auto_convert = False  # self.slices converts step by step
        pipeline.set_density(self._density)
        pipeline.view = self._view
        pipeline.set_lod(self._lod)
        pipeline.set_slice_params(self._slice_params)
        if self._maps is not None:
            pipeline.set_design_maps(self._maps)
        if self._props is not None:
            pipeline.set_props(self._props)
        if self._lighting is not None:
            pipeline.lighting = self._lighting
        if self._patch is not None:
            pipeline.set_patch(self._patch)
        if self._grass_types:
            pipeline.set_grass_types(self._grass_types)
        if self._instances is not None:
            pipeline.set_instances(self._instances)
        if self._terrain is not None:
            pipeline.set_terrain(self._terrain)
        pipeline.set_only(self._mode)
        self.pipeline = pipeline
        QTimer.singleShot(0, self.slices.schedule)

    def paintGL(self) -> None:
        if self.pipeline is None or self.ctx is None:
            return
        ratio = self.devicePixelRatio()
        size = (max(1, int(self.width() * ratio)), max(1, int(self.height() * ratio)))
        out = self.ctx.detect_framebuffer(self.defaultFramebufferObject())
        if self.show_zones and self._terrain is not None:
            rings = zone_rings(self._terrain, self.camera.eye, self.pipeline.lod.levels)
            self.pipeline.overlay.set_lines(
                "zones", [(ring, ZONE_COLORS[rep]) for ring, rep in rings]
            )
        moving = (
            self._drag is not None
            or self._painting
            or self._fly_timer.isActive()
            or self._settle.isActive()
        )
        stats = self.pipeline.render(self.camera, out, size, measure=True, preview=moving)
        self.last_stats = stats
        self.frame_rendered.emit(stats)
        if self.continuous:
            QTimer.singleShot(0, self.update)

    def render_image(self, size: tuple[int, int]) -> np.ndarray:
        """The current view drawn at full quality at any size (screenshots larger than the
        window): (h, w, 3) uint8, top row first, without the brush outline and zone rings."""
        if self.pipeline is None or self.ctx is None:
            raise RuntimeError("the viewport has no GL context yet")
        self.makeCurrent()
        overlay = self.pipeline.overlay
        groups = dict(overlay.groups)
        try:
            for name in groups:
                overlay.set_lines(name, [])
            out = self.ctx.framebuffer(self.ctx.renderbuffer(size, 4))
            self.pipeline.render(self.camera, out, size)
            image = context.read_rgb(out, size)
            release_framebuffer(out, *out.color_attachments)
        finally:
            for name, lines in groups.items():
                overlay.set_lines(name, lines)
            self.doneCurrent()
        return image

    @property
    def settling(self) -> bool:
        """True while frames are previews because the cursor just moved."""
        return self._settle.isActive()

    def set_continuous(self, on: bool) -> None:
        self.continuous = on
        self.update()

    # -- mouse and keys ----------------------------------------------------------------------
    def mousePressEvent(self, event) -> None:
        if self.tool == "paint" and event.button() == Qt.MouseButton.LeftButton:
            pos = event.position()
            texel = self.texel_at(pos.x(), pos.y())
            if texel is not None:
                self._painting = True
                self.paint_pressed.emit(texel[0], texel[1], event.modifiers())
                self._update_outline()
            return
        self._drag = event.position().toPoint()
        self._button = event.button()

    def mouseReleaseEvent(self, event) -> None:
        if self._painting:
            self._painting = False
            self.paint_released.emit()
        self._drag = None
        self._button = Qt.MouseButton.NoButton
        self.update()  # the full-quality frame after a preview drag

    def mouseMoveEvent(self, event) -> None:
        if self.tool == "paint" and self._drag is None:
            pos = event.position()
            texel = self.texel_at(pos.x(), pos.y())
            if texel is not None and self._painting:
                self.paint_moved.emit(texel[0], texel[1])
            self._settle.start()
            self._update_outline()
            return
        if self._drag is None:
            return
        pos = event.position().toPoint()
        dx, dy = pos.x() - self._drag.x(), pos.y() - self._drag.y()
        self._drag = pos
        orbit = Qt.MouseButton.RightButton if self.tool == "paint" else Qt.MouseButton.LeftButton
        if self._button == orbit:
            self.camera.orbit(-0.4 * dx, 0.3 * dy)
        else:
            scale = 1.0 / max(self.height(), 1)
            self.camera.pan(-dx * scale, dy * scale)
        self.camera_changed.emit()
        self.update()

    def wheelEvent(self, event) -> None:
        steps = event.angleDelta().y() / 120.0
        self.camera.zoom(0.88**steps)
        self.camera_changed.emit()
        self.update()

    def keyPressEvent(self, event) -> None:
        key = event.key()
        if key == Qt.Key.Key_F:
            self.fly_mode = not self.fly_mode
            self._held.clear()
            self._fly_timer.stop()
        elif self.fly_mode and key in self.FLY_KEYS:
            if not event.isAutoRepeat():
                self._held.add(key)
            if not self._fly_timer.isActive():
                self._fly_timer.start()
        else:
            super().keyPressEvent(event)

    def keyReleaseEvent(self, event) -> None:
        if not event.isAutoRepeat():
            self._held.discard(event.key())
        if not self._held and self._fly_timer.isActive():
            self._fly_timer.stop()
            self.update()
        super().keyReleaseEvent(event)

    def _fly_step(self) -> None:
        k = Qt.Key
        speed = 0.03 * max(self.camera.distance, 1.0)
        forward = (k.Key_W in self._held) - (k.Key_S in self._held)
        strafe = (k.Key_D in self._held) - (k.Key_A in self._held)
        rise = (k.Key_E in self._held) - (k.Key_Q in self._held)
        if forward or strafe or rise:
            self.camera.fly(forward * speed, strafe * speed, rise * speed)
            self.camera_changed.emit()
            self.update()

    def release_gl(self) -> None:
        self.slices.wait()
        if self.pipeline is not None:
            self.makeCurrent()
            self.pipeline.release()
            self.pipeline = None
            self.doneCurrent()
