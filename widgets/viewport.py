"""The live viewport: shows the frames the render processes draw (render/render_client.py) and
turns mouse and keys into camera moves and brush strokes. No GL on the window's thread: every
change asks for a frame, the draft process answers first with a cheap one, the full-quality
process follows, and the newest frame is painted.

Left drag orbits, right or middle drag pans, the wheel zooms. F toggles fly mode, in which
W A S D move and Q E sink and rise.

While the document's wind blows, the view animates: each state asked for carries the moment of
the wind (seconds of wind since it started blowing here), and the next moment is asked for as
soon as the full-quality frame of the last one is on screen, or after ANIMATION_STEP_MS when
that frame is slower. Where a full frame takes longer than ANIMATION_STEP_MS (a CPU renderer),
the wind shows drafts, as the camera does while it moves, and the next moment is asked for as
soon as the draft of the last one is on screen: the wind then moves as fast as drafts come,
not once per ANIMATION_STEP_MS. With `sharp_wind` (View → Sharp wind frames) a new moment waits for the full
frame of the last one and is drawn without a draft: fewer moments a second on a slow renderer,
each at full quality. Switching the wind off holds the grass still, and so does the Quality
view while it is on (its all-geometry reference takes seconds: the next moment would give it
up).

The Quality view: once a full-quality frame of the newest state is on screen, the full-quality
process draws an all-geometry reference of the same camera in the background and answers with
the difference as a heat map (shown over the frame) and its figures (`quality_ready`); any
change gives it up, and it is asked for again when the view rests.
"""

from __future__ import annotations

from time import monotonic
from typing import ClassVar

import numpy as np
from PySide6.QtCore import QEventLoop, QPoint, QSocketNotifier, Qt, QTimer, Signal
from PySide6.QtGui import QColor, QImage, QPainter
from PySide6.QtWidgets import QWidget

from core.camera import Camera
from core.document import Document
from core.picking import ground_circle, ground_hit, pixel_ray, world_to_texel, zone_rings
from core.stats import FrameStats
from core.view_mode import ViewMode
from core.wind import Wind
from render import protocol as msg
from render.render_client import Frame, RenderClient

# LOD zone rings (thesis Figs. 7.1-7.6 colours): geometry red, volume yellow, image-based blue
ZONE_COLORS = {
    "geometry": (1.0, 0.25, 0.2, 0.95),
    "volume": (1.0, 0.85, 0.1, 0.95),
    "image": (0.3, 0.5, 1.0, 0.95),
}
BRUSH_COLOR = (1.0, 1.0, 1.0, 0.9)
IMAGE_TIMEOUT_S = 600.0
ANIMATION_STEP_MS = 250  # the longest wait for a full frame before the wind moves on
SHARP_STEP_MS = 10_000  # with sharp wind frames: moves on only if a full frame never comes


class GrassViewport(QWidget):
    frame_rendered = Signal(object)  # FrameStats of each frame shown (drafts: preview=True)
    camera_changed = Signal()
    status_changed = Signal(str)  # what the renderer is doing ("" when it is done)
    renderer_restarted = Signal(str)  # what happened to a render process that died
    quality_ready = Signal(object)  # the Quality view's figures for the state on screen
    # painting (tool "paint"): map texel (column, row) under the cursor, keyboard modifiers
    paint_pressed = Signal(float, float, object)
    paint_moved = Signal(float, float)
    paint_released = Signal()

    FLY_KEYS: ClassVar[frozenset] = frozenset(
        {Qt.Key.Key_W, Qt.Key.Key_A, Qt.Key.Key_S, Qt.Key.Key_D, Qt.Key.Key_Q, Qt.Key.Key_E}
    )

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
        self.fly_mode = False
        self._held: set[int] = set()
        self._fly_timer = QTimer(self, interval=30)
        self._fly_timer.timeout.connect(self._fly_step)
        self.last_stats = FrameStats()
        self.continuous = False
        self.tool = "camera"  # camera | paint
        self.brush_size = 24.0  # texels, for the outline
        self.show_zones = False  # LOD zone rings on the ground
        self._painting = False
        self._hover: tuple[float, float] | None = None  # world x, z under the cursor
        # frames: `version` counts the states asked for; a frame shows the newest state seen
        self.version = 0
        self.shown = (0, True)  # (version, preview) of the frame on screen
        self._image: QImage | None = None
        self._images: dict[int, Frame] = {}  # screenshots waited for, by token
        self._token = 0  # screenshots and questions to the renderer
        self._pending = False
        self.quality = False  # the Quality view (set_quality)
        self._quality: tuple[int, QImage, dict] | None = None  # version, heat map, figures
        self._quality_asked = 0  # the version a quality frame was last asked for
        # the wind's animation: the moment drawn, and the clock it follows while the wind blows
        self.wind_time = 0.0
        self._wind_clock: float | None = None  # monotonic() at wind_time 0; None: still
        self._wind_step = QTimer(self, singleShot=True, interval=ANIMATION_STEP_MS)
        self.sharp_wind = False  # each moment of the wind at full quality, no drafts
        self._draft = False  # whether the frame asked for next needs a draft first
        self._full_ms = 0.0  # how long the last full-quality frame took to draw
        self._wind_step.timeout.connect(self._next_moment)
        self.renderer = RenderClient(self._on_frame, self.status_changed.emit, self._on_restart)
        self._notifiers: list[QSocketNotifier] = []
        self._watch()
        self.renderer.attach(document, self.request_frame)
        self.renderer.set_view_state(msg.SetMode(self._mode))
        document.events.wind.connect(self._on_wind)
        self._on_wind(document.wind)
        self.request_frame()

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

    @property
    def animating(self) -> bool:
        """True while the wind blows and the view follows it."""
        return self._wind_clock is not None

    def _on_wind(self, wind: Wind) -> None:
        # the Quality view holds the wind at its moment: its reference takes seconds, and a
        # frame of the next moment would give it up before it is drawn
        if wind.enabled and not self.quality and self._wind_clock is None:
            self._wind_clock = monotonic() - self.wind_time  # on from where it stopped
        elif (not wind.enabled or self.quality) and self._wind_clock is not None:
            self.wind_time = monotonic() - self._wind_clock
            self._wind_clock = None
            self._wind_step.stop()

    def _next_moment(self) -> None:
        if self.animating:
            self.request_frame(draft=not self.sharp_wind)

    def set_sharp_wind(self, on: bool) -> None:
        """While the wind blows: each moment at full quality (on) or drafts between (off)."""
        self.sharp_wind = on

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
        self.quality = on
        self._quality, self._quality_asked = None, 0
        blew = self.animating
        self._on_wind(self.document.wind)  # held while the Quality view is on
        if self.animating and not blew:
            self.request_frame()  # on again from the moment it was held at
        self._ask_quality()
        self.update()

    @property
    def quality_figures(self) -> dict | None:
        """The Quality view's figures for the frame on screen (None until they are drawn)."""
        if self._quality is None or self._quality[0] != self.shown[0]:
            return None
        return self._quality[2]

    def _ask_quality(self) -> None:
        if self.quality and not self.settling and self._quality_asked != self.version:
            self._quality_asked = self.version
            self.status_changed.emit("quality: drawing the all-geometry reference")
            self.renderer.request(
                self.version, self.camera, self._size(), purpose="quality", time=self.wind_time
            )

    @property
    def max_image_size(self) -> int:
        return self.renderer.max_image_size

    # -- frames --------------------------------------------------------------------------------
    def request_frame(self, draft: bool = True) -> None:
        """Something changed: ask for a frame of the new state (once per event-loop turn); a
        draft comes first unless only the wind moved on and sharp wind frames are on."""
        self.version += 1
        self._draft = self._draft or draft
        if not self._pending:
            self._pending = True
            QTimer.singleShot(0, self._send_request)

    def _size(self) -> tuple[int, int]:
        ratio = self.devicePixelRatio()
        return max(1, int(self.width() * ratio)), max(1, int(self.height() * ratio))

    def _send_request(self) -> None:
        self._pending = False
        if self.show_zones:
            lod = self.document.lod(0).for_view(self._size()[1], self.camera.fov_y)
            lod = lod.with_blade_reach(self.document.wind.reach)
            rings = zone_rings(self.document.terrain, self.camera.eye, lod.levels)
            lines = [(ring, ZONE_COLORS[rep]) for ring, rep in rings]
            self.renderer.set_view_state(msg.SetOverlay("zones", lines))
        if self._wind_clock is not None:
            self.wind_time = monotonic() - self._wind_clock
            # the next moment, unless the full frame comes first
            self._wind_step.start(SHARP_STEP_MS if self.sharp_wind else ANIMATION_STEP_MS)
        draft, self._draft = self._draft, False
        self.renderer.request(
            self.version, self.camera, self._size(), time=self.wind_time, draft=draft
        )

    def _on_frame(self, frame: Frame) -> None:
        if frame.purpose == "screenshot":
            self._images[frame.version] = frame
            return
        if frame.purpose == "quality":
            if self.quality and frame.version == self.version:
                h, w = frame.image.shape[:2]
                heat = QImage(frame.image.data, w, h, 4 * w, QImage.Format.Format_RGBA8888)
                self._quality = (frame.version, heat.copy(), frame.figures)
                self.status_changed.emit("")
                self.update()
                self.quality_ready.emit(frame.figures)
            return
        key = (frame.version, frame.stats.preview)
        if frame.version < self.shown[0] or (key[0] == self.shown[0] and key[1] > self.shown[1]):
            return  # older than what is on screen, or a draft of a state shown in full
        self.shown = key
        h, w = frame.image.shape[:2]
        self._image = QImage(frame.image.data, w, h, 4 * w, QImage.Format.Format_RGBA8888).copy()
        self.last_stats = frame.stats
        self.update()
        self.frame_rendered.emit(frame.stats)
        if not frame.stats.preview:
            self._full_ms = frame.stats.t_a_ms
        # the full frame is on screen, or a draft where full frames are too slow to follow the
        # wind: the next moment now
        slow = not self.sharp_wind and self._full_ms > ANIMATION_STEP_MS
        if self.animating and frame.version == self.version and (not frame.stats.preview or slow):
            self._wind_step.stop()
            QTimer.singleShot(0, self._next_moment)
        self._ask_quality()

    def _on_restart(self, role: str, why: str) -> None:
        self._watch()
        self.renderer_restarted.emit(f"the {role} renderer stopped ({why}); started a new one")

    @property
    def settling(self) -> bool:
        """True until a full-quality frame of the newest state is on screen."""
        return self.shown != (self.version, False)

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
        self._token -= 1  # negative: never taken for a view's version
        version = self._token
        self.renderer.request(version, self.camera, size, purpose="screenshot", time=self.wind_time)
        loop = QEventLoop()
        timer = QTimer(interval=20, timeout=lambda: version in self._images and loop.quit())
        timer.start()
        QTimer.singleShot(int(IMAGE_TIMEOUT_S * 1000), loop.quit)
        loop.exec()
        timer.stop()
        self._update_outline()
        frame = self._images.pop(version, None)
        if frame is None:
            raise RuntimeError("the renderer did not draw the image in time")
        return np.ascontiguousarray(frame.image[..., :3])

    def renderer_facts(self, timeout_s: float = 60.0, role: str = "full") -> dict:
        """What a renderer holds (slice counts, terrain, light, patches, props, its copy of the
        document), once it has handled every change sent before this call."""
        self._token -= 1
        token = self._token
        self.renderer.query(token, role)
        loop = QEventLoop()
        found: dict = {}

        def check() -> None:
            facts = self.renderer.facts(token, role)
            if facts is not None:
                found.update(facts)
                loop.quit()

        timer = QTimer(interval=20, timeout=check)
        timer.start()
        QTimer.singleShot(int(timeout_s * 1000), loop.quit)
        loop.exec()
        timer.stop()
        return found

    def paintEvent(self, _event) -> None:
        painter = QPainter(self)
        if self._image is None:
            painter.fillRect(self.rect(), QColor(158, 191, 230))
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, "starting the renderer …")
        else:
            painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform)
            painter.drawImage(self.rect(), self._image)
            if self.quality and self.quality_figures is not None:
                painter.setOpacity(0.7)
                painter.drawImage(self.rect(), self._quality[1])
                painter.setOpacity(1.0)
        painter.end()

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
        self.camera.zoom(0.88**steps)
        self.camera_changed.emit()
        self.request_frame()

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
            self.request_frame()

    def close_renderer(self) -> None:
        """Stop the render processes (the window closes)."""
        self._wind_step.stop()
        self._wind_clock = None
        self.document.events.wind.disconnect(self._on_wind)
        for notifier in self._notifiers:
            notifier.setEnabled(False)
        self.renderer.close()
