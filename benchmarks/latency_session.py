"""One latency session (benchmarks/latency.py starts it under a display): the designer on the
default scene, continuous redraw on, driven with xdotool from a second thread while the window's
thread records when each input event is handled, each edit reaches the undo stack and each frame
is shown. Every kind of input is sent REPS times, each edit followed by its undo and redo; the
driver waits for the full frame that shows an input before it sends the next. Then the wind
blows for a while and the frames shown are counted. Writes the raw records to
$SWARD_LATENCY_OUT."""

from __future__ import annotations

from app.cli import start_render_processes

# as `sward` does, the render processes start before the window's modules load
if __name__ == "__main__":
    start_render_processes()

import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from PySide6.QtCore import QEvent, QObject, QSettings, Qt, QTimer
from PySide6.QtWidgets import QApplication, QMessageBox

from benchmarks.latency_places import places

INPUT_EVENTS = {
    # a key that is a shortcut reaches the window as ShortcutOverride, not as KeyPress
    QEvent.Type.ShortcutOverride: "key",
    QEvent.Type.KeyPress: "key",
    QEvent.Type.KeyRelease: "key-release",
    QEvent.Type.MouseButtonPress: "press",
    QEvent.Type.MouseButtonRelease: "release",
    QEvent.Type.MouseMove: "move",
}
REPS = 5  # each input this many times
WAIT_S = 15.0  # at most this long for the full frame that shows an input
EFFECT_S = 3.0  # an input that changed nothing by then is recorded as missed
SETTLE_S = 0.5  # after it, before the next input
WIND_S = 6.0  # frames counted while the wind blows
FIRST_FRAME_S = 600.0


def now_ms() -> float:
    return time.monotonic() * 1000.0


class Probe(QObject):
    """Event filter, undo-stack log and frame log on the window's thread."""

    def __init__(self, app: QApplication, window) -> None:
        super().__init__()
        self.events: list[dict] = []
        self.frames: list[dict] = []
        self.edits: list[float] = []  # when the undo stack moved (an edit, an undo, a redo)
        self.timer_late: list[float] = []
        self._seen: set = set()
        app.installEventFilter(self)
        window.viewport.frame_rendered.connect(self._on_frame)
        window.undo_stack.indexChanged.connect(lambda _index: self.edits.append(now_ms()))
        self._tick = QTimer(self, interval=10, timerType=Qt.TimerType.PreciseTimer)
        self._tick.timeout.connect(self._on_tick)
        self._last_tick: float | None = None
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
                "draft": bool(stats.draft),
                **{f"t_{part}_ms": getattr(stats, f"t_{part}_ms") for part in "aqugvimo"},
            }
        )


def xdo(*args) -> None:
    subprocess.run(["xdotool", *map(str, args)], check=True)


def effect_time(entry: dict, probe: Probe) -> float | None:
    """When the input took effect on the window's thread: an edit when the undo stack moved,
    a view change when its first event of the kind was handled."""
    sent = entry["sent_ms"]
    if entry["effect"] == "edit":
        later = [t for t in probe.edits if t >= sent]
    else:
        later = [
            e["at_ms"] for e in probe.events if e["kind"] == entry["effect"] and e["at_ms"] >= sent
        ]
    return min(later) if later else None


def measure(entry: dict, probe: Probe) -> bool:
    """The input's first and full frame (ms after it was sent), once its full frame is shown."""
    effect = effect_time(entry, probe)
    if effect is None:
        return False
    showing = [f for f in list(probe.frames) if f["state_ms"] >= effect]
    full = [f["shown_ms"] for f in showing if not f["draft"]]
    if not full:
        return False
    entry["effect_ms"] = effect - entry["sent_ms"]
    entry["first_frame_ms"] = min(f["shown_ms"] for f in showing) - entry["sent_ms"]
    entry["full_frame_ms"] = min(full) - entry["sent_ms"]
    return True


class Driver(threading.Thread):
    """The inputs, sent through the X server; each records when its decisive event was sent
    and waits for the full frame that shows it."""

    def __init__(self, places: dict, probe: Probe) -> None:
        super().__init__(daemon=True)
        self.places = places
        self.probe = probe
        self.inputs: list[dict] = []
        self.wind: dict = {}
        self.done = False
        self.error = ""

    def run(self) -> None:
        try:
            self._script()
        except Exception as exc:  # reported in the JSON, the session still ends
            self.error = repr(exc)
        self.done = True

    # -- primitives --------------------------------------------------------------------------
    @staticmethod
    def reps(name: str) -> int:
        """How many times to send an input: REPS, or none when SWARD_LATENCY_ONLY names others
        (comma-separated input names, "wind" for the frames under the wind)."""
        only = os.environ.get("SWARD_LATENCY_ONLY")
        return REPS if not only or name in {n.strip() for n in only.split(",")} else 0

    def send(self, name: str, effect: str, *keys: str) -> None:
        """The decisive input: keys (xdotool key names), its time recorded just before; then
        wait for its full frame."""
        entry = {"name": name, "effect": effect, "sent_ms": now_ms()}
        self.inputs.append(entry)
        if keys:
            xdo("key", *keys)
        self.wait(entry)

    def wait(self, entry: dict) -> None:
        start = time.monotonic()
        while not measure(entry, self.probe):
            waited = time.monotonic() - start
            if waited > WAIT_S or (waited > EFFECT_S and effect_time(entry, self.probe) is None):
                entry["missed"] = True  # no effect, or no full frame showing it
                break
            time.sleep(0.02)
        entry["until_ms"] = now_ms()
        time.sleep(SETTLE_S)

    def click(self, place: str) -> None:
        xdo("mousemove", *self.places[place], "click", "1")
        time.sleep(0.3)

    def away(self) -> None:
        """Keyboard focus to the viewport (a click that does not drag), so that the undo and
        redo shortcuts reach the window rather than a field's own undo."""
        self.click("viewport_centre")

    def undo_redo(self, name: str) -> None:
        self.away()
        self.send(f"{name}: undo", "edit", "ctrl+z")
        self.send(f"{name}: redo", "edit", "ctrl+shift+z")

    def pick(self, place: str, name: str, first_letters: tuple[str, str], rep: int) -> None:
        """An entry of a drop-down list by the first letter of its text (a person's quickest
        way): the first of the two on even repetitions, the second on odd ones."""
        self.click(place)
        self.send(name, "edit", first_letters[rep % 2], "Return")

    # -- the script ----------------------------------------------------------------------------
    def _script(self) -> None:
        cx, cy = self.places["viewport_centre"]
        self.away()
        xdo("mousemove", cx, cy)
        time.sleep(1.0)
        for _rep in range(self.reps("technique colours")):
            self.send("technique colours", "key", "t")
        if self.reps("technique colours") % 2:
            xdo("key", "t")  # back to the shaded view
            time.sleep(2.0)
        for rep in range(self.reps("camera drag")):
            xdo("mousemove", cx, cy)
            entry = {"name": "camera drag", "effect": "move", "sent_ms": now_ms()}
            self.inputs.append(entry)
            xdo("mousedown", "1")
            sign = 1 if rep % 2 == 0 else -1
            for step in range(1, 9):
                xdo("mousemove", cx + sign * 12 * step, cy + 2 * step)
                time.sleep(0.03)
            xdo("mouseup", "1")
            self.wait(entry)
        for rep in range(self.reps("blade count typed")):
            self.click("patch_tab")
            self.click("blade_count")
            xdo("key", "ctrl+a")
            xdo("type", str(1500 - 100 * rep))  # a new patch each time
            self.send("blade count typed", "edit", "Return")
            self.undo_redo("blade count typed")
        for rep in range(self.reps("preset change")):
            self.click("patch_tab")
            self.pick("preset", "preset change", ("s", "u"), rep)
            self.undo_redo("preset change")
        for rep in range(self.reps("slice count")):
            self.click("patch_tab")
            xdo("mousemove", *self.places["patch_tree"])
            xdo("click", "--repeat", "30", "5")  # the wheel, down to the slice count
            self.pick("slices", "slice count", ("4", "8"), rep)
            self.undo_redo("slice count")
        self.click("patch_tab")
        xdo("mousemove", *self.places["patch_tree"])
        xdo("click", "--repeat", "30", "4")  # back up
        for rep in range(self.reps("sun elevation")):
            self.click("light_tab")
            self.click("sun_elevation")
            self.send("sun elevation", "edit", "Prior" if rep % 2 == 0 else "Next")
            self.undo_redo("sun elevation")
        for rep in range(self.reps("LOD zone distance")):
            self.click("lod_tab")
            self.click("lod_end")
            self.send("LOD zone distance", "edit", "Up" if rep % 2 == 0 else "Down")
            self.undo_redo("LOD zone distance")
        for rep in range(self.reps("wind preset")):
            self.click("wind_tab")
            self.pick("wind_preset", "wind preset", ("l", "s"), rep)
            self.undo_redo("wind preset")
        self.away()
        xdo("mousemove", cx, cy + 120)
        xdo("key", "b")  # paint in the viewport
        time.sleep(1.0)
        for rep in range(self.reps("paint stroke")):
            entry = {"name": "paint stroke", "effect": "press", "sent_ms": now_ms()}
            self.inputs.append(entry)
            xdo("mousedown", "1")
            for step in range(1, 9):
                xdo("mousemove", cx - 100 + 25 * step, cy + 100 + 10 * rep)
                time.sleep(0.03)
            xdo("mouseup", "1")
            self.wait(entry)
            self.send("paint stroke: undo", "edit", "ctrl+z")
            self.send("paint stroke: redo", "edit", "ctrl+shift+z")
        xdo("key", "Escape")  # leave painting
        if self.reps("wind"):
            self._wind()

    def _wind(self) -> None:
        """Frames shown per second while the wind blows (drafts count)."""
        self.away()
        xdo("key", "ctrl+shift+w")
        time.sleep(1.5)
        start = now_ms()
        time.sleep(WIND_S)
        end = now_ms()
        shown = [f for f in list(self.probe.frames) if start <= f["shown_ms"] < end]
        self.wind = {
            "frames": len(shown),
            "seconds": (end - start) / 1000.0,
            "fps": len(shown) / ((end - start) / 1000.0),
            "full": sum(not f["draft"] for f in shown),
        }
        xdo("key", "ctrl+shift+w")
        time.sleep(1.0)


def main() -> int:
    out = Path(os.environ["SWARD_LATENCY_OUT"])
    launched = float(os.environ.get("SWARD_LATENCY_LAUNCHED_MS", now_ms()))
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
    while not any(not f["draft"] for f in probe.frames):
        app.processEvents()
        time.sleep(0.005)
        if time.monotonic() - start > FIRST_FRAME_S:
            raise SystemExit("latency session: no full frame within the time limit")
    startup_ms = next(f["shown_ms"] for f in probe.frames if not f["draft"]) - launched
    window.activateWindow()  # keys go to the window with the input focus
    focused = time.monotonic()
    while not window.isActiveWindow() and time.monotonic() - focused < 10.0:
        app.processEvents()
        time.sleep(0.01)
    window.profile_panel.continuous_box.setChecked(True)
    driver = Driver(places(app, window), probe)
    probe.start()
    driver.start()
    check = QTimer(interval=100)
    check.timeout.connect(lambda: driver.done and app.quit())
    check.start()
    app.exec()
    probe.recording = False
    vp = window.viewport
    result = {
        "viewport": [vp.width(), vp.height()],
        "startup_ms": startup_ms,
        "inputs": driver.inputs,
        "wind": driver.wind,
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
