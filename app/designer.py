"""The designer window: viewport, blade panel, undo, background patch generation."""

from __future__ import annotations

import dataclasses
import sys

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QActionGroup, QKeySequence, QUndoStack
from PySide6.QtWidgets import (
    QApplication,
    QDockWidget,
    QFileDialog,
    QInputDialog,
    QLabel,
    QMainWindow,
    QMessageBox,
    QUndoView,
)

from app import commands
from app.autosave import Autosave
from app.map_files import MapFileActions
from app.painting import PaintController
from app.patch_builder import PatchBuilder
from app.projects import ProjectActions
from app.scenes import DEFAULT_SCENE, SCENES, CameraSpec, Scene, get_scene
from core.design import PatchDesign
from core.lighting import Lighting
from core.lod_edit import LodDesign
from core.params import PatchParams, SliceParams
from core.patch import GrassPatch, generate_patch
from widgets.light_panel import LightPanel
from widgets.lod_panel import LodPanel
from widgets.map_view import MapView
from widgets.paint_panel import PaintPanel
from widgets.patch_panel import PatchPanel
from widgets.profile_view import ProfileOverlay, ProfilePanel
from widgets.viewport import GrassViewport

# (mode, menu text, shortcut): how the viewport draws the cells (render/frame.py MODES)
REPRESENTATIONS = (
    ("lod", "&LOD zones (all three)", "Ctrl+1"),
    ("geometry", "&Geometry only", "Ctrl+2"),
    ("volume", "&Volume only", "Ctrl+3"),
    ("image", "&Image-based only", "Ctrl+4"),
    ("compare", "&Compare side by side", "Ctrl+5"),
)


class DesignerWindow(QMainWindow):
    def __init__(self, scene: Scene) -> None:
        super().__init__()
        self.scene = scene
        self.setWindowTitle(f"Sward — {scene.name}[*]")
        self.design = PatchDesign(scene.params, scene.density, scene.slices)
        self.designs = self._grass_designs(scene)  # blade parameters per grass type
        self.undo_stack = QUndoStack(self)
        self.history_cap = commands.MEMORY_CAP
        self.builder = PatchBuilder(self)
        self.projects = ProjectActions(self)
        self.autosave = Autosave(self)
        self.undo_stack.cleanChanged.connect(self._on_clean_changed)
        self.patch: GrassPatch | None = None

        self.viewport = GrassViewport(scene.camera())
        self.lods = lod_design(scene)
        self.paint_panel = PaintPanel(self.lods.names)
        self.painter = PaintController(self)
        self.map_view = MapView()
        self.map_files = MapFileActions(self)
        self._show_scene(scene)
        self.viewport.set_density(self.design.density)
        self.viewport.set_slice_params(self.design.slices)
        self._converting = ""
        self._last_frame = None
        self.setCentralWidget(self.viewport)

        self.panel = PatchPanel(self.design)
        self.panel.set_grass_types(self.lods.names)
        dock = self._dock("Patch", self.panel, "patch-dock")
        dock.setMinimumWidth(330)
        self.lod_panel = LodPanel(self.lods)
        self.light_panel = LightPanel(scene.light())
        self.light_dock = self._dock("Light", self.light_panel, "light-dock")
        self.paint_dock = self._dock("Paint", self.paint_panel, "paint-dock")
        self.lod_dock = self._dock("LOD zones", self.lod_panel, "lod-dock")
        self.overlay = ProfileOverlay(self.viewport)
        self.profile_panel = ProfilePanel()
        self.profile_dock = self._dock("Timings", self.profile_panel, "profile-dock")
        self.profile_panel.continuous_toggled.connect(self.viewport.set_continuous)
        self.profile_panel.recorded.connect(self._save_recording)
        self.map_dock = self._dock("Map", self.map_view, "map-dock")
        self.history = QUndoView(self.undo_stack)
        self.history.setEmptyLabel("(opened)")
        self.history_dock = self._dock("History", self.history, "history-dock")
        self.tabifyDockWidget(dock, self.paint_dock)
        self.tabifyDockWidget(self.paint_dock, self.lod_dock)
        self.tabifyDockWidget(self.lod_dock, self.light_dock)
        self.tabifyDockWidget(self.history_dock, self.profile_dock)
        self.tabifyDockWidget(self.profile_dock, self.map_dock)
        self.history_dock.raise_()
        dock.raise_()
        self.resizeDocks([dock], [380], Qt.Orientation.Horizontal)

        self.status = QLabel("generating patch …")
        self.statusBar().addPermanentWidget(self.status, 1)

        self.panel.params_edited.connect(self._push_params)
        self.panel.density_edited.connect(self._push_density)
        self.panel.slices_edited.connect(self._push_slices)
        self.design.params_changed.connect(self.builder.request)
        self.panel.grass_type_changed.connect(self._on_grass_type_chosen)
        self.design.density_changed.connect(self.viewport.set_density)
        self.design.slices_changed.connect(self.viewport.set_slice_params)
        self.viewport.slices.progress.connect(self._on_conversion)
        self.builder.ready.connect(self._on_patch_ready)
        self.builder.busy.connect(self._on_busy)
        self.viewport.frame_rendered.connect(self._on_frame)
        self.viewport.paint_pressed.connect(self.painter.press)
        self.viewport.paint_moved.connect(self.painter.move)
        self.viewport.paint_released.connect(self.painter.release)
        self.paint_panel.brush_changed.connect(self._on_brush_changed)
        self.painter.heights_changed.connect(self._rebuild_terrain)
        self.map_view.pressed.connect(self.painter.press)
        self.map_view.moved.connect(self.painter.move)
        self.map_view.released.connect(self.painter.release)
        self.paint_panel.import_requested.connect(lambda: self.map_files.import_map())
        self.paint_panel.export_requested.connect(lambda: self.map_files.export_map())
        self.lod_panel.lod_edited.connect(
            lambda i, config: self.push(commands.SetLod(self.lods, i, config))
        )
        self.lod_panel.zones_toggled.connect(self.viewport.set_show_zones)
        self.lods.changed.connect(self.viewport.set_layer_lod)
        self.light_panel.lighting_edited.connect(
            lambda light: self.push(
                commands.SetValue("change light", self, "lighting", self.lighting, light, 2)
            )
        )
        self._build_menus(dock)
        self.resize(1200, 760)
        self.builder.request(self.design.params)

    @property
    def lighting(self) -> Lighting:
        return self.scene.light()

    @lighting.setter
    def lighting(self, light: Lighting) -> None:
        """Sun, ambient and fog of the scene (undoable: commands.SetValue)."""
        self.scene = dataclasses.replace(
            self.scene, lighting=light, fog_distance=light.fog_distance
        )
        self.viewport.set_lighting(light)
        if self.light_panel.lighting != light:
            self.light_panel.show_lighting(light)

    def _dock(self, title: str, widget, name: str) -> QDockWidget:
        dock = QDockWidget(title, self)
        dock.setObjectName(name)
        dock.setWidget(widget)
        self.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, dock)
        return dock

    def _action(self, text: str, key: str, slot, checkable: bool = False) -> QAction:
        act = QAction(text, self, shortcut=QKeySequence(key), checkable=checkable)
        (act.toggled if checkable else act.triggered).connect(slot)
        self.addAction(act)  # works while the menu bar is hidden, e.g. in a test
        return act

    def _build_menus(self, dock: QDockWidget) -> None:
        file_menu = self.menuBar().addMenu("&File")
        scenes = file_menu.addMenu("&New from built-in scene")
        for name in SCENES:
            act = QAction(f"{name} — {SCENES[name].description}", self)
            act.triggered.connect(lambda _=False, n=name: self.projects.new(get_scene(n)))
            scenes.addAction(act)
        open_ = QAction("&Open project…", self, shortcut=QKeySequence.StandardKey.Open)
        open_.triggered.connect(lambda: self.projects.open())
        self.recent_menu = file_menu.addMenu("Open &recent")
        save = QAction("&Save project", self, shortcut=QKeySequence.StandardKey.Save)
        save.triggered.connect(self.projects.save)
        save_as = QAction("Save project &as…", self, shortcut=QKeySequence("Ctrl+Shift+S"))
        save_as.triggered.connect(lambda: self.projects.save_as())
        image = QAction("Save &image…", self, shortcut=QKeySequence("Ctrl+E"))
        image.triggered.connect(self._save_image)
        quit_ = QAction("&Quit", self, shortcut=QKeySequence.StandardKey.Quit)
        quit_.triggered.connect(self.close)
        file_menu.insertAction(scenes.menuAction(), open_)
        file_menu.addActions([save, save_as, image, quit_])
        self.fill_recent_menu()
        edit = self.menuBar().addMenu("&Edit")
        undo = self.undo_stack.createUndoAction(self, "&Undo")
        undo.setShortcut(QKeySequence.StandardKey.Undo)
        redo = self.undo_stack.createRedoAction(self, "&Redo")
        redo.setShortcut(QKeySequence.StandardKey.Redo)
        edit.addActions([undo, redo])
        view = self.menuBar().addMenu("&View")
        reset = QAction("&Reset camera", self, shortcut=QKeySequence("Home"))
        reset.triggered.connect(lambda: self.viewport.set_camera(self.scene.camera()))
        view.addAction(reset)
        self.camera_menu = view.addMenu("&Cameras")
        self._fill_camera_menu()
        bookmark = self._action("&Bookmark this view…", "Ctrl+D", lambda: self.bookmark_view())
        view.addAction(bookmark)
        view.addSeparator()
        group = QActionGroup(self)
        self.mode_actions: dict[str, QAction] = {}
        for mode, text, key in REPRESENTATIONS:
            act = QAction(text, self, shortcut=QKeySequence(key), checkable=True)
            act.setChecked(mode == self.viewport.mode)
            act.triggered.connect(lambda _=False, m=mode: self.viewport.set_mode(m))
            group.addAction(act)
            view.addAction(act)
            self.mode_actions[mode] = act
        self.techniques_action = QAction(
            "&Technique colours", self, shortcut=QKeySequence("T"), checkable=True
        )
        self.techniques_action.setToolTip("geometry red, volume yellow, image-based blue")
        self.techniques_action.toggled.connect(
            lambda on: self.viewport.set_view("techniques" if on else "shaded")
        )
        view.addAction(self.techniques_action)
        self.zones_action = self._action(
            "LOD &zones on the terrain", "Z", self.lod_panel.zones_box.setChecked, checkable=True
        )
        self.lod_panel.zones_box.toggled.connect(self.zones_action.setChecked)
        view.addAction(self.zones_action)
        self.timings_action = self._action(
            "T&imings overlay", "P", self.overlay.setVisible, checkable=True
        )
        view.addAction(self.timings_action)
        view.addSeparator()
        docks = (self.paint_dock, self.lod_dock, self.light_dock, self.map_dock, self.history_dock)
        for d in (dock, *docks, self.profile_dock):
            view.addAction(d.toggleViewAction())
        paint = self.menuBar().addMenu("&Paint")
        self.paint_action = self._action("&Paint in the viewport", "B", self._set_painting, True)
        paint.addAction(self.paint_action)
        paint.addSeparator()
        panel = self.paint_panel
        paint.addActions(
            [
                self._action("&Bigger brush", "]", lambda: panel.scale_size(1.25)),
                self._action("&Smaller brush", "[", lambda: panel.scale_size(0.8)),
                self._action("S&tronger", "=", lambda: panel.add_strength(0.1)),
                self._action("&Weaker", "-", lambda: panel.add_strength(-0.1)),
                self._action("&Eyedropper", "I", self.painter.start_eyedropper),
                self._action("&Leave painting", "Escape", self._leave_painting),
            ]
        )

    @property
    def cameras(self) -> dict:
        return self.scene.cameras

    @cameras.setter
    def cameras(self, cameras: dict) -> None:
        """The scene's named cameras (bookmarks; undoable: commands.SetValue)."""
        self.scene = dataclasses.replace(self.scene, cameras=dict(cameras))
        self._fill_camera_menu()

    def bookmark_view(self, name: str | None = None) -> bool:
        """Keep the current view as a named camera of the scene (saved with the project)."""
        if name is None:
            name, ok = QInputDialog.getText(self, "Bookmark this view", "Name")
            if not ok:
                return False
        name = name.strip()
        if not name:
            return False
        cam = self.viewport.camera
        spec = CameraSpec(
            tuple(float(v) for v in cam.eye), tuple(cam.target), far=cam.far, near=cam.near
        )
        cameras = {**self.scene.cameras, name: spec}
        self.push(commands.SetValue(f"bookmark {name}", self, "cameras", self.cameras, cameras))
        return True

    def _fill_camera_menu(self) -> None:
        self.camera_menu.clear()
        for name in self.scene.cameras:
            act = QAction(name, self)
            act.triggered.connect(
                lambda _=False, n=name: self.viewport.set_camera(self.scene.camera(n))
            )
            self.camera_menu.addAction(act)

    def _on_clean_changed(self, clean: bool) -> None:
        self.setWindowModified(not clean)  # "*" in the title: unsaved changes

    def fill_recent_menu(self) -> None:
        self.recent_menu.clear()
        for path in self.projects.recent():
            act = QAction(path, self)
            act.triggered.connect(lambda _=False, p=path: self.projects.open(p))
            self.recent_menu.addAction(act)
        self.recent_menu.setEnabled(bool(self.projects.recent()))

    def _set_painting(self, on: bool) -> None:
        self.viewport.set_tool("paint" if on else "camera")
        self.viewport.set_brush_size(self.paint_panel.size_box.value())
        if on:
            self.paint_dock.show()
            self.paint_dock.raise_()

    def _leave_painting(self) -> None:
        """Escape: drop a pending eyedropper pick, else leave the paint tool."""
        if self.painter.eyedropper:
            self.painter.cancel_eyedropper()
        elif self.paint_action.isChecked():
            self.paint_action.setChecked(False)

    def _on_brush_changed(self) -> None:
        self.viewport.set_brush_size(self.paint_panel.size_box.value())
        self.map_view.brush_size = float(self.paint_panel.size_box.value())
        self.map_view.show_layer(*self.paint_panel.target)
        flat = self.paint_panel.target[0] == "height" and self.scene.height_scale <= 0
        self.paint_panel.message.setText(
            f"the {self.scene.name} scene is flat (height scale 0): its height map has no effect"
            if flat
            else ""
        )

    def _rebuild_terrain(self) -> None:
        """The terrain's bounding volumes and ground ranges follow a changed height map."""
        scene = dataclasses.replace(self.scene, stack=self.maps.stack)
        self.viewport.set_terrain(scene.terrain())

    def _show_scene(self, scene: Scene) -> None:
        """Hand a scene's terrain, maps, props, LOD levels and fog to the viewport."""
        self.viewport.set_terrain(scene.terrain())
        self.maps = scene.design_maps()
        self.painter.set_maps(self.maps)
        self.map_view.set_maps(self.maps)
        self.viewport.set_design_maps(self.maps)
        self.viewport.set_props(scene.prop_boxes())
        self.viewport.set_lod(scene.lod)
        self.viewport.set_lighting(scene.light())
        self.viewport.set_grass_types(
            [(generate_patch(kind.params), kind.lod, kind.channel) for kind in scene.grass]
        )

    def open_scene(self, scene: Scene) -> None:
        """Replace the scene (its patch, terrain, maps, cameras); edits of the old one cannot
        be undone across the switch."""
        QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
        try:
            self.scene = scene
            self.setWindowTitle(f"Sward — {scene.name}[*]")
            self.undo_stack.clear()
            self.overlay.frames.clear()
            self.lods = lod_design(scene)
            self.lods.changed.connect(self.viewport.set_layer_lod)
            self.lod_panel.set_model(self.lods)
            self.paint_panel.set_grass_names(self.lods.names)
            self.light_panel.show_lighting(scene.light())
            self._show_scene(scene)
            self.viewport.set_camera(scene.camera())
            self._fill_camera_menu()
            self.design.density = scene.density
            self.design.slices = scene.slices
            self.design.params = scene.params
            self.designs = self._grass_designs(scene)
            self.panel.set_grass_types(self.lods.names)
            self.panel.set_blade_model(self.design)
        finally:
            QApplication.restoreOverrideCursor()

    # -- edits become undoable commands ------------------------------------------------------
    def push(self, command: commands.Command) -> None:
        """Every edit goes through here: onto the undo stack, under its memory cap."""
        dropped = commands.push(self.undo_stack, command, self.history_cap)
        if dropped:
            self.statusBar().showMessage(
                f"undo history over {self.history_cap // 2**20} MB: "
                f"the oldest {dropped} step(s) can no longer be undone",
                6000,
            )

    def _push_params(self, params: PatchParams) -> None:
        model = self.panel.blades
        if params != model.params:
            self.push(commands.set_params(model, params))

    def _push_slices(self, slices: SliceParams) -> None:
        if slices != self.design.slices:
            self.push(commands.set_slices(self.design, slices))

    def _push_density(self, density: float) -> None:
        if density != self.design.density:
            self.push(commands.set_density(self.design, density))

    # -- results -----------------------------------------------------------------------------
    def _grass_designs(self, scene: Scene) -> list[PatchDesign]:
        """The first grass type's design, then one per further type (only its blades: density
        and slices are the scene's)."""
        designs = [self.design]
        for i, kind in enumerate(scene.grass, start=1):
            design = PatchDesign(kind.params)
            design.params_changed.connect(lambda p, i=i: self.builder.request(p, i))
            designs.append(design)
        return designs

    def _on_grass_type_chosen(self, index: int) -> None:
        self.panel.set_blade_model(self.designs[index])

    def _on_patch_ready(self, kind: int, patch: GrassPatch) -> None:
        if kind:
            self.viewport.set_grass_patch(kind, patch)
            return
        self.patch = patch
        self.viewport.set_patch(patch)

    def _on_busy(self, busy: bool) -> None:
        if busy:
            self.status.setText("generating patch …")

    def _on_conversion(self, done: int, total: int) -> None:
        self._converting = f"converting slices {done}/{total} · " if total else ""
        self._on_frame(self.viewport.last_stats)

    def _on_frame(self, stats) -> None:
        self.lod_panel.show_counts(stats)
        if stats is not self._last_frame:  # (also called for conversion progress)
            self._last_frame = stats
            self.overlay.add(stats)
            self.profile_panel.add(stats)
        self.status.setText(
            self._converting + f"{stats.blades:,} blades · {stats.triangles:,} triangles · "
            f"cells g/v/i {stats.c_g}/{stats.c_v}/{stats.c_i} · frame {stats.t_a_ms:.0f} ms "
            f"(g {stats.t_g_ms:.0f} · v {stats.t_v_ms:.0f} · i {stats.t_i_ms:.0f} ms)"
            + ("  ·  fly mode (WASD, Q/E, F to leave)" if self.viewport.fly_mode else "")
        )

    def _save_image(self) -> None:
        w, h = self.viewport.width(), self.viewport.height()
        sizes = {
            f"window size ({w} × {h})": 1,
            f"2 × ({2 * w} × {2 * h})": 2,
            f"4 × ({4 * w} × {4 * h})": 4,
        }
        choice, ok = QInputDialog.getItem(self, "Save image", "Size", list(sizes), 0, False)
        if not ok:
            return
        path, _ = QFileDialog.getSaveFileName(self, "Save image", "grass.png", "PNG (*.png)")
        if path:
            self.save_image(path, sizes[choice])

    def save_image(self, path: str, scale: int = 1) -> bool:
        """Save the view as PNG at the viewport's size times `scale` (drawn anew, not
        enlarged)."""
        from PIL import Image

        size = (self.viewport.width() * scale, self.viewport.height() * scale)
        limit = self.viewport.max_image_size
        if max(size) > limit:
            QMessageBox.warning(
                self, "Sward", f"{size[0]} × {size[1]} is larger than this GPU draws ({limit})"
            )
            return False
        QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
        try:
            image = self.viewport.render_image(size)
            Image.fromarray(image).save(path, format="PNG")
        except OSError as exc:
            QMessageBox.warning(self, "Sward", f"cannot write {path}: {exc.strerror or exc}")
            return False
        finally:
            QApplication.restoreOverrideCursor()
        self.statusBar().showMessage(f"saved {size[0]} × {size[1]} image to {path}", 5000)
        return True

    def _save_recording(self, frames: list) -> None:
        if not frames:
            self.statusBar().showMessage("nothing recorded: no frame was drawn", 5000)
            return
        path, _ = QFileDialog.getSaveFileName(
            self, "Save recorded frames", "timings.csv", "CSV (*.csv);;JSON (*.json)"
        )
        if not path:
            return
        try:
            text = self.profile_panel.save(path, frames, scene=self.scene.name)
        except OSError as exc:
            QMessageBox.warning(self, "Sward", f"cannot write {path}: {exc.strerror or exc}")
            return
        self.statusBar().showMessage(text, 5000)

    def closeEvent(self, event) -> None:
        if not self.projects.confirm_discard():
            event.ignore()
            return
        self.autosave.timer.stop()
        self.autosave.discard()
        self.builder.wait()
        self.viewport.release_gl()
        super().closeEvent(event)


def lod_design(scene: Scene) -> LodDesign:
    """The LOD levels of the scene's grass types, as the LOD zone editor edits them."""
    names = ["main grass", *(kind.name for kind in scene.grass)]
    return LodDesign(names, [scene.lod, *(kind.lod for kind in scene.grass)])


def run_designer(scene_name: str = DEFAULT_SCENE) -> int:
    QApplication.setApplicationName("Sward")
    app = QApplication.instance() or QApplication(sys.argv)
    window = DesignerWindow(get_scene(scene_name))
    window.show()
    window.autosave.recover_if_any()
    return app.exec()
