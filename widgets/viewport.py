"""The live viewport: shows the frames the render processes draw (render/render_client.py) and
turns mouse and keys into camera moves and brush strokes. No GL on the window's thread: which
frames are asked for and which are shown is render/frame_schedule.py's (the wind's moments, draft
before full, the Quality view); the viewport gives it Qt's timers, the camera and the size, and
paints what it shows.

Left drag orbits, right or middle drag pans, the wheel zooms. F toggles fly mode, in which
W A S D move and Q E sink and rise.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, QSocketNotifier, Qt, Signal
from PySide6.QtGui import QColor, QImage, QPainter
from PySide6.QtWidgets import QWidget

from core.camera import Camera
from core.document import Document
from core.frame_schedule import FrameSchedule
from core.picking import ground_circle, ground_hit, pixel_ray, world_to_texel, zone_rings
from core.stats import FrameStats
from core.view_mode import ViewMode
from core.wind import Wind
from render import protocol as msg
from render.render_client import Frame, RenderClient
from widgets import view_legends
from widgets.fly import Fly
from widgets.qt_clock import QtClock, wait_until
from widgets.zone_scale import ZoneScale

# LOD zone rings (thesis Figs. 7.1-7.6 colours): geometry red, volume yellow, image-based blue
ZONE_COLORS = {
    "geometry": (1.0, 0.25, 0.2, 0.95),
    "volume": (1.0, 0.85, 0.1, 0.95),
    "image": (0.3, 0.5, 1.0, 0.95),
}
BRUSH_COLOR = (1.0, 1.0, 1.0, 0.9)
IMAGE_TIMEOUT_S = 600.0


class GrassViewport(QWidget):
    frame_rendered = Signal(object)  # FrameStats of each frame shown (drafts: draft=True)
    camera_changed = Signal()
    status_changed = Signal(str)  # what the renderer is doing ("" when it is done)
    renderer_restarted = Signal(str)  # what happened to a render process that died
    quality_ready = Signal(object)  # the Quality view's figures for the state on screen
    # painting (tool "paint"): map texel (column, row) under the cursor, keyboard modifiers
    paint_pressed = Signal(float, float, object)
    paint_moved = Signal(float, float)
    paint_released = Signal()

    def __init__(self, document: Document, parent=None) -> None:
        super().__init__(parent)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.setMinimumSize(320, 240)
        self.setAttribute(Qt.WidgetAttribute.WA_OpaquePaintEvent)
        self.document = document
        self.camera = document.camera()
        self._mode = ViewMode.LOD
        self._drag: QPoint | None = None
        self._button = Qt.MouseButton.NoButton
        self.fly = Fly(self)
        self.zone_scale = ZoneScale(self)  # adaptive LOD's factor on every zone's distances
        self.fly.set_scene(max(document.terrain_spec.columns, document.terrain_spec.rows))
        self.last_stats = FrameStats()
        self.continuous = False
        self.tool = "camera"  # camera | paint
        self.brush_size = 24.0  # texels, for the outline
        self.show_zones = False  # LOD zone rings on the ground
        self._painting = False
        self._hover: tuple[float, float] | None = None  # world x, z under the cursor
        self._image: QImage | None = None
        self._heat: QImage | None = None  # the Quality view's difference over the frame
        self.renderer = RenderClient(self._on_frame, self.status_changed.emit, self._on_restart)
        self.schedule = FrameSchedule(
            self.renderer,
            lambda: (self.camera, self._size()),
            QtClock(self),
            on_show=self._show,
            on_quality=self._show_quality,
            on_quality_asked=lambda: self.status_changed.emit(
                "quality: comparing with all-geometry (drawn once, then kept)"
            ),
            before_request=self._zone_rings,
        )
        self._notifiers: list[QSocketNotifier] = []
        self._watch()
        self.renderer.attach(document, self.request_frame)
        self.renderer.set_view_state(msg.SetMode(self._mode))
        document.events.wind.connect(self._on_wind)
        self._on_wind(document.wind)
        self.request_frame()

    # the schedule's state, read by the window and the tests
    version = property(lambda self: self.schedule.version)
    settling = property(lambda self: self.schedule.settling)
    animating = property(lambda self: self.schedule.animating)
    wind_time = property(lambda self: self.schedule.wind_time)
    sharp_wind = property(lambda self: self.schedule.sharp_wind)
    quality = property(lambda self: self.schedule.quality)
    quality_figures = property(lambda self: self.schedule.quality_figures)

    def _watch(self) -> None:
        """Read each render process's messages when its pipe has some (no polling)."""
        for notifier in self._notifiers:
            notifier.setEnabled(False)
            notifier.deleteLater()
        self._notifiers = []
        for role, conn in self.renderer.connections().items():
            notifier = QSocketNotifier(conn.fileno(), QSocketNotifier.Type.Read, self)
            notifier.activated.connect(lambda *_, r=role: self.renderer.receive(r))
            self._notifiers.append(notifier)

    # -- the document and the view -------------------------------------------------------------
    def set_document(self, document: Document) -> None:
        """Show another project: the render processes get it whole."""
        self.fly.set_scene(max(document.terrain_spec.columns, document.terrain_spec.rows))
        self.document.events.wind.disconnect(self._on_wind)
        self.document = document
        document.events.wind.connect(self._on_wind)
        self._on_wind(document.wind)
        self.renderer.attach(document, self.request_frame)
        self.request_frame()

    def set_mode(self, mode: str) -> None:
        """A ViewMode: lod | geometry | volume | image | compare."""
        self._mode = ViewMode.parse(mode)
        self.renderer.set_view_state(msg.SetMode(self._mode))
        self.request_frame()

    @property
    def mode(self) -> ViewMode:
        return self._mode

    def set_view(self, view: str) -> None:
        """shaded | techniques."""
        self.renderer.set_view_state(msg.SetView(view))
        self.request_frame()

    def _on_wind(self, wind: Wind) -> None:
        self.schedule.set_wind(wind.enabled)

    def set_sharp_wind(self, on: bool) -> None:
        """While the wind blows: each moment at full quality (on) or drafts between (off)."""
        self.schedule.sharp_wind = on

    def set_camera(self, camera: Camera) -> None:
        self.camera = camera
        self.camera_changed.emit()
        self.request_frame()

    def set_continuous(self, on: bool) -> None:
        """Full frames one after another (profiling)."""
        self.continuous = on
        self.renderer.set_view_state(msg.SetContinuous(on))
        self.request_frame()

    def set_quality(self, on: bool) -> None:
        """The Quality view: the difference against all-geometry over the frame, when at rest."""
        self._heat = None
        left = self.quality and not on
        self.schedule.set_quality(on)
        if left:  # its figures and its "drawing the reference" no longer describe the view
            self.status_changed.emit("")
        self.update()

    def image_size_limit(self) -> int:
        """The largest side the full-quality renderer draws, waiting (the window's events
        handled) for a renderer that has not said it yet: just started, or started again."""
        if self.renderer.max_image_size <= 0:
            wait_until(lambda: self.renderer.max_image_size > 0, IMAGE_TIMEOUT_S)
        return self.renderer.max_image_size

    # -- frames --------------------------------------------------------------------------------
    def request_frame(self, draft: bool = True) -> None:
        """Something changed: ask for a frame of the new state (render/frame_schedule.py)."""
        self.schedule.changed(draft)

    def _size(self) -> tuple[int, int]:
        ratio = self.devicePixelRatio()
        return max(1, int(self.width() * ratio)), max(1, int(self.height() * ratio))

    def _zone_rings(self) -> None:
        if self.show_zones:
            lod = self.document.lod(0).for_view(self._size()[1], self.camera.fov_y)
            lod = lod.scaled(self.zone_scale.factor).with_blade_reach(self.document.wind.reach)
            rings = zone_rings(self.document.terrain, self.camera.eye, lod.levels)
            lines = [(ring, ZONE_COLORS[rep]) for ring, rep in rings]
            self.renderer.set_view_state(msg.SetOverlay("zones", lines))

    def _on_frame(self, frame: Frame) -> None:
        self.schedule.arrived(frame)

    def _show(self, frame: Frame) -> None:
        h, w = frame.image.shape[:2]
        self._image = QImage(frame.image.data, w, h, 4 * w, QImage.Format.Format_RGBA8888).copy()
        self.last_stats = frame.stats
        self.update()
        self.zone_scale.shown(frame.stats)
        self.frame_rendered.emit(frame.stats)

    def _show_quality(self, frame: Frame) -> None:
        h, w = frame.image.shape[:2]
        self._heat = QImage(frame.image.data, w, h, 4 * w, QImage.Format.Format_RGBA8888).copy()
        self.status_changed.emit("")
        self.update()
        self.quality_ready.emit(frame.figures)

    def _on_restart(self, role: str, why: str) -> None:
        self._watch()
        self.renderer_restarted.emit(f"the {role} renderer stopped ({why}); started a new one")

    def frame_image(self) -> np.ndarray:
        """The frame on screen as (h, w, 3) uint8 (drafts at their own, smaller size)."""
        if self._image is None:
            return np.zeros((1, 1, 3), np.uint8)
        image = self._image.convertToFormat(QImage.Format.Format_RGB888)
        w, h = image.width(), image.height()
        data = np.frombuffer(image.constBits(), np.uint8, count=image.sizeInBytes())
        return data.reshape(h, image.bytesPerLine())[:, : w * 3].reshape(h, w, 3).copy()

    def render_image(self, size: tuple[int, int]) -> np.ndarray:
        """The current view drawn at full quality at any size (screenshots larger than the
        window): (h, w, 3) uint8, top row first, without the brush outline and zone rings.
        The window keeps handling events while it waits."""
        self.renderer.set_view_state(msg.SetOverlay("brush", []))
        self.renderer.set_view_state(msg.SetOverlay("zones", []))
        version = self.schedule.ask_screenshot(self.camera, size)
        images = self.schedule.screenshots
        wait_until(lambda: version in images, IMAGE_TIMEOUT_S)
        self._update_outline()
        frame = images.pop(version, None)
        if frame is None:
            raise RuntimeError("the renderer did not draw the image in time")
        return np.ascontiguousarray(frame.image[..., :3])

    def renderer_facts(self, timeout_s: float = 60.0, role: str = "full") -> dict:
        """What a renderer holds (slice counts, terrain, light, patches, props, its copy of the
        document), once it has handled every change sent before this call."""
        token = self.schedule.new_token()
        self.renderer.query(token, role)
        found: dict = {}

        def answered() -> bool:
            found.update(self.renderer.facts(token, role) or {})
            return bool(found)

        wait_until(answered, timeout_s)
        return found

    def paintEvent(self, _event) -> None:
        painter = QPainter(self)
        if self._image is None:
            painter.fillRect(self.rect(), QColor(158, 191, 230))
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, "starting the renderer …")
        else:
            painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform)
            painter.drawImage(self.rect(), self._image)
            if self.heat_shown:
                painter.setOpacity(0.7)
                painter.drawImage(self.rect(), self._heat)
                painter.setOpacity(1.0)
            view_legends.paint(painter, self.rect(), self.legends(), ZONE_COLORS)
        painter.end()

    heat_shown = property(
        lambda self: self.quality and self.quality_figures is not None and self._heat is not None
    )

    def legends(self) -> list[view_legends.Legend]:
        """What the colours over the frame mean (Compare's columns, zone rings, heat map)."""
        return view_legends.legends(self._mode, self.show_zones, self.heat_shown)

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self.request_frame()

    # -- painting ------------------------------------------------------------------------------
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
        if not on:
            self.renderer.set_view_state(msg.SetOverlay("zones", []))
        self.request_frame()

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
        self.renderer.set_view_state(msg.SetOverlay("brush", lines))
        self.request_frame()

    # -- mouse and keys ------------------------------------------------------------------------
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

    def mouseMoveEvent(self, event) -> None:
        if self.tool == "paint" and self._drag is None:
            pos = event.position()
            texel = self.texel_at(pos.x(), pos.y())
            if texel is not None and self._painting:
                self.paint_moved.emit(texel[0], texel[1])
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
        self.request_frame()

    def wheelEvent(self, event) -> None:
        steps = event.angleDelta().y() / 120.0
        if self.fly.on:  # flying, the wheel sets the speed
            self.fly.wheel(steps)
            return
        self.camera.zoom(0.88**steps)
        self.camera_changed.emit()
        self.request_frame()

    def keyPressEvent(self, event) -> None:
        if event.key() == Qt.Key.Key_F:
            self.fly.toggle()
        elif not self.fly.press(event.key(), event.isAutoRepeat()):
            super().keyPressEvent(event)

    def keyReleaseEvent(self, event) -> None:
        self.fly.release(event.key(), event.isAutoRepeat())
        super().keyReleaseEvent(event)

    def close_renderer(self) -> None:
        """Stop the render processes (the window closes)."""
        self.schedule.stop()
        self.document.events.wind.disconnect(self._on_wind)
        for notifier in self._notifiers:
            notifier.setEnabled(False)
        self.renderer.close()
