"""A number parameter (pyqtgraph) shown with its unit and typed with or without it: the
"unit_float" type of the Patch and Light panels."""

from __future__ import annotations

from pyqtgraph.parametertree import registerParameterType
from pyqtgraph.parametertree.parameterTypes import NumericParameterItem, SimpleParameter


class UnitNumberItem(NumericParameterItem):
    """A number shown with its unit, typed with or without it ("0.6" or "0.6 patch units").
    The box has no limits of its own: a value out of range reaches the panel, which refuses it
    with a message naming the field and its range (a clamped value would hide the mistake)."""

    def makeWidget(self):
        box = super().makeWidget()
        unit = box.opts["suffix"].strip()
        with_unit = box.interpret

        def interpret():
            text = box.lineEdit().text().strip()
            if unit and not text.endswith(unit):
                try:
                    return float(text.replace(",", "."))
                except ValueError:
                    return False
            return with_unit()

        box.interpret = interpret
        return box


class UnitNumberParameter(SimpleParameter):
    itemClass = UnitNumberItem

    def _interpretValue(self, v):
        return float(v)


registerParameterType("unit_float", UnitNumberParameter, override=True)
