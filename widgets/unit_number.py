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


def fit_names(tree) -> None:
    """Size a ParameterTree's name column to its fields' names, not to its group titles (a
    group title spans the row), so the values keep the width to show their units."""
    from PySide6.QtWidgets import QHeaderView

    metrics = tree.fontMetrics()
    widths = [0]
    for item in tree.listAllItems():
        param = getattr(item, "param", None)
        if param is None or param.type() == "group":
            continue
        depth, parent = 0, item.parent()
        while parent is not None:
            depth, parent = depth + 1, parent.parent()
        widths.append(metrics.horizontalAdvance(item.text(0)) + tree.indentation() * depth + 24)
    header = tree.header()
    header.setSectionResizeMode(0, QHeaderView.ResizeMode.Interactive)
    tree.setColumnWidth(0, max(widths))


def report_bad_text(tree, message) -> None:
    """Say in the panel's `message` label what is wrong with text typed into a number field of
    the tree, as it is typed ("Sun elevation: “abc” is not a number …"; pyqtgraph only draws
    a red border), and take it back once the text is a number again. An out-of-range number in
    a field with bounds gets the bounds; the other fields' panels refuse such numbers with
    their own message."""
    from pyqtgraph import SpinBox

    def show(problem: str) -> None:
        if problem:
            message.setText(problem)
        elif message.text() == message.property("typed_problem"):
            message.clear()
        message.setProperty("typed_problem", problem)

    for item in tree.listAllItems():
        box = getattr(item, "widget", None)
        if isinstance(box, SpinBox):
            box.lineEdit().textEdited.connect(
                lambda _text, box=box, param=item.param: show(_problem(box, param))
            )


def _problem(box, param) -> str:
    if box.textValid:
        return ""
    text = box.lineEdit().text().strip()
    unit = box.opts["suffix"].strip()
    if box.interpret() is False:
        typed = f" (with or without “{unit}”)" if unit else ""
        return f"{param.title()}: “{text}” is not a number; type a number{typed}"
    low, high = ("…" if b is None else f"{b:g}" for b in box.opts["bounds"])
    return f"{param.title()}: {text} is out of range; allowed {low} … {high}"
