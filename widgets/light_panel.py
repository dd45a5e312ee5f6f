"""The light panel (thesis 6.4.3): a sun dial to drag the sun by feel, then sun elevation and
azimuth, sun and ambient colours, translucency, how dark the dense grass gets at its roots, and
the fog distance as numbers, and the blades' shadows on the ground (on / off, strength) — a
pyqtgraph ParameterTree that shows a Lighting and reports edits
as a new one."""

from __future__ import annotations

import dataclasses

from pyqtgraph.parametertree import Parameter, ParameterTree
from PySide6.QtCore import Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from core.lighting import Lighting
from core.sun_dial import camera_heading
from widgets.sun_dial import SunDial
from widgets.unit_number import fit_names, report_bad_text  # and registers the unit_float type

# (field, title, low, high, step, suffix); colours are edited with colour buttons
NUMBERS = (
    ("sun_elevation", "Sun elevation", 0.0, 90.0, 1.0, "°"),
    ("sun_azimuth", "Sun azimuth", 0.0, 360.0, 5.0, "°"),
    ("translucency", "Translucency", 0.0, 1.0, 0.05, ""),
    ("blade_ao_impact", "Blade occlusion", 0.0, 1.0, 0.05, ""),
    ("fog_distance", "Fog distance", 10.0, 5000.0, 10.0, "units"),
    ("shadow_strength", "Shadow strength", 0.0, 1.0, 0.05, ""),
)
COLOURS = (("sun_color", "Sun colour"), ("ambient_color", "Ambient colour"))
FLAGS = (("blade_shadows", "Blade shadows"),)  # on / off: check boxes


class LightPanel(QWidget):
    light_edited = Signal(object)  # Lighting

    def __init__(self, light: Lighting, parent=None) -> None:
        super().__init__(parent)
        numbers = [
            {
                "name": name,
                "title": title,
                # typed with or without its unit; a value out of range reaches Lighting, which
                # refuses it with a message naming the field and its range
                "type": "unit_float",
                "decimals": 6,  # 1500 reads "1500", not "1.5e+03"
                "step": step,
                "suffix": suffix,
                "value": getattr(light, name),
                # a light edit costs the next frame nothing per blade: apply each step at once
                # (the spin box's default waits 0.3 s for more; consecutive steps merge into
                # one undo step, app/commands.py)
                "delay": 0.0,
            }
            for name, title, _low, _high, step, suffix in NUMBERS
        ]
        colours = [
            {
                "name": name,
                "title": title,
                "type": "color",
                "value": QColor.fromRgbF(*getattr(light, name)),
            }
            for name, title in COLOURS
        ]
        flags = [
            {"name": name, "title": title, "type": "bool", "value": getattr(light, name)}
            for name, title in FLAGS
        ]
        # the blades' shadows together at the end: the switch, then its strength (NUMBERS' last)
        children = numbers[:-1] + colours + flags + numbers[-1:]
        self.root = Parameter.create(name="light", type="group", children=children)
        self.tree = ParameterTree(showHeader=False)
        self.tree.setParameters(self.root, showTop=False)
        fit_names(self.tree)
        self.message = QLabel()
        self.message.setWordWrap(True)
        self.dial = SunDial(light.sun_elevation, light.sun_azimuth)
        self.dial.sun_moved.connect(self._on_dial)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.dial)
        layout.addWidget(self.tree)
        layout.addWidget(self.message)
        report_bad_text(self.tree, self.message)
        self.light = light
        self._updating = False
        self.root.sigTreeStateChanged.connect(self._on_tree_changed)

    def show_light(self, light: Lighting) -> None:
        """Model -> widgets (an undo, a newly opened project)."""
        self.light = light
        self.dial.set_sun(light.sun_elevation, light.sun_azimuth)
        self._updating = True
        try:
            for name, *_ in NUMBERS:
                self.root.child(name).setValue(getattr(light, name))
            for name, _ in COLOURS:
                self.root.child(name).setValue(QColor.fromRgbF(*getattr(light, name)))
            for name, _ in FLAGS:
                self.root.child(name).setValue(getattr(light, name))
        finally:
            self._updating = False

    def show_view(self, yaw: float) -> None:
        """Turn the dial with the camera: its top is the way the view looks."""
        self.dial.set_heading(camera_heading(yaw))

    def _on_dial(self, elevation: float, azimuth: float) -> None:
        """A drag or arrow key on the dial: both numbers change, one edit goes out."""
        with self.root.treeChangeBlocker():
            self.root.child("sun_elevation").setValue(elevation)
            self.root.child("sun_azimuth").setValue(azimuth)

    def _on_tree_changed(self, *_) -> None:
        if self._updating:
            return
        values = {name: float(self.root.child(name).value()) for name, *_ in NUMBERS}
        for name, title, low, high, _step, suffix in NUMBERS:
            if not low <= values[name] <= high:
                unit = f" {suffix}" if suffix else ""
                self.message.setText(
                    f"{title} {values[name]:g}{unit} is out of range; "
                    f"allowed {low:g} … {high:g}{unit}"
                )
                return
        for name, _ in COLOURS:
            c = self.root.child(name).value()
            values[name] = (c.redF(), c.greenF(), c.blueF())
        for name, _ in FLAGS:
            values[name] = bool(self.root.child(name).value())
        try:
            light = dataclasses.replace(self.light, **values)
        except ValueError as exc:
            self.message.setText(str(exc))
            return
        self.message.clear()
        if light != self.light:
            self.light = light
            self.light_edited.emit(light)
