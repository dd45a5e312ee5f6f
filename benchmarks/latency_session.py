"""One latency session (benchmarks/latency.py starts it under a display): the designer on the
default scene, continuous redraw on, driven with xdotool from a second thread while the window's
thread records when each input event is handled and each frame is shown. Writes the raw
records to $SWARD_LATENCY_OUT."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from PySide6.QtCore import QEvent, QObject, QPoint, QSettings, Qt, QTimer
from PySide6.QtWidgets import QApplication, QMessageBox

INPUT_EVENTS = {
    # a key that is a shortcut reaches the window as ShortcutOverride, not as KeyPress
    QEvent.Type.ShortcutOverride: "key",
    QEvent.Type.KeyPress: "key",
    QEvent.Type.KeyRelease: "key-release",
    QEvent.Type.MouseButtonPress: "press",
    QEvent.Type.MouseButtonRelease: "release",
    QEvent.Type.MouseMove: "move",
}
GAP_S = 4.0  # between inputs
FIRST_FRAME_S = 600.0


def now_ms() -> float:
    return time.monotonic() * 1000.0


class Probe(QObject):
    """Event filter and frame log on the window's thread."""

    def __init__(self, app: QApplication, window) -> None:
        super().__init__()
        self.events: list[dict] = []
        self.frames: list[dict] = []
        self.timer_late: list[float] = []
        self._seen: set = set()
        app.installEventFilter(self)
        window.viewport.frame_rendered.connect(self._on_frame)
        self._tick = QTimer(self, interval=10, timerType=Qt.TimerType.PreciseTimer)
        self._tick.timeout.connect(self._on_tick)
        self._last_tick = None
        self.recording = False

    def start(self) -> None:
        self.recording = True
        self._last_tick = now_ms()
        self._tick.start()

    def eventFilter(self, obj, event) -> bool:
        kind = INPUT_EVENTS.get(event.type())
        if kind is not None and self.recording and event.timestamp():
            key = (kind, event.timestamp())
            if key not in self._seen:  # an event is filtered again for each parent it reaches
                self._seen.add(key)
                handled = now_ms()
                self.events.append(
                    {"kind": kind, "at_ms": handled, "latency_ms": handled - event.timestamp()}
                )
        return False

    def _on_tick(self) -> None:
        t = now_ms()
        if self._last_tick is not None:
            self.timer_late.append(max(0.0, t - self._last_tick - 10.0))
        self._last_tick = t

    def _on_frame(self, stats) -> None:
        self.frames.append(
            {
                "shown_ms": now_ms(),
                "state_ms": stats.state_time * 1000.0,
                "preview": bool(stats.preview),
                "t_a_ms": stats.t_a_ms,
                "blades": stats.blades,
            }
        )


def xdo(*args: str) -> None:
    subprocess.run(["xdotool", *args], check=True)


class Driver(threading.Thread):
    """The inputs, sent through the X server; each records when it was sent."""

    def __init__(self, places: dict) -> None:
        super().__init__(daemon=True)
        self.places = places
        self.inputs: list[dict] = []
        self.done = False
        self.error = ""

    def mark(self, name: str, effect: str, **extra) -> None:
        self.inputs.append({"name": name, "sent_ms": now_ms(), "effect": effect, **extra})

    def run(self) -> None:
        try:
            self._script()
        except Exception as exc:  # reported in the JSON, the session still ends
            self.error = repr(exc)
        self.done = True

    def _script(self) -> None:
        p = self.places
        cx, cy = p["viewport_centre"]
        # a click on the status line gives the window the keyboard (no window manager here)
        xdo("mousemove", *map(str, p["status_line"]), "click", "1")
        xdo("mousemove", str(cx), str(cy))
        time.sleep(1.0)
        for name in ("technique colours on", "technique colours off"):
            self.mark(name, "key")
            xdo("key", "t")
            time.sleep(GAP_S)
        self.mark("menu opened and closed", "none")
        xdo("mousemove", *map(str, p["file_menu"]), "click", "1")
        time.sleep(1.0)
        xdo("key", "Escape")
        time.sleep(GAP_S)
        xdo("mousemove", str(cx), str(cy))
        self.mark("camera drag", "move")
        xdo("mousedown", "1")
        for step in range(1, 9):
            xdo("mousemove", str(cx + 12 * step), str(cy + 2 * step))
            time.sleep(0.03)
        xdo("mouseup", "1")
        time.sleep(GAP_S)
        bx, by = p["blade_count"]
        xdo("mousemove", str(bx), str(by), "click", "1")
        time.sleep(1.0)
        xdo("key", "ctrl+a")
        xdo("type", "1500")
        self.mark("blade-parameter edit", "blades")
        xdo("key", "Return")
        time.sleep(GAP_S + 4.0)
        xdo("mousemove", str(cx), str(cy + 120))
        xdo("key", "b")
        time.sleep(1.0)
        self.mark("paint stroke", "press")
        xdo("mousedown", "1")
        for step in range(1, 9):
            xdo("mousemove", str(cx - 100 + 25 * step), str(cy + 120))
            time.sleep(0.03)
        xdo("mouseup", "1")
        time.sleep(GAP_S)
        self.mark("undo", "key")
        xdo("key", "ctrl+z")
        time.sleep(GAP_S)


def places(window) -> dict:
    """Screen positions of the controls the driver uses."""
    vp = window.viewport
    centre = vp.mapToGlobal(vp.rect().center())
    bar = window.menuBar()
    file_at = bar.mapToGlobal(bar.actionGeometry(bar.actions()[0]).center())
    tree = window.panel.tree
    item = next(iter(window.panel.param("blade_count").items))
    rect = tree.visualItemRect(item)
    value_x = tree.header().sectionPosition(1) + 30
    blade = tree.viewport().mapToGlobal(QPoint(value_x, rect.center().y()))
    status = window.statusBar()
    status_at = status.mapToGlobal(status.rect().center())
    return {
        "status_line": (status_at.x(), status_at.y()),
        "viewport_centre": (centre.x(), centre.y()),
        "file_menu": (file_at.x(), file_at.y()),
        "blade_count": (blade.x(), blade.y()),
    }


def effect_time(entry: dict, events: list[dict], frames: list[dict]) -> float | None:
    """When the input took effect on the window's thread (its first handled event)."""
    kinds = {"key": ("key",), "move": ("move",), "press": ("press",), "blades": ("key",)}
    wanted = kinds.get(entry["effect"])
    if wanted is None:
        return None
    later = [e["at_ms"] for e in events if e["kind"] in wanted and e["at_ms"] >= entry["sent_ms"]]
    return min(later) if later else None


def shows(entry: dict, frame: dict, effect: float, frames: list[dict]) -> bool:
    if frame["state_ms"] < effect:
        return False
    if entry["effect"] != "blades":
        return True
    before = [f["blades"] for f in frames if f["state_ms"] < entry["sent_ms"]]
    return bool(before) and frame["blades"] != before[-1]


def measure(inputs: list[dict], events: list[dict], frames: list[dict]) -> None:
    for entry in inputs:
        effect = effect_time(entry, events, frames)
        entry["effect_ms"] = effect
        if effect is None:
            continue
        showing = [f for f in frames if shows(entry, f, effect, frames)]
        first = min((f["shown_ms"] for f in showing), default=None)
        full = min((f["shown_ms"] for f in showing if not f["preview"]), default=None)
        entry["first_frame_ms"] = None if first is None else first - entry["sent_ms"]
        entry["full_frame_ms"] = None if full is None else full - entry["sent_ms"]


def main() -> int:
    out = Path(os.environ["SWARD_LATENCY_OUT"])
    settings = tempfile.mkdtemp(prefix="sward-latency-")
    QSettings.setPath(QSettings.Format.NativeFormat, QSettings.Scope.UserScope, settings)
    QMessageBox.question = lambda *a, **k: QMessageBox.StandardButton.Discard
    app = QApplication(sys.argv)
    from app.designer import DesignerWindow
    from app.scenes import DEFAULT_SCENE, get_scene

    document = get_scene(DEFAULT_SCENE).document()
    view_height = os.environ.get("SWARD_LATENCY_VIEW_HEIGHT")  # LOD distances for that view
    if view_height:
        from core.lod_edit import set_view_heights

        document.set_lods(set_view_heights(document.lods, float(view_height)))
    window = DesignerWindow(document)
    window.autosave.directory = Path(settings)
    window.show()
    probe = Probe(app, window)
    start = time.monotonic()
    while not any(not f["preview"] for f in probe.frames):
        app.processEvents()
        time.sleep(0.005)
        if time.monotonic() - start > FIRST_FRAME_S:
            raise SystemExit("latency session: no full frame within the time limit")
    window.activateWindow()  # keys go to the window with the input focus
    focused = time.monotonic()
    while not window.isActiveWindow() and time.monotonic() - focused < 10.0:
        app.processEvents()
        time.sleep(0.01)
    window.profile_panel.continuous_box.setChecked(True)
    driver = Driver(places(window))
    probe.start()
    driver.start()
    check = QTimer(interval=100)
    check.timeout.connect(lambda: driver.done and app.quit())
    check.start()
    app.exec()
    probe.recording = False
    measure(driver.inputs, probe.events, probe.frames)
    vp = window.viewport
    result = {
        "viewport": [vp.width(), vp.height()],
        "inputs": driver.inputs,
        "events": probe.events,
        "frames": probe.frames,
        "timer_late_ms": probe.timer_late,
        "error": driver.error,
    }
    out.write_text(json.dumps(result, indent=1))
    window.profile_panel.continuous_box.setChecked(False)
    window.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
