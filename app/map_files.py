"""Importing and exporting the design map chosen in the paint panel (File dialogs, the raw
dialog, messages). A file that cannot be read changes nothing; an import is one undo step."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PySide6.QtCore import QObject
from PySide6.QtWidgets import QDialog, QFileDialog, QMessageBox

from app.commands import SetMap
from core.brush import ALL_TYPES
from core.map_io import (
    RAW_SUFFIXES,
    MapFileError,
    fit_channels,
    read_image,
    read_raw16,
    resample,
    write_map,
)
from widgets.raw_dialog import RawHeightDialog

IMPORT_FILTER = "Images (*.png *.tif *.tiff *.jpg *.jpeg *.bmp);;Raw 16-bit heights (*.r16 *.raw)"


class MapFileActions(QObject):
    def __init__(self, window) -> None:
        super().__init__(window)
        self.window = window

    def _target(self) -> tuple[str, int | None, str]:
        layer, channel = self.window.paint_panel.target
        return layer, channel, self.window.paint_panel.layer_box.currentText()

    def import_map(self, path: Path | str | None = None, raw: dict | None = None) -> bool:
        """Read a file into the chosen map; `raw` (width, height, big_endian, low, high) skips
        the raw dialog. Returns whether the map changed."""
        w = self.window
        if path is None:
            path, _ = QFileDialog.getOpenFileName(w, "Import map", "", IMPORT_FILTER)
            if not path:
                return False
        path = Path(path)
        layer, channel, label = self._target()
        try:
            if path.suffix.lower() in RAW_SUFFIXES:
                if raw is None:
                    size = path.stat().st_size if path.exists() else 0
                    dialog = RawHeightDialog(path.name, size, w)
                    if dialog.exec() != QDialog.DialogCode.Accepted:
                        return False
                    raw = dialog.values()
                values = read_raw16(path, **raw)
            else:
                values = read_image(path)
        except MapFileError as exc:
            QMessageBox.warning(w, "Sward", str(exc))
            return False
        single = channel is not None
        values = fit_channels(values, layer, single)
        size = w.maps.size
        if (values.shape[1], values.shape[0]) != size:
            w.statusBar().showMessage(
                f"{path.name} is {values.shape[1]} × {values.shape[0]}: resampled to the "
                f"project's maps, {size[0]} × {size[1]}",
                8000,
            )
            values = resample(values, size)
        if channel == ALL_TYPES:  # one density for every grass type
            channel = None
            values = np.repeat(values, 4, axis=2)
        w.push(SetMap(w.maps, layer, channel, values, f"import {path.name} into {label}"))
        return True

    def export_map(self, path: Path | str | None = None) -> bool:
        w = self.window
        layer, channel, label = self._target()
        if path is None:
            name = label.split(" ")[0] + ".png"
            path, _ = QFileDialog.getSaveFileName(
                w, "Export map", name, "PNG (*.png);;Raw 16-bit (*.r16)"
            )
            if not path:
                return False
        values = w.maps.layer(layer)
        if channel is not None:
            values = values[..., [max(channel, 0)]]
        try:
            write_map(path, np.asarray(values))
        except MapFileError as exc:
            QMessageBox.warning(w, "Sward", str(exc))
            return False
        w.statusBar().showMessage(f"exported {label} to {path}", 5000)
        return True
