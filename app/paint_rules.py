"""Painting by rule, wired: the paint dock's rule controls edit the document's paint rule (one
undo step per change), the Map dock shades where it does not hold, Fill by rule paints the
chosen map where it does (app/painting.py PaintController)."""

from __future__ import annotations

from collections.abc import Callable

from app import commands
from app.painting import PaintController
from core.document import Document


class PaintRules:
    def __init__(
        self,
        document: Document,
        panel,  # widgets/paint_panel.py PaintPanel: its rule_box (widgets/rule_box.py)
        map_view,  # widgets/map_view.py MapView
        painter: PaintController,
        push: Callable[[commands.Command], None],
    ) -> None:
        box = panel.rule_box
        self.box, self.map_view, self.painter, self.push = box, map_view, painter, push
        self.document = document
        box.rule_edited.connect(self._edited)
        box.fill_requested.connect(painter.fill_by_rule)
        self._connect(document)

    def set_document(self, document: Document) -> None:
        self.document.events.paint_rule.disconnect(self._show)
        self.document.events.terrain_spec.disconnect(self._show)
        self.document.maps.changed.disconnect(self._on_map_changed)
        self._connect(document)

    def _connect(self, document: Document) -> None:
        self.document = document
        document.events.paint_rule.connect(self._show)
        document.events.terrain_spec.connect(self._show)  # the height scale
        document.maps.changed.connect(self._on_map_changed)
        self._show()

    def _edited(self, rule) -> None:
        if rule != self.document.paint_rule:
            old = self.document.paint_rule
            self.push(
                commands.SetValue("change the paint rule", self.document, "paint_rule", old, rule)
            )

    def _show(self, _rule=None) -> None:
        self.box.set_rule(self.document.paint_rule)
        self.map_view.show_mask(self.painter.rule_mask())

    def _on_map_changed(self, name: str, _rect) -> None:
        if name == "height" and self.document.paint_rule.active:
            self.map_view.show_mask(self.painter.rule_mask())


__all__ = ["PaintController", "PaintRules"]  # the window takes both from here
