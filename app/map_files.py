"""Importing and exporting the design map chosen in the paint panel. A file that cannot be read
changes nothing; an import is one undo step (`on_import` makes it one).

Qt-free: the person is asked through `Dialogs` (app/dialogs.py), the chosen map comes from the
paint panel's `target` and `target_label`."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from app.dialogs import Dialogs
from core.brush import ALL_TYPES
from core.document import Document
from core.map_io import (
    RAW_SUFFIXES,
    MapFileError,
    fit_channels,
    read_image_at,
    read_raw16,
    resample,
    write_map,
)
from core.species import Species

IMAGE_FILTER = "Images (*.png *.tif *.tiff *.jpg *.jpeg *.bmp)"
IMPORT_FILTER = f"{IMAGE_FILTER};;Raw 16-bit heights (*.r16 *.raw)"
# (layer, channel or None, (rows, columns, channels) values, text for the undo history)
Import = Callable[[str, int | None, np.ndarray, str], None]


class MapFileActions:
    def __init__(
        self,
        document: Callable[[], Document],
        panel,
        on_import: Import,
        dialogs: Dialogs,
        on_species: Callable[[Species, np.ndarray, str], None],
    ) -> None:
        self.document = document
        self.panel = panel  # target (layer, channel), target_label
        self.on_import = on_import
        self.on_species = on_species  # species rules and the density they place, one step
        self.dialogs = dialogs

    def import_map(self, path: Path | str | None = None, raw: dict | None = None) -> bool:
        """Read a file into the chosen map; `raw` (width, height, big_endian, low, high) skips
        the raw dialog. Returns whether the map changed."""
        if path is None:
            path = self.dialogs.open_path("Import map", IMPORT_FILTER)
            if not path:
                return False
        path = Path(path)
        layer, channel = self.panel.target
        try:
            if path.suffix.lower() in RAW_SUFFIXES:
                if raw is None:
                    size = path.stat().st_size if path.exists() else 0
                    raw = self.dialogs.raw_height_options(path.name, size)
                    if raw is None:
                        return False
                values, own = read_raw16(path, **raw), None
            else:
                # resampled before its channels are fitted: an 8192² grey image is not
                # widened to float RGBA at full size first
                values, own = read_image_at(path, self.document().maps.size)
        except MapFileError as exc:
            self.dialogs.warn(str(exc))
            return False
        size = self.document().maps.size
        if own is None and (values.shape[1], values.shape[0]) != size:
            own = (values.shape[1], values.shape[0])
            values = resample(values, size)
        values = fit_channels(values, layer, channel is not None)
        if own is not None and own != size:
            self.dialogs.status(
                f"{path.name} is {own[0]} × {own[1]}: resampled to the project's maps, "
                f"{size[0]} × {size[1]}",
                8000,
            )
        if channel == ALL_TYPES:  # one density for every grass type
            channel = None
            values = np.repeat(values, 4, axis=2)
        self.on_import(layer, channel, values, f"import {path.name} into {self.panel.target_label}")
        return True

    def export_map(self, path: Path | str | None = None) -> bool:
        layer, channel = self.panel.target
        label = self.panel.target_label
        if path is None:
            path = self.dialogs.save_path(
                "Export map", label.split(" ")[0] + ".png", "PNG (*.png);;Raw 16-bit (*.r16)"
            )
            if not path:
                return False
        values = self.document().maps.layer(layer)
        if channel is not None:
            values = values[..., [max(channel, 0)]]
        try:
            write_map(path, np.asarray(values))
        except MapFileError as exc:
            self.dialogs.warn(str(exc))
            return False
        self.dialogs.status(f"exported {label} to {path}", 5000)
        return True

    def species_from_image(self, path: Path | str | None = None, species=None) -> bool:
        """Paint → Grass types from colours…: the person sets each kind's rule (reference
        colour, weights, exponent; skipped when `species` is given), then picks a terrain
        colour image; each grass type's density follows from it (core/species.py). The rules
        and the density are one undo step. Returns whether the maps changed."""
        from core.species import density_layer, derived_references

        document = self.document()
        if species is None:
            grass, soil = derived_references(document)
            species = self.dialogs.species_rules(
                [*document.grass_names, "bare soil"], [*grass, soil], document.species
            )
            if species is None:
                return False
        if path is None:
            path = self.dialogs.open_path("Grass types from a colour image", IMAGE_FILTER)
            if not path:
                return False
        path = Path(path)
        try:
            values, _own = read_image_at(path, document.maps.size)
        except MapFileError as exc:
            self.dialogs.warn(str(exc))
            return False
        rgb = fit_channels(values, "ambient", False)  # as RGB, as a light map takes an image
        density = density_layer(document, rgb, species)
        self.on_species(species, density, f"grass types from {path.name}")
        return True
