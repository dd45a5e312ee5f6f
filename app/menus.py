"""The designer's menus and shortcuts (File, Edit, View, Paint)."""

from __future__ import annotations

from PySide6.QtGui import QAction, QActionGroup, QKeySequence

from app import view_settings
from app.export_job import open_export
from app.image_output import save_image_dialog
from app.scenes import SCENES, get_scene
from core.view_mode import ViewMode

# the View menu's view modes: (mode, menu text, shortcut)
VIEW_MODES = (
    (ViewMode.LOD, "&LOD zones (all three)", "Ctrl+1"),
    (ViewMode.GEOMETRY, "&Geometry only", "Ctrl+2"),
    (ViewMode.VOLUME, "&Volume only", "Ctrl+3"),
    (ViewMode.IMAGE, "&Image-based only", "Ctrl+4"),
    (ViewMode.COMPARE, "&Compare side by side", "Ctrl+5"),
)


def _action(window, text: str, key, slot, checkable: bool = False) -> QAction:
    act = QAction(text, window, shortcut=QKeySequence(key), checkable=checkable)
    (act.toggled if checkable else act.triggered).connect(slot)
    window.addAction(act)  # works while the menu bar is hidden, e.g. in a test
    return act


def build_menus(w) -> None:
    """Menus of the designer window `w`; the actions a test or a shortcut reaches are kept
    on the window (mode_actions, techniques_action, zones_action, timings_action,
    quality_action, wind_action, sharp_wind_action, reset_layout_action, paint_action,
    recent_menu, camera_menu)."""
    _file_menu(w)
    _edit_menu(w)
    view = w.menuBar().addMenu("&View")
    _view_cameras_and_modes(w, view)
    _view_toggles(w, view)
    _view_docks(w, view)
    _paint_menu(w)


def _file_menu(w) -> None:
    file_menu = w.menuBar().addMenu("&File")
    file_menu.addAction(
        _action(w, "&Open project…", QKeySequence.StandardKey.Open, lambda: w.projects.open())
    )
    w.recent_menu = file_menu.addMenu("Open &recent")
    scenes = file_menu.addMenu("&New from built-in scene")
    for name, scene in SCENES.items():
        act = scenes.addAction(f"{name} — {scene.description}")
        act.triggered.connect(lambda _=False, n=name: w.projects.new(get_scene(n).document()))
    file_menu.addActions(
        [
            _action(w, "&Save project", QKeySequence.StandardKey.Save, w.projects.save),
            _action(w, "Save project &as…", "Ctrl+Shift+S", lambda: w.projects.save_as()),
            _action(w, "Save &image…", "Ctrl+E", lambda: save_image_dialog(w)),
            _action(w, "E&xport…", "Ctrl+Shift+E", lambda: open_export(w)),
            _action(w, "&Quit", QKeySequence.StandardKey.Quit, w.close),
        ]
    )
    w.fill_recent_menu()


def _edit_menu(w) -> None:
    edit = w.menuBar().addMenu("&Edit")
    undo = w.undo_stack.createUndoAction(w, "&Undo")
    undo.setShortcuts(QKeySequence.StandardKey.Undo)
    redo = w.undo_stack.createRedoAction(w, "&Redo")
    redo.setShortcuts(QKeySequence.StandardKey.Redo)  # every key the platform binds to it
    edit.addActions([undo, redo])


def _view_cameras_and_modes(w, view) -> None:
    view.addAction(
        _action(w, "&Reset camera", "Home", lambda: w.viewport.set_camera(w.document.camera()))
    )
    w.camera_menu = view.addMenu("&Cameras")
    fill_camera_menu(w)
    view.addAction(_action(w, "&Bookmark this view…", "Ctrl+D", lambda: w.bookmark_view()))
    view.addSeparator()
    group = QActionGroup(w)
    w.mode_actions = {}
    for mode, text, key in VIEW_MODES:
        act = QAction(text, w, shortcut=QKeySequence(key), checkable=True)
        act.setChecked(mode == w.viewport.mode)
        act.triggered.connect(lambda _=False, m=mode: w.viewport.set_mode(m))
        group.addAction(act)
        view.addAction(act)
        w.mode_actions[mode] = act


def _view_toggles(w, view) -> None:
    w.techniques_action = _action(
        w,
        "&Technique colours",
        "T",
        lambda on: w.viewport.set_view("techniques" if on else "shaded"),
        checkable=True,
    )
    w.techniques_action.setToolTip("geometry red, volume yellow, image-based blue")
    view.addAction(w.techniques_action)
    w.zones_action = _action(
        w, "LOD &zones on the terrain", "Z", w.lod_panel.zones_box.setChecked, checkable=True
    )
    w.lod_panel.zones_box.toggled.connect(w.zones_action.setChecked)
    view.addAction(w.zones_action)
    w.timings_action = _action(w, "T&imings overlay", "P", w.overlay.setVisible, checkable=True)
    view.addAction(w.timings_action)
    w.quality_action = _action(
        w, "&Quality against all-geometry", "Ctrl+6", w.viewport.set_quality, checkable=True
    )
    w.quality_action.setToolTip(
        "when the view rests, an all-geometry frame is drawn in the background and the "
        "difference shown as a heat map, with its figures in the status line"
    )
    view.addAction(w.quality_action)
    w.hold_action = _action(
        w, "&Hold frame rate…", "Ctrl+Shift+R", w.hold_frame_rate, checkable=True
    )
    w.hold_action.setToolTip(
        "adaptive LOD: one factor on every zone's distances keeps the full-quality frame time at "
        "a target; the status line shows the factor"
    )
    view.addAction(w.hold_action)
    w.wind_action = _action(w, "&Wind blows", "Ctrl+Shift+W", w.set_wind_blowing, checkable=True)
    w.wind_action.setToolTip("animate the grass in the project's wind (the Wind dock sets it)")
    w.wind_action.setChecked(w.document.wind.enabled)
    w.wind_panel.enabled_box.toggled.connect(w.wind_action.setChecked)
    view.addAction(w.wind_action)
    w.sharp_wind_action = _action(
        w, "S&harp wind frames", "Ctrl+Shift+H", w.viewport.set_sharp_wind, checkable=True
    )
    w.sharp_wind_action.setToolTip(
        "while the wind blows, draw each moment at full quality without drafts: fewer moments "
        "a second where full frames are slow"
    )
    view.addAction(w.sharp_wind_action)


def _view_docks(w, view) -> None:
    view.addSeparator()
    docks = (
        w.patch_dock,
        w.paint_dock,
        w.lod_dock,
        w.light_dock,
        w.wind_dock,
        w.map_dock,
        w.history_dock,
    )
    for dock in (*docks, w.profile_dock):
        view.addAction(dock.toggleViewAction())
    view.addSeparator()
    w.reset_layout_action = _action(w, "Reset &layout", "", lambda: view_settings.reset_layout(w))
    w.reset_layout_action.setToolTip("the docks and the window as the designer first opens them")
    view.addAction(w.reset_layout_action)


def _paint_menu(w) -> None:
    paint = w.menuBar().addMenu("&Paint")
    w.paint_action = _action(w, "&Paint in the viewport", "B", w.set_painting, True)
    paint.addAction(w.paint_action)
    paint.addSeparator()
    panel = w.paint_panel
    paint.addActions(
        [
            _action(w, "&Bigger brush", "]", lambda: panel.scale_size(1.25)),
            _action(w, "&Smaller brush", "[", lambda: panel.scale_size(0.8)),
            _action(w, "S&tronger", "=", lambda: panel.add_strength(0.1)),
            _action(w, "&Weaker", "-", lambda: panel.add_strength(-0.1)),
            _action(w, "&Eyedropper", "I", w.painter.start_eyedropper),
            _action(w, "&Leave painting", "Escape", w.leave_painting),
        ]
    )


def fill_camera_menu(w) -> None:
    """The project's named cameras (bookmarks among them)."""
    w.camera_menu.clear()
    for name in w.document.cameras:
        act = w.camera_menu.addAction(name)
        act.triggered.connect(lambda _=False, n=name: w.viewport.set_camera(w.document.camera(n)))
