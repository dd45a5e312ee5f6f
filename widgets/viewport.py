"""The live viewport: a QOpenGLWidget that drives the moderngl frame pipeline.

Left drag orbits, right or middle drag pans, the wheel zooms. F toggles fly mode, in which
W A S D move and Q E sink and rise. Frames are drawn on demand (after an edit or a camera move);
while the camera or the brush moves they are drawn at half resolution without MSAA (preview),
then once more at full quality.
"""

from __future__ import annotations

import contextlib
import time
from typing import ClassVar

import numpy as np
from PySide6.QtCore import QPoint, Qt, QTimer, Signal
from PySide6.QtGui import QSurfaceFormat
from PySide6.QtOpenGLWidgets import QOpenGLWidget

from core.camera import Camera
from core.document import Document
from core.patch import GrassPatch
from core.picking import ground_circle, ground_hit, pixel_ray, world_to_texel, zone_rings
from core.stats import FrameStats
from core.view_mode import ViewMode
from render import context
from render.binding import DocumentBinding, PatchRequest
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

    def __init__(
        self, document: Document, request_patch: PatchRequest | None = None, parent=None
    ) -> None:
        """`request_patch(index, params)` asks for a grass type's patch to be made off this
        thread; it comes back through `set_patch`."""
        super().__init__(parent)
        self.setFormat(gl_format())
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.setMinimumSize(320, 240)
        self.document = document
        self.camera = document.camera()
        self._request_patch = request_patch
        self.ctx = None
        self.pipeline: FramePipeline | None = None
        self.binding: DocumentBinding | None = None
        self._mode = ViewMode.LOD
        self._view = "shaded"
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

    # -- the document (render/binding.py keeps the pipeline in step with it) ---------------
    def set_document(self, document: Document) -> None:
        """Show another project; its grass, maps and terrain reach the pipeline through one
        new binding (at once, or in initializeGL if the GL context does not exist yet)."""
        self.document = document
        if self.pipeline is None:
            return
        self.binding.detach()
        self.binding = DocumentBinding(
            self.pipeline, document, self._request_patch, self._current, self._document_changed
        )
        self._document_changed()

    def set_patch(self, index: int, patch: GrassPatch) -> None:
        """A patch made off the window's thread for grass type `index` (stale ones are
        dropped by the binding); before the GL context exists it is asked for again."""
        if self.binding is not None:
            self.binding.set_patch(index, patch)

    @contextlib.contextmanager
    def _current(self):
        self.makeCurrent()
        try:
            yield
        finally:
            self.doneCurrent()

    def _document_changed(self) -> None:
        self.slices.schedule()  # a new patch, slice count or volume level may need slices
        self.update()

    def set_mode(self, mode: str) -> None:
        """A ViewMode: lod | geometry | volume | image | compare."""
        self._mode = ViewMode.parse(mode)
        if self.pipeline is not None:
            with self._current():
                self.pipeline.set_mode(self._mode)
        self._document_changed()

    @property
    def mode(self) -> ViewMode:
        return self._mode

    def set_view(self, view: str) -> None:
        """shaded | techniques."""
        self._view = view
        if self.pipeline is not None:
            self.pipeline.view = view
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
        terrain, maps = self.document.terrain, self.document.maps
        ray = pixel_ray(self.camera, x, y, max(self.width(), 1), max(self.height(), 1))
        # the height map as painted so far: the terrain follows it only after the stroke
        heights = maps.layer("height")[..., 0] if terrain.height_scale > 0 else None
        return ground_hit(terrain, *ray, heights=heights)

    def texel_at(self, x: float, y: float) -> tuple[float, float] | None:
        """The design-map texel (column, row) under widget position (x, y), or None."""
        hit = self.ground_at(x, y)
        if hit is None:
            return None
        self._hover = (float(hit[0]), float(hit[2]))
        terrain, size = self.document.terrain, self.document.maps.size
        return world_to_texel(terrain, size, self._hover[0], self._hover[1])

    def _update_outline(self) -> None:
        lines = []
        if self.tool == "paint" and self._hover is not None:
            terrain = self.document.terrain
            radius = 0.5 * self.brush_size * terrain.columns / self.document.maps.size[0]
            lines.append((ground_circle(terrain, *self._hover, radius), BRUSH_COLOR))
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
        pipeline.view = self._view
        pipeline.set_mode(self._mode)
        # the context is current here already: no makeCurrent around the first synchronisation
        self.binding = DocumentBinding(pipeline, self.document, self._request_patch)
        self.binding.current = self._current
        self.binding.changed = self._document_changed
        self.pipeline = pipeline
        QTimer.singleShot(0, self.slices.schedule)

    def paintGL(self) -> None:
        if self.pipeline is None or self.ctx is None:
            return
        ratio = self.devicePixelRatio()
        size = (max(1, int(self.width() * ratio)), max(1, int(self.height() * ratio)))
        out = self.ctx.detect_framebuffer(self.defaultFramebufferObject())
        if self.show_zones:
            levels = self.document.lod(0).levels
            rings = zone_rings(self.document.terrain, self.camera.eye, levels)
            self.pipeline.overlay.set_lines(
                "zones", [(ring, ZONE_COLORS[rep]) for ring, rep in rings]
            )
        moving = (
            self._drag is not None
            or self._painting
            or self._fly_timer.isActive()
            or self._settle.isActive()
        )
        taken = time.monotonic()
        stats = self.pipeline.render(self.camera, out, size, measure=True, preview=moving)
        stats.state_time = taken
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
            self.binding.detach()
            self.binding = None
            with self._current():
                self.pipeline.release()
            self.pipeline = None
