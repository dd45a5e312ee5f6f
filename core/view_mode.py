"""How the renderer draws the cells: by LOD zones, every cell with one representation (the
thesis's Table 7.1 comparisons, `sward render --only`), or the three side by side."""

from __future__ import annotations

from enum import StrEnum


class ViewMode(StrEnum):
    LOD = "lod"  # each cell by its distance: geometry near, volume mid-range, image-based far
    GEOMETRY = "geometry"
    VOLUME = "volume"
    IMAGE = "image"
    COMPARE = "compare"  # three columns, one representation each (the thesis's viewer tool)

    @classmethod
    def parse(cls, text: str) -> ViewMode:
        try:
            return cls(text)
        except ValueError:
            raise ValueError(
                f"unknown view mode {text!r}; use {', '.join(m.value for m in cls)}"
            ) from None
