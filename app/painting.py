"""The paint controller: turns presses and drags on the ground (viewport) or on the 2D map view
into brush strokes on the document's design maps, one undo step per stroke; the eyedropper; and
a note when the height map changed, so the terrain's bounding volumes can follow it.

Qt-free: it talks to the paint panel through the narrow `BrushPanel` interface and hands each
finished stroke to `on_stroke` (the window makes it an undo step)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

import numpy as np

from core.brush import Brush, Stroke
from core.document import Document
from core.paint_rule import rule_mask


class BrushPanel(Protocol):
    """What the controller needs of the paint panel."""

    @property
    def target(self) -> tuple[str, int | None]: ...  # map layer, density channel

    @property
    def target_label(self) -> str: ...

    def brush(self, mode: str | None = None) -> Brush: ...

    @property
    def follows(self) -> bool: ...  # strokes turn the brush's lean the way they go

    def show_message(self, text: str) -> None: ...

    def set_value(self, values) -> None: ...


class PaintController:
    def __init__(
        self,
        document: Document,
        panel: BrushPanel,
        on_stroke: Callable[[Stroke, str], None],
        on_heights: Callable[[], None],
    ) -> None:
        """`on_stroke(stroke, label)`: a stroke finished; `on_heights()`: the height map
        changed (after a stroke, an undo, an import)."""
        self.panel = panel
        self.on_stroke = on_stroke
        self.on_heights = on_heights
        self.stroke: Stroke | None = None
        self.eyedropper = False
        self.document = document
        self._mask: tuple[tuple, np.ndarray] | None = None  # ((rule, terrain), its mask)
        document.maps.changed.connect(self._on_map_changed)

    def set_document(self, document: Document) -> None:
        self.document.maps.changed.disconnect(self._on_map_changed)
        self.document = document
        self.stroke = None
        self._mask = None
        document.maps.changed.connect(self._on_map_changed)

    # -- strokes -----------------------------------------------------------------------------
    def press(self, x: float, y: float, erase: bool = False, smooth: bool = False) -> None:
        """Start a stroke at map texel (x, y); `erase` (Ctrl) or `smooth` (Shift) override
        the brush's mode."""
        if self.eyedropper:
            self.pick(x, y)
            return
        mode = "erase" if erase else "smooth" if smooth else None
        layer, channel = self.panel.target
        try:
            brush = self.panel.brush(mode)
            self.stroke = Stroke(
                self.document.maps, layer, brush, channel, self.rule_mask(),
                follow=self.panel.follows, texel=self._texel(),
            )  # fmt: skip
        except ValueError as exc:
            self.panel.show_message(str(exc))
            return
        self.panel.show_message("")
        self.stroke.add(x, y)

    def fill_by_rule(self) -> bool:
        """Paint → Fill by rule: the chosen map takes the brush's value wherever the rule holds
        (its soft edge part of the way), one undo step. Returns whether it painted."""
        if not self.document.paint_rule.active:
            self.panel.show_message("set a slope or height rule first")
            return False
        layer, channel = self.panel.target
        try:
            brush = self.panel.brush("fill")
            stroke = Stroke(self.document.maps, layer, brush, channel, self.rule_mask())
        except ValueError as exc:
            self.panel.show_message(str(exc))
            return False
        stroke.finish()
        self.on_stroke(stroke, f"fill {self.panel.target_label} by rule")
        if layer == "height":
            self.on_heights()
        return True

    def rule_mask(self) -> np.ndarray | None:
        """The document's paint rule over the maps (core/paint_rule.py), None where it has
        none; kept until the rule or the height map changes."""
        rule = self.document.paint_rule
        if not rule.active:
            return None
        t = self.document.terrain_spec
        if self._mask is None or self._mask[0] != (rule, t):
            heights = self.document.maps.layer("height")[..., 0]
            mask = rule_mask(rule, heights, t.height_scale, (t.columns, t.rows))
            self._mask = ((rule, t), mask)
        return self._mask[1]

    def _texel(self) -> tuple[float, float]:
        """A map texel's size on the ground (x, z), in cells."""
        t, (w, h) = self.document.terrain_spec, self.document.maps.size
        return (t.columns / w, t.rows / h)

    def move(self, x: float, y: float) -> None:
        if self.stroke is not None:
            self.stroke.add(x, y)

    def release(self) -> None:
        stroke, self.stroke = self.stroke, None
        if stroke is None or not stroke.saved:
            return
        stroke.finish()
        self.on_stroke(stroke, f"{stroke.brush.mode} {self.panel.target_label}")
        if stroke.layer == "height":
            self.on_heights()

    # -- eyedropper --------------------------------------------------------------------------
    def start_eyedropper(self) -> None:
        self.eyedropper = True
        self.panel.show_message("click the map to take its value")

    def cancel_eyedropper(self) -> None:
        self.eyedropper = False
        self.panel.show_message("")

    def pick(self, x: float, y: float) -> None:
        self.eyedropper = False
        self.panel.show_message("")
        layer, channel = self.panel.target
        maps = self.document.maps
        w, h = maps.size
        col, row = int(np.clip(x, 0, w - 1)), int(np.clip(y, 0, h - 1))
        values = maps.layer(layer)[row, col]
        if channel is not None:
            values = values[[max(channel, 0)]]  # all grass types: show the first one's
        self.panel.set_value(tuple(float(v) for v in values))

    def _on_map_changed(self, name: str, _rect) -> None:
        if name == "height":
            self._mask = None  # the slopes and heights the rule weighs changed
        if name == "height" and self.stroke is None:  # undo, redo, import; strokes: release
            self.on_heights()
