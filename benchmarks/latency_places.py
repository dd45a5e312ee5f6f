"""Where the latency session (benchmarks/latency_session.py) finds the designer's controls on
the screen, for xdotool."""

from __future__ import annotations

import time

from PySide6.QtCore import QPoint
from PySide6.QtWidgets import QApplication, QTabBar


def _centre(widget, point: QPoint | None = None) -> tuple[int, int]:
    at = widget.mapToGlobal(point if point is not None else widget.rect().center())
    return at.x(), at.y()


def _tree_value(tree, param) -> tuple[int, int]:
    """The value column of a ParameterTree's row for `param`."""
    item = next(iter(param.items))
    rect = tree.visualItemRect(item)
    return _centre(
        tree.viewport(), QPoint(tree.header().sectionPosition(1) + 30, rect.center().y())
    )


def places(app: QApplication, window) -> dict:
    """Screen positions of the controls the driver uses, each dock raised in turn to lay it
    out; the patch dock raised last."""
    out: dict = {}
    out["viewport_centre"] = _centre(window.viewport)
    docks = {
        "wind": window.wind_dock,
        "lod": window.lod_dock,
        "light": window.light_dock,
        "patch": window.patch_dock,
    }
    for name, dock in docks.items():
        dock.raise_()
        for _ in range(20):
            app.processEvents()
            time.sleep(0.01)
        for bar in window.findChildren(QTabBar):
            for i in range(bar.count()):
                if bar.tabText(i) == dock.windowTitle():
                    out[f"{name}_tab"] = _centre(bar, bar.tabRect(i).center())
        if name == "patch":  # the slice count lies below the blades: scrolled to the bottom
            panel = window.panel
            out["patch_tree"] = _centre(panel.tree.viewport())
            panel.tree.scrollToBottom()
            app.processEvents()
            out["slices"] = _tree_value(panel.tree, panel.param("slices"))
            panel.tree.scrollToTop()
            app.processEvents()
            for param in ("blade_count", "preset"):
                out[param] = _tree_value(panel.tree, panel.param(param))
        elif name == "light":
            panel = window.light_panel
            out["sun_elevation"] = _tree_value(panel.tree, panel.root.child("sun_elevation"))
        elif name == "lod":
            out["lod_end"] = _centre(window.lod_panel.end_box(0))
        elif name == "wind":
            out["wind_preset"] = _centre(window.wind_panel.preset_box)
    return out
