"""The designer's File → Export…: writes `sward export` of the open design (its state now,
saved to a temporary project) in another process, so the window stays live while a large
terrain is written; the dialog (widgets/export_dialog.py) shows the progress, Cancel stops it,
and the status line says what was written where."""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

from PySide6.QtCore import QObject, QProcess

from widgets.export_dialog import PARTS, ExportDialog

PROGRESS = re.compile(r"blocks (\d+)/(\d+)")
FOLDER_KEY = "export/folder"


class ExportJob(QObject):
    def __init__(self, window) -> None:
        super().__init__(window)
        self.window = window
        # the folder of the last export, else one beside where files were last opened or saved
        last = window.settings.value(FOLDER_KEY, "", type=str)
        folder = last or str(Path(window.dialogs.folder) / "sward-export")
        self.dialog = ExportDialog(folder, window)
        self.process: QProcess | None = None
        self.temp: tempfile.TemporaryDirectory | None = None  # the project copy, while running
        self.dialog.export_requested.connect(self.start)
        self.dialog.cancel_requested.connect(self.cancel)
        self.dialog.finished.connect(self._closed)

    def start(self) -> None:
        from core.project_file import save_project

        folder, fmt, parts = self.dialog.chosen()
        if not folder:
            self.dialog.message.setText("Choose a folder to export into.")
            return
        if not parts:
            self.dialog.message.setText(f"Tick at least one of: {', '.join(PARTS)}.")
            return
        self.temp = tempfile.TemporaryDirectory(prefix="sward-export-")
        project = Path(self.temp.name) / "export.sward"
        save_project(project, self.window.document)
        self.window.settings.setValue(FOLDER_KEY, folder)
        args = ["-m", "app.cli", "export", "--project", str(project), "--out", folder]
        args += ["--format", fmt, "--what", ",".join(parts)]
        self.output = ""
        self.process = QProcess(self)
        self.process.setProcessChannelMode(QProcess.ProcessChannelMode.MergedChannels)
        self.process.readyReadStandardOutput.connect(self._read)
        self.process.finished.connect(self._finished)
        self.process.setWorkingDirectory(str(Path(__file__).resolve().parent.parent))
        self.process.start(sys.executable, args)
        self.dialog.running(True)
        self.dialog.progress.setValue(0)
        self.dialog.message.setText(f"exporting into {folder} …")

    def cancel(self) -> None:
        if self.process is not None and self.process.state() != QProcess.ProcessState.NotRunning:
            self.process.kill()
            self.process.waitForFinished(5000)
            self.dialog.message.setText("cancelled: the folder holds part of an export")

    def _closed(self, _code: int) -> None:
        self.cancel()

    def _clean(self) -> None:
        if self.temp is not None:
            self.temp.cleanup()
            self.temp = None

    def _read(self) -> None:
        text = bytes(self.process.readAllStandardOutput()).decode(errors="replace")
        self.output += text
        for line in text.splitlines():
            found = PROGRESS.search(line)
            if found:
                self.dialog.progress.setValue(round(100 * int(found[1]) / int(found[2])))
            elif line.strip():
                self.dialog.message.setText(line.strip())

    def _finished(self, code: int, status) -> None:
        self._clean()
        self.dialog.running(False)
        if status != QProcess.ExitStatus.NormalExit:
            return  # cancelled: cancel() said so
        lines = [line for line in self.output.splitlines() if line.strip()]
        if code != 0:
            error = lines[-1] if lines else f"exit status {code}"
            self.dialog.message.setText(error.replace("sward export: error: ", ""))
            return
        self.dialog.progress.setValue(100)
        folder = self.dialog.chosen()[0]
        self.dialog.message.setText("\n".join(lines[-4:]))
        self.window.dialogs.status(f"exported the design into {folder}")


def open_export(window) -> ExportJob:
    """File → Export…: the dialog, kept on the window while it is open."""
    window.export_job = ExportJob(window)
    window.export_job.dialog.show()
    return window.export_job
