"""What the designer remembers between sessions (QSettings, beside the recent files): the
window's size, place and dock layout, and the View menu's display preferences. Not the project
(that is the file and its autosave), not the wind's blowing (the project's), not the Quality
view (an all-geometry frame in the background, asked for each time) and not the view mode
(a designer that opened in all-geometry mode would start with slow frames nobody asked for)."""

from __future__ import annotations

from typing import Any

# settings key -> the designer window's checkable action
PREFERENCES = {
    "view/technique_colours": "techniques_action",
    "view/lod_zones": "zones_action",
    "view/timings_overlay": "timings_action",
    "view/sharp_wind_frames": "sharp_wind_action",
}
GEOMETRY, STATE = "window/geometry", "window/dock_state"


def restore(window: Any, settings: Any) -> None:
    """The window's layout and preferences as last saved (nothing saved: as built). A value
    that is not what was saved (a settings file edited by hand, another version's) is passed
    over: the window stays as built there."""
    from PySide6.QtCore import QByteArray

    window.built_layout = (window.saveState(), window.size())  # for View → Reset layout
    geometry, state = settings.value(GEOMETRY), settings.value(STATE)
    if isinstance(geometry, QByteArray | bytes):
        window.restoreGeometry(geometry)
    if isinstance(state, QByteArray | bytes):
        window.restoreState(state)  # False (and no change) where the bytes are not a state
    for key, name in PREFERENCES.items():
        on = _flag(settings.value(key))
        if on is not None:
            getattr(window, name).setChecked(on)


def reset_layout(window: Any) -> None:
    """View → Reset layout: the docks where the designer puts them, every one open again, and
    the window at its first size (the View preferences stay as they are)."""
    state, size = window.built_layout
    window.restoreState(state)
    window.resize(size)


def _flag(value: Any) -> bool | None:
    """A saved check mark: QSettings gives a bool back from some formats, 'true' / 'false'
    from an INI file; None for anything else."""
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.lower() in ("true", "false"):
        return value.lower() == "true"
    return None


def save(window: Any, settings: Any) -> None:
    settings.setValue(GEOMETRY, window.saveGeometry())
    settings.setValue(STATE, window.saveState())
    for key, name in PREFERENCES.items():
        settings.setValue(key, getattr(window, name).isChecked())
    settings.sync()
