"""The designer's Tune… (LOD zones dock): runs `sward tune` on a copy of the open project in
another process (the window's process draws no GL), shows its progress and front in the
dialog (widgets/tune_dialog.py), shows a clicked setting in the viewport, and applies the one
the person picks as one undo step. Cancel stops the search with Ctrl+C's signal: it keeps what
it found, which the dialog then shows."""

from __future__ import annotations

import json
import os
import re
import signal
import sys
import tempfile
from pathlib import Path

from PySide6.QtCore import QObject, QProcess

from app import commands
from core.document import CameraSpec
from core.tuning import Knobs, tuned
from widgets.tune_dialog import CURRENT_VIEW, TuneDialog

PROGRESS = re.compile(r"^\[(\d+)/(\d+)\] .*: (\d+) ms, FLIP ([0-9.]+)")


class TuneJob(QObject):
    def __init__(self, window) -> None:
        super().__init__(window)
        self.window = window
        doc = window.document
        self.dialog = TuneDialog(list(doc.cameras), window)
        self.original = doc.lods  # the levels before any point was shown
        self.result: dict | None = None
        self.live: list[tuple[float, float]] = []
        self.process: QProcess | None = None
        self.folder = tempfile.TemporaryDirectory(prefix="sward-tune-")
        d = self.dialog
        d.start_requested.connect(self.start)
        d.cancel_requested.connect(self.cancel)
        d.apply_requested.connect(self.apply)
        d.point_clicked.connect(self.show_setting)
        d.finished.connect(self._closed)

    # -- the search ------------------------------------------------------------------------------
    def start(self) -> None:
        from core.project_file import save_project

        names = self.dialog.chosen_cameras()
        if not names:
            self.dialog.message.setText("Choose at least one camera to tune on.")
            return
        doc = self.window.document
        doc.set_lods(self.original)
        cameras = dict(doc.cameras)
        if CURRENT_VIEW in names:
            cam = self.window.viewport.camera
            cameras[CURRENT_VIEW] = CameraSpec(
                tuple(float(v) for v in cam.eye), tuple(cam.target), far=cam.far, near=cam.near
            )
        project = Path(self.folder.name) / "tuned.sward"
        save_project(project, doc)
        if CURRENT_VIEW in names:  # the view as a camera of the copy, not of the project
            from core.project_file import load_project

            copy = load_project(project)
            copy.cameras = cameras
            save_project(project, copy)
        kind, value = self.dialog.target()
        args = ["-m", "app.cli", "tune", "--project", str(project), "--out", self.folder.name]
        args += ["--candidates", str(self.dialog.candidates_box.value())]
        if value is not None:
            args += ["--budget-ms" if kind == "budget" else "--quality", f"{value:g}"]
        for name in names:
            args += ["--camera", name]
        self.live, self.result = [], None
        self.dialog.show_candidates([], [], {})
        self.process = QProcess(self)
        self.process.readyReadStandardError.connect(self._read_progress)
        self.process.finished.connect(self._finished)
        self.process.setWorkingDirectory(str(Path(__file__).resolve().parent.parent))
        self.process.start(sys.executable, args)
        self.dialog.running(True)
        self.dialog.show_progress(0, self.dialog.candidates_box.value(), "drawing the references …")

    def cancel(self) -> None:
        if self.process is not None and self.process.state() != QProcess.ProcessState.NotRunning:
            os.kill(self.process.processId(), signal.SIGINT)  # keeps what it found
            self.dialog.message.setText("stopping: keeping what was found …")

    def _read_progress(self) -> None:
        text = bytes(self.process.readAllStandardError()).decode(errors="replace")
        for line in text.splitlines():
            found = PROGRESS.match(line)
            if found:
                done, total = int(found[1]), int(found[2])
                self.live.append((float(found[3]), float(found[4])))
                self.dialog.show_progress(done, total, line)
                self.dialog.show_candidates(self.live, [], {0: "shipped"})
            elif line.strip():
                self.dialog.message.setText(line.strip())

    def _finished(self, code: int, _status) -> None:
        self.dialog.running(False)
        path = Path(self.folder.name) / "tune.json"
        if not path.is_file():
            err = bytes(self.process.readAllStandardError()).decode(errors="replace").strip()
            self.dialog.message.setText(f"the search stopped without a result ({code}): {err}")
            return
        self.result = json.loads(path.read_text())
        self._show(self.result["chosen"])
        chosen = self.result["chosen"]
        self.dialog.apply_button.setEnabled(chosen is not None)
        self.dialog.progress.setValue(self.dialog.progress.maximum())
        self.dialog.message.setText(_summary(self.result))

    # -- showing and applying a setting ------------------------------------------------------------
    def show_setting(self, index: int) -> None:
        """A click on a point: the viewport draws that setting (not an edit until Apply)."""
        if self.result is None or not 0 <= index < len(self.result["candidates"]):
            return
        self.result["chosen"] = index
        self.window.document.set_lods(self._levels(index))
        self._show(index)
        self.dialog.apply_button.setEnabled(True)

    def apply(self) -> None:
        if self.result is None or self.result["chosen"] is None:
            return
        levels = self._levels(self.result["chosen"])
        self.window.document.set_lods(self.original)
        self.window.push(commands.set_lods(self.window.document, levels, "tune LOD zones"))
        self.original = self.window.document.lods
        self.dialog.message.setText("applied: Edit → Undo takes it back")

    def _levels(self, index: int) -> list:
        knobs = Knobs(**self.result["candidates"][index]["knobs"])
        return [tuned(lod, knobs) for lod in self.original]

    def _show(self, chosen: int | None) -> None:
        r = self.result
        points = [(c["cost_ms"], c["flip_quarter"]) for c in r["candidates"]]
        marks = {0: "shipped"}
        if chosen is not None:
            marks[chosen] = "chosen"
        self.dialog.show_candidates(points, r["front"], marks)

    def _closed(self, _code: int) -> None:
        self.cancel()
        if self.window.document.lods != self.original:  # a point shown, not applied
            self.window.document.set_lods(self.original)
        self.folder.cleanup()


def _summary(result: dict) -> str:
    c = result["candidates"]
    shipped = c[0]
    text = f"{len(c)} settings tried; shipped {shipped['cost_ms']:.0f} ms, FLIP {shipped['flip_quarter']:.4f}"
    if result["chosen"] is not None:
        ch = c[result["chosen"]]
        text += f"; chosen {ch['cost_ms']:.0f} ms, FLIP {ch['flip_quarter']:.4f}"
    else:
        text += "; nothing tried meets the target"
    return text + ". Click a point to see it; Apply keeps it (one undo step)."
