"""The designer window: the open project (one document, core/document.py), the viewport that
draws it, the panels that edit it through undoable commands, and the controllers."""

from __future__ import annotations

import sys

from PySide6.QtCore import QSettings, Qt, QTimer
from PySide6.QtGui import QUndoStack
from PySide6.QtWidgets import (
    QApplication,
    QDockWidget,
    QFrame,
    QLabel,
    QMainWindow,
    QScrollArea,
    QUndoView,
)

from app import commands, view_settings
from app.autosave import INTERVAL_MS, Autosave, default_directory
from app.history_keys import HistoryKeys
from app.image_output import save_recording
from app.map_files import MapFileActions
from app.menus import build_menus, fill_camera_menu
from app.paint_rules import PaintController, PaintRules
from app.project_actions import ProjectActions
from app.qt_dialogs import QtDialogs
from app.scenes import DEFAULT_SCENE, get_scene
from app.status_line import quality_text, status_text
from core.brush import Stroke
from core.document import CameraSpec, Document
from widgets.light_panel import LightPanel
from widgets.lod_panel import LodPanel
from widgets.map_view import MapView
from widgets.paint_panel import PaintPanel
from widgets.patch_panel import PatchPanel
from widgets.profile_view import ProfileOverlay, ProfilePanel
from widgets.viewport import GrassViewport
from widgets.wind_panel import WindPanel

HEIGHTS_SETTLE_MS = 250  # the terrain follows a changed height map this long after the edit


class DesignerWindow(QMainWindow):
    def __init__(self, document: Document) -> None:
        super().__init__()
        self.document = document
        self.setWindowTitle(f"Sward — {document.name}[*]")
        self.undo_stack = QUndoStack(self)
        self._history_keys = HistoryKeys(self)  # Ctrl+Z from a field with nothing to undo
        QApplication.instance().installEventFilter(self._history_keys)
        self.history_cap = commands.MEMORY_CAP
        self.dialogs = QtDialogs(self)
        settings = self.settings = QSettings("Sward", "Sward")
        self.projects = ProjectActions(
            lambda: self.document,
            self.open_document,
            self.undo_stack,
            self.dialogs,
            settings,
            lambda: self.fill_recent_menu(),
        )
        self.autosave = Autosave(default_directory(), self.projects, self.undo_stack, self.dialogs)
        self.projects.titled = lambda name: self.setWindowTitle(f"Sward — {name}[*]")
        self.projects.saved = self.autosave.discard  # recovery never offers work older than it
        self._autosave_timer = QTimer(self, interval=INTERVAL_MS, timeout=self.autosave.save_now)
        self._autosave_timer.start()
        self.undo_stack.cleanChanged.connect(self._on_clean_changed)

        self.viewport = GrassViewport(document)
        self.setCentralWidget(self.viewport)
        self.paint_panel = PaintPanel(document.grass_names)
        self._heights = QTimer(self, singleShot=True, interval=HEIGHTS_SETTLE_MS)
        self._heights.timeout.connect(lambda: self.document.rebuild_terrain())
        self.painter = PaintController(
            document, self.paint_panel, self._push_stroke, self._heights.start
        )
        self.map_view = MapView()
        self.map_view.set_maps(document.maps)
        self.map_files = MapFileActions(
            lambda: self.document,
            self.paint_panel,
            self._push_map,
            self.dialogs,
            lambda s, v, t: self.push(commands.PlaceSpecies(self.document, s, v, t)),
        )
        self.rules = PaintRules(document, self.paint_panel, self.map_view, self.painter, self.push)
        self._renderer_status = ""

        self.panel = PatchPanel(document)
        self.patch_dock = self._dock("Patch", self.panel, "patch-dock")
        self.patch_dock.setMinimumWidth(330)
        self.lod_panel = LodPanel(document)
        self.light_panel = LightPanel(document.light)
        self.light_dock = self._dock("Light", self.light_panel, "light-dock", scroll=True)
        self.wind_panel = WindPanel(document.wind)
        self.wind_dock = self._dock("Wind", self.wind_panel, "wind-dock", scroll=True)
        self.paint_dock = self._dock("Paint", self.paint_panel, "paint-dock", scroll=True)
        self.lod_dock = self._dock("LOD zones", self.lod_panel, "lod-dock", scroll=True)
        self.overlay = ProfileOverlay(self.viewport)
        self.profile_panel = ProfilePanel()
        self.profile_dock = self._dock("Timings", self.profile_panel, "profile-dock")
        self.map_dock = self._dock("Map", self.map_view, "map-dock")
        self.history = QUndoView(self.undo_stack)
        self.history.setEmptyLabel("(opened)")
        self.history_dock = self._dock("History", self.history, "history-dock")
        self.tabifyDockWidget(self.patch_dock, self.paint_dock)
        self.tabifyDockWidget(self.paint_dock, self.lod_dock)
        self.tabifyDockWidget(self.lod_dock, self.light_dock)
        self.tabifyDockWidget(self.light_dock, self.wind_dock)
        self.tabifyDockWidget(self.history_dock, self.profile_dock)
        self.tabifyDockWidget(self.profile_dock, self.map_dock)
        self.history_dock.raise_()
        self.patch_dock.raise_()
        self.resizeDocks([self.patch_dock], [380], Qt.Orientation.Horizontal)
        # the panels above, the Map (as wide as the docks), history and timings below
        self.resizeDocks([self.patch_dock, self.map_dock], [60, 40], Qt.Orientation.Vertical)

        self.status = QLabel("starting the renderer …")
        self.statusBar().addWidget(self.status, 1)  # a message (saved, resampled) shows over it
        self._connect()
        self._bind_document(document)
        build_menus(self)
        self.resize(1200, 760)
        view_settings.restore(self, settings)  # layout and View preferences of last time

    def _connect(self) -> None:
        """Panels -> commands -> the document; viewport and builder -> the window."""
        self.panel.params_edited.connect(self._push_params)
        self.panel.density_edited.connect(self._push_density)
        self.panel.slices_edited.connect(self._push_slices)
        self.lod_panel.lod_edited.connect(
            lambda i, config: self.push(commands.set_lod(self.document, i, config))
        )
        self.lod_panel.view_height_edited.connect(
            lambda configs, text: self.push(commands.set_lods(self.document, configs, text))
        )
        self.lod_panel.zones_toggled.connect(self.viewport.set_show_zones)
        self.lod_panel.tune_requested.connect(self.tune_dialog)
        self.light_panel.light_edited.connect(
            lambda light: self.push(
                commands.set_light(self.document, light, self.light_panel.dial.drag)
            )
        )
        self.viewport.camera_changed.connect(
            lambda: self.light_panel.show_view(self.viewport.camera.yaw)
        )
        self.light_panel.show_view(self.viewport.camera.yaw)
        self.wind_panel.wind_edited.connect(
            lambda wind: self.push(commands.set_wind(self.document, wind))
        )
        self.profile_panel.continuous_toggled.connect(self.viewport.set_continuous)
        self.profile_panel.recorded.connect(lambda frames: save_recording(self, frames))
        self.viewport.status_changed.connect(self._on_renderer_status)
        self.viewport.renderer_restarted.connect(self._on_renderer_restarted)
        self.viewport.frame_rendered.connect(self._on_frame)
        self.viewport.fly.changed.connect(lambda: self._show_status(self.viewport.last_stats))
        self.viewport.quality_ready.connect(self._on_quality)
        for source in (self.viewport, self.map_view):
            source.paint_pressed.connect(self._paint_press)
            source.paint_moved.connect(self.painter.move)
            source.paint_released.connect(self.painter.release)
        self.paint_panel.brush_changed.connect(self._on_brush_changed)
        self.paint_panel.import_requested.connect(lambda: self.map_files.import_map())
        self.paint_panel.export_requested.connect(lambda: self.map_files.export_map())
        self.paint_panel.species_requested.connect(lambda: self.map_files.species_from_image())

    def _bind_document(self, document: Document) -> None:
        """The window's own views of the document (the others bind themselves)."""
        document.events.light.connect(self.light_panel.show_light)
        document.events.wind.connect(self.wind_panel.show_wind)
        document.events.cameras.connect(self._on_cameras_changed)

    def _unbind_document(self, document: Document) -> None:
        document.events.light.disconnect(self.light_panel.show_light)
        document.events.wind.disconnect(self.wind_panel.show_wind)
        document.events.cameras.disconnect(self._on_cameras_changed)

    def _dock(self, title: str, widget, name: str, scroll: bool = False) -> QDockWidget:
        """A dock on the right; a panel of fields scrolls when its dock is made short (so the
        docks below, the Map's among them, can take the height)."""
        dock = QDockWidget(title, self)
        dock.setObjectName(name)
        if scroll:
            area = QScrollArea()
            area.setWidgetResizable(True)
            area.setFrameShape(QFrame.Shape.NoFrame)
            area.setWidget(widget)
            widget = area
        dock.setWidget(widget)
        self.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, dock)
        return dock

    # -- the open project ----------------------------------------------------------------
    def open_document(self, document: Document) -> None:
        """Show another project (its patch, terrain, maps, cameras); edits of the old one
        cannot be undone across the switch."""
        QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
        try:
            self._unbind_document(self.document)
            self.document = document
            self._bind_document(document)
            self.setWindowTitle(f"Sward — {document.name}[*]")
            self.undo_stack.clear()
            self.overlay.frames.clear()
            self.viewport.set_document(document)
            self.viewport.set_camera(document.camera())
            self.painter.set_document(document)
            self.map_view.set_maps(document.maps)
            self.rules.set_document(document)
            self.panel.set_document(document)
            self.lod_panel.set_document(document)
            self.paint_panel.set_grass_names(document.grass_names)
            self.light_panel.show_light(document.light)
            self.wind_panel.show_wind(document.wind)
            fill_camera_menu(self)
        finally:
            QApplication.restoreOverrideCursor()

    def set_wind_blowing(self, on: bool) -> None:
        """Wind on or off (View → Wind blows): one undo step, the Wind dock follows."""
        if on != self.document.wind.enabled:
            self.push(commands.set_wind(self.document, self.document.wind.replace(enabled=on)))

    def bookmark_view(self, name: str | None = None) -> bool:
        """Keep the current view as a named camera of the project (saved with it)."""
        if name is None:
            name = self.dialogs.ask_text("Bookmark this view", "Name (View → Cameras lists it)")
            if name is None:
                return False
        name = name.strip()
        if not name:
            return False
        cam = self.viewport.camera
        spec = CameraSpec(
            tuple(float(v) for v in cam.eye), tuple(cam.target), far=cam.far, near=cam.near
        )
        cameras = {**self.document.cameras, name: spec}
        self.push(commands.set_cameras(self.document, cameras, f"bookmark {name}"))
        return True

    def _on_cameras_changed(self, _cameras) -> None:
        fill_camera_menu(self)

    def _on_clean_changed(self, clean: bool) -> None:
        self.setWindowModified(not clean)  # "*" in the title: unsaved changes

    def fill_recent_menu(self) -> None:
        self.recent_menu.clear()
        for path in self.projects.recent():
            act = self.recent_menu.addAction(path)
            act.triggered.connect(lambda _=False, p=path: self.projects.open(p))
        self.recent_menu.setEnabled(bool(self.projects.recent()))

    # -- painting ------------------------------------------------------------------------
    def _paint_press(self, x: float, y: float, modifiers) -> None:
        mods = Qt.KeyboardModifier(modifiers or 0)
        self.painter.press(
            x,
            y,
            erase=bool(mods & Qt.KeyboardModifier.ControlModifier),
            smooth=bool(mods & Qt.KeyboardModifier.ShiftModifier),
        )

    def set_painting(self, on: bool) -> None:
        self.viewport.set_tool("paint" if on else "camera")
        self.viewport.set_brush_size(self.paint_panel.size_box.value())
        if on:
            self.paint_dock.show()
            self.paint_dock.raise_()

    def leave_painting(self) -> None:
        """Escape: drop a pending eyedropper pick, else leave the paint tool."""
        if self.painter.eyedropper:
            self.painter.cancel_eyedropper()
        elif self.paint_action.isChecked():
            self.paint_action.setChecked(False)

    def _on_brush_changed(self) -> None:
        self.viewport.set_brush_size(self.paint_panel.size_box.value())
        self.map_view.brush_size = float(self.paint_panel.size_box.value())
        self.map_view.show_layer(*self.paint_panel.target)
        flat = (
            self.paint_panel.target[0] == "height" and self.document.terrain_spec.height_scale <= 0
        )
        self.paint_panel.message.setText(
            f"{self.document.name} is flat (height scale 0): its height map has no effect"
            if flat
            else ""
        )

    # -- edits become undoable commands --------------------------------------------------
    def push(self, command: commands.Command) -> None:
        """Every edit goes through here: onto the undo stack, under its memory cap."""
        dropped = commands.push(self.undo_stack, command, self.history_cap)
        if dropped:
            self.statusBar().showMessage(
                f"undo history over {self.history_cap // 2**20} MB: "
                f"the oldest {dropped} step(s) can no longer be undone",
                6000,
            )

    def _push_stroke(self, stroke: Stroke, label: str) -> None:
        self.push(commands.PaintStroke(stroke, label))

    def _push_map(self, layer: str, channel: int | None, values, text: str) -> None:
        self.push(commands.SetMap(self.document.maps, layer, channel, values, text))

    def _push_params(self, index: int, params) -> None:
        if params != self.document.params(index):
            self.push(commands.set_params(self.document, index, params))

    def _push_slices(self, slices) -> None:
        if slices != self.document.slices:
            self.push(commands.set_slices(self.document, slices))

    def _push_density(self, density: float) -> None:
        if density != self.document.density:
            self.push(commands.set_density(self.document, density))

    # -- results -------------------------------------------------------------------------
    def _on_renderer_status(self, text: str) -> None:
        self._renderer_status = text
        self._show_status(self.viewport.last_stats)

    def _on_renderer_restarted(self, text: str) -> None:
        self.statusBar().showMessage(text, 10000)

    def _on_frame(self, stats) -> None:
        """A frame arrived: full frames' timings go to the overlay and the Timings dock."""
        if not stats.draft:
            self.lod_panel.show_counts(stats)
            self.overlay.add(stats)
            self.profile_panel.add(stats)
        self._show_status(stats)

    def _on_quality(self, figures: dict) -> None:
        """The Quality view's figures (quarter-resolution FLIP over the frame and per
        technique, what LOD saves) in the status line."""
        self._show_status(self.viewport.last_stats)

    def _show_status(self, stats) -> None:
        vp = self.viewport
        fly = vp.fly.speed if vp.fly.on else None
        text = status_text(stats, self._renderer_status, fly, vp.schedule.wind_on_drafts)
        if vp.quality_figures is not None:
            text = quality_text(vp.quality_figures)
        elif vp.quality and not self._renderer_status:
            text = "quality: waiting for the view to rest · " + text
        held = vp.zone_scale.describe()
        self.status.setText(f"{text}  ·  {held}" if held else text)

    def tune_dialog(self) -> None:
        """LOD zones dock → Tune… (app/tune_job.py)."""
        from app.tune_job import TuneJob

        self.tune_job = TuneJob(self)
        self.tune_job.dialog.show()

    def hold_frame_rate(self, on: bool) -> None:
        """View → Hold frame rate…: ask for the frame time to hold (the last full frame's to
        begin with); adaptive LOD scales every zone's distances to keep it."""
        target = None
        if on:
            last = self.viewport.last_stats.t_a_ms
            target = self.dialogs.ask_number(
                "Hold frame rate",
                "Full-quality frame time to hold",
                last or 100.0,
                1.0,
                60000.0,
                " ms",
            )
            if target is None:
                self.hold_action.setChecked(False)  # comes back here with on = False
                return
        self.viewport.zone_scale.set_target(target)
        self._show_status(self.viewport.last_stats)

    def closeEvent(self, event) -> None:
        if not self.projects.confirm_discard():
            event.ignore()
            return
        view_settings.save(self, self.settings)
        QApplication.instance().removeEventFilter(self._history_keys)
        self._autosave_timer.stop()
        self.autosave.close()
        self.viewport.close_renderer()
        super().closeEvent(event)


def run_designer(scene_name: str = DEFAULT_SCENE) -> int:
    QApplication.setApplicationName("Sward")
    app = QApplication.instance() or QApplication(sys.argv)
    window = DesignerWindow(get_scene(scene_name).document())
    window.show()
    window.autosave.recover_if_any()
    return app.exec()
