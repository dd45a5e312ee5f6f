"""Blade-parameter panel: a pyqtgraph ParameterTree over PatchParams, a preset picker and the
global density. It shows the model and reports edits; it holds no algorithm."""

from __future__ import annotations

import dataclasses

from pyqtgraph.parametertree import Parameter, ParameterTree
from PySide6.QtCore import Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from core.document import Document
from core.params import (
    PRESETS,
    SLICE_COUNTS,
    SLICE_SIZES,
    TOP_SIZES,
    ParameterError,
    PatchParams,
    SliceParams,
)
from widgets.unit_number import fit_names, report_bad_text  # and registers the unit_float type

CUSTOM = "(custom)"
SIZE_LABELS = {f"{w} × {h}": (w, h) for w, h in SLICE_SIZES}


SPEC_NAMES = {f.name for f in dataclasses.fields(PatchParams) if "spec" in f.metadata}


def _slice_children(sp: SliceParams) -> list[dict]:
    return [
        {
            "name": "slices",
            # the LOD zones dock sets each volume level's own count: this one is what the
            # Volume only and Compare views draw with
            "title": "Slices (Volume, Compare)",
            "tip": "slices per direction in the Volume only (Ctrl+3) and Compare (Ctrl+5) views; "
            "each volume zone of the LOD view has its own count in the LOD zones dock",
            "type": "list",
            "limits": list(SLICE_COUNTS),
            "value": sp.slices,
        },
        {
            "name": "slice_size",
            "title": "Slice size",
            "type": "list",
            "limits": list(SIZE_LABELS),
            "value": f"{sp.width} × {sp.height}",
        },
        {
            "name": "top",
            "title": "Horizontal slice",
            "type": "list",
            "limits": list(TOP_SIZES),
            "value": sp.top,
        },
    ]


def _in_words(message: str, name: str) -> str:
    """A refusal as the panel names things: each parameter by its label, not its field."""
    for field in sorted(SPEC_NAMES, key=len, reverse=True):
        message = message.replace(field, PatchParams.spec(field).label)
    label = PatchParams.spec(name).label if name in SPEC_NAMES else name.replace("_", " ")
    return message if message.startswith(label) else f"{label}: {message}"


def _field_param(f: dataclasses.Field, value) -> dict:
    if f.name.endswith("_color"):
        label = f.name.replace("_color", " colour").replace("_", " ").capitalize()
        return {"name": f.name, "title": label, "type": "color", "value": QColor.fromRgbF(*value)}
    if f.type in ("bool", bool):
        return {"name": f.name, "title": "Clustered thresholds", "type": "bool", "value": value}
    spec = f.metadata["spec"]
    kind = "int" if spec.integer else "unit_float"
    step = 1 if spec.integer else (spec.high - spec.low) / 200.0
    return {
        "name": f.name,
        "title": spec.label,
        "type": kind,
        "value": value,
        "step": step,
        "suffix": f" {spec.unit}" if spec.unit else "",
        "decimals": 4,
    }


class PatchPanel(QWidget):
    params_edited = Signal(int, object)  # grass type, PatchParams
    density_edited = Signal(float)
    slices_edited = Signal(object)  # SliceParams

    def __init__(self, document: Document, parent=None) -> None:
        super().__init__(parent)
        self.document = document
        self.grass_type = 0  # whose blade parameters are shown
        params = document.params(0)
        fields = dataclasses.fields(PatchParams)
        children = [
            {
                "name": "grass_type",
                "title": "Grass type",
                "type": "list",
                "limits": {"main grass": 0},
                "value": 0,
            },
            {
                "name": "preset",
                "title": "Preset",
                "type": "list",
                "limits": [*PRESETS, CUSTOM],
                "value": self._preset_of(params),
            },
            {
                "name": "density",
                "title": "Global density",
                "type": "float",
                "value": document.density,
                "limits": (0.0, 1.0),
                "step": 0.05,
            },
            {
                "name": "blades",
                "title": "Blades",
                "type": "group",
                "children": [_field_param(f, getattr(params, f.name)) for f in fields],
            },
            {
                "name": "conversion",
                "title": "Slices (volume and image-based)",
                "type": "group",
                "children": _slice_children(document.slices),
            },
        ]
        self.root = Parameter.create(name="patch", type="group", children=children)
        self.tree = ParameterTree(showHeader=False)
        self.tree.setParameters(self.root, showTop=False)
        fit_names(self.tree)
        self.message = QLabel("")
        self.message.setWordWrap(True)
        self.message.setStyleSheet("color: #b03020")
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.tree)
        layout.addWidget(self.message)
        report_bad_text(self.tree, self.message)
        self._updating = False
        self.root.sigTreeStateChanged.connect(self._on_tree_changed)
        self._connect(document)
        self._show_grass_types()

    def _connect(self, document: Document) -> None:
        document.events.params.connect(self._on_params_changed)
        document.events.density.connect(self._on_density_changed)
        document.events.slices.connect(self._on_slices_changed)

    def _disconnect(self) -> None:
        events = self.document.events
        events.params.disconnect(self._on_params_changed)
        events.density.disconnect(self._on_density_changed)
        events.slices.disconnect(self._on_slices_changed)

    def set_document(self, document: Document) -> None:
        """Show another project (File > Open): every control from the new document."""
        self._disconnect()
        self.document = document
        self._connect(document)
        self.grass_type = 0
        self._show_grass_types()
        self.message.setText("")
        self._show(document.params(0))
        self._on_density_changed(document.density)
        self._on_slices_changed(document.slices)

    @staticmethod
    def _preset_of(params: PatchParams) -> str:
        for name, preset in PRESETS.items():
            if preset == params:
                return name
        return CUSTOM

    def _show_grass_types(self) -> None:
        names = self.document.grass_names
        self._updating = True
        try:
            param = self.root.child("grass_type")
            param.setLimits({name: i for i, name in enumerate(names)})
            param.setValue(self.grass_type)
            param.setOpts(visible=len(names) > 1)
        finally:
            self._updating = False

    def show_grass_type(self, index: int) -> None:
        """Show and edit the blade parameters of another grass type."""
        self.grass_type = index
        self.message.setText("")
        self._show(self.document.params(index))

    def param(self, name: str) -> Parameter:
        if name in ("preset", "density", "grass_type"):
            return self.root.child(name)
        if name in ("slices", "slice_size", "top"):
            return self.root.child("conversion", name)
        return self.root.child("blades", name)

    # -- widget → model ----------------------------------------------------------------------
    def _on_tree_changed(self, _root, changes) -> None:
        if self._updating:
            return
        for param, change, value in changes:
            if change != "value":
                continue
            name = param.name()
            if name == "grass_type":
                self.show_grass_type(int(value))
            elif name == "preset":
                if value in PRESETS:
                    self.params_edited.emit(self.grass_type, PRESETS[value])
            elif name == "density":
                self.density_edited.emit(float(value))
            elif name in ("slices", "top"):
                self.slices_edited.emit(self.document.slices.replace(**{name: int(value)}))
            elif name == "slice_size":
                w, h = SIZE_LABELS[value]
                self.slices_edited.emit(self.document.slices.replace(width=w, height=h))
            else:
                self._edit_field(name, value)

    def _edit_field(self, name: str, value) -> None:
        if isinstance(value, QColor):
            value = (round(value.redF(), 4), round(value.greenF(), 4), round(value.blueF(), 4))
        current = self.document.params(self.grass_type)
        try:
            params = current.replace(**{name: value})
        except ParameterError as exc:
            self.message.setText(_in_words(str(exc), name))
            self._show(current)  # revert the control to the model
            return
        self.message.setText("")
        self.params_edited.emit(self.grass_type, params)

    # -- model → widget ----------------------------------------------------------------------
    def _show(self, params: PatchParams) -> None:
        self._updating = True
        try:
            for f in dataclasses.fields(params):
                value = getattr(params, f.name)
                if f.name.endswith("_color"):
                    value = QColor.fromRgbF(*value)
                self.param(f.name).setValue(value)
            self.param("preset").setValue(self._preset_of(params))
        finally:
            self._updating = False

    def _on_params_changed(self, index: int, params: PatchParams) -> None:
        if index == self.grass_type:
            self.message.setText("")
            self._show(params)

    def _on_density_changed(self, density: float) -> None:
        self._updating = True
        try:
            self.param("density").setValue(density)
        finally:
            self._updating = False

    def _on_slices_changed(self, sp: SliceParams) -> None:
        self._updating = True
        try:
            self.param("slices").setValue(sp.slices)
            self.param("slice_size").setValue(f"{sp.width} × {sp.height}")
            self.param("top").setValue(sp.top)
        finally:
            self._updating = False

    def closeEvent(self, event) -> None:
        self._disconnect()
        super().closeEvent(event)
