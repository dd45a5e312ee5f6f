"""The designer's undoable edits (QUndoStack commands) and the history's memory cap.

Every command applies its change in `apply` and takes it back in `revert`; `clone` makes a
fresh command holding the same change, so the history can be rebuilt without its oldest steps
when the paint strokes it keeps grow past the memory cap (QUndoStack can only limit the number
of steps, and only while it is empty)."""

from __future__ import annotations

from time import monotonic

from PySide6.QtGui import QUndoCommand, QUndoStack

from core.brush import Stroke
from core.design_maps import DesignMaps
from core.document import Document
from core.lighting import Lighting
from core.lod import LodConfig
from core.params import PatchParams, SliceParams
from core.wind import Wind

MEMORY_CAP = 512 * 1024 * 1024  # bytes of paint-stroke texels the history keeps
# Edits of one value that follow each other this closely are one undo step (a slider or dial
# dragged, a key held); after a pause an edit is a step of its own (two presets picked).
MERGE_S = 1.0


class Command(QUndoCommand):
    def __init__(self, text: str) -> None:
        super().__init__(text)
        self._skip_redo = False  # the change is made already (a stroke; a rebuilt history)

    def redo(self) -> None:
        if self._skip_redo:
            self._skip_redo = False
            return
        self.apply()

    def undo(self) -> None:
        self.revert()

    def apply(self) -> None:
        raise NotImplementedError

    def revert(self) -> None:
        raise NotImplementedError

    def clone(self) -> Command:
        raise NotImplementedError

    @property
    def memory_bytes(self) -> int:
        return 0


class SetValue(Command):
    """One value of the document from `old` to `new`: an attribute (density, slices, light,
    cameras), or with `index` one grass type's `params` or `lod` (document.set_<name>)."""

    def __init__(
        self,
        text: str,
        document: Document,
        name: str,
        old,
        new,
        merge_id: int = -1,
        index: int | None = None,
        at: float | None = None,
        gesture: int | None = None,
    ) -> None:
        super().__init__(text)
        self.document, self.name, self.index = document, name, index
        self.old, self.new, self.merge_id = old, new, merge_id
        self.at = monotonic() if at is None else at  # when its last edit came
        self.gesture = gesture  # one drag (press to release): merged however slow

    def _set(self, value) -> None:
        if self.index is None:
            setattr(self.document, self.name, value)
        else:
            getattr(self.document, f"set_{self.name}")(self.index, value)

    def apply(self) -> None:
        self._set(self.new)

    def revert(self) -> None:
        self._set(self.old)

    def id(self) -> int:
        return self.merge_id

    def mergeWith(self, other) -> bool:  # a slider drag is one undo step
        if other.id() != self.merge_id or (other.document, other.name, other.index) != (
            self.document,
            self.name,
            self.index,
        ):
            return False
        same_drag = other.gesture is not None and other.gesture == self.gesture
        if other.at - self.at > MERGE_S and not same_drag:
            return False
        self.new, self.at = other.new, other.at
        return True

    def clone(self) -> SetValue:
        return SetValue(
            self.text(),
            self.document,
            self.name,
            self.old,
            self.new,
            self.merge_id,
            self.index,
            self.at,
            self.gesture,
        )


def set_params(doc: Document, index: int, new: PatchParams) -> SetValue:
    text = f"change blades of {doc.grass_names[index]}"
    return SetValue(text, doc, "params", doc.params(index), new, index=index)


def set_lod(doc: Document, index: int, new: LodConfig) -> SetValue:
    text = f"edit LOD levels of {doc.grass_names[index]}"
    return SetValue(text, doc, "lod", doc.lod(index), new, index=index)


class SetLods(Command):
    """Every grass type's LodConfig at once (one undo step): the view height the LOD
    distances hold for is one setting of the view, whatever the type."""

    def __init__(self, text: str, document: Document, new: list[LodConfig]) -> None:
        super().__init__(text)
        self.document = document
        self.old = document.lods
        self.new = list(new)

    def apply(self) -> None:
        self.document.set_lods(self.new)

    def revert(self) -> None:
        self.document.set_lods(self.old)

    def clone(self) -> SetLods:
        twin = SetLods(self.text(), self.document, self.new)
        twin.old = list(self.old)
        return twin


def set_lods(doc: Document, new: list[LodConfig], text: str) -> SetLods:
    return SetLods(text, doc, new)


def set_density(doc: Document, new: float) -> SetValue:
    return SetValue("change density", doc, "density", doc.density, new, merge_id=1)


def set_slices(doc: Document, new: SliceParams) -> SetValue:
    return SetValue("change slices", doc, "slices", doc.slices, new)


def set_light(doc: Document, new: Lighting, gesture: int | None = None) -> SetValue:
    """A light edit; those of one drag of the sun dial (`gesture`) are one undo step, and
    switching the blade shadows on or off is one of its own."""
    switch = new.blade_shadows != doc.light.blade_shadows
    return SetValue(
        "change light", doc, "light", doc.light, new, merge_id=-1 if switch else 2, gesture=gesture
    )


def set_wind(doc: Document, new: Wind) -> SetValue:
    """Switching the wind on or off is an undo step of its own; a drag of the dial or a slider
    merges into one "change wind"."""
    if new.enabled != doc.wind.enabled:
        return SetValue("wind on" if new.enabled else "wind off", doc, "wind", doc.wind, new)
    return SetValue("change wind", doc, "wind", doc.wind, new, merge_id=3)


def set_cameras(doc: Document, new: dict, text: str) -> SetValue:
    return SetValue(text, doc, "cameras", doc.cameras, new)


class PaintStroke(Command):
    """One finished brush stroke: its texels before and after, in the tiles it touched."""

    def __init__(self, stroke: Stroke, text: str) -> None:
        super().__init__(text)
        self.stroke = stroke
        self._skip_redo = True  # painted while the mouse moved

    def apply(self) -> None:
        self.stroke.redo()

    def revert(self) -> None:
        self.stroke.undo()

    def clone(self) -> PaintStroke:
        return PaintStroke(self.stroke, self.text())

    @property
    def memory_bytes(self) -> int:
        return self.stroke.memory_bytes


def history_bytes(stack: QUndoStack) -> int:
    return sum(getattr(stack.command(i), "memory_bytes", 0) for i in range(stack.count()))


def push(stack: QUndoStack, command: Command, cap: int = MEMORY_CAP) -> int:
    """Push a command; if the history then keeps more than `cap` bytes, forget its oldest
    steps (the newest step always stays). Returns how many steps were forgotten."""
    stack.push(command)
    if history_bytes(stack) <= cap:  # (a push leaves nothing to redo)
        return 0
    commands = [stack.command(i) for i in range(stack.count())]
    keep, total = 0, 0
    for cmd in reversed(commands):
        total += getattr(cmd, "memory_bytes", 0)
        if keep and total > cap:
            break
        keep += 1
    dropped = len(commands) - keep
    clean = stack.cleanIndex()
    clones = [cmd.clone() for cmd in commands[dropped:]]
    stack.clear()
    for i, cmd in enumerate(clones):
        if clean - dropped == i:
            stack.setClean()
        cmd._skip_redo = True  # the state already holds every kept change
        stack.push(cmd)
    if clean - dropped == len(clones):
        stack.setClean()
    elif clean < dropped:
        stack.resetClean()  # the saved state is no longer reachable by undo
    return dropped


class SetMap(Command):
    """A whole map (or one grass type's density) replaced, e.g. by an imported file."""

    def __init__(self, maps: DesignMaps, layer: str, channel: int | None, new, text: str) -> None:
        super().__init__(text)
        self.maps, self.layer, self.channel, self.new = maps, layer, channel, new
        view = maps.layer(layer)
        self.old = view[..., [channel]].copy() if channel is not None else view.copy()

    def _put(self, values) -> None:
        if self.channel is not None:
            self.maps.write(self.layer, 0, 0, values[..., 0], channel=self.channel)
        else:
            self.maps.write(self.layer, 0, 0, values)

    def apply(self) -> None:
        self._put(self.new)

    def revert(self) -> None:
        self._put(self.old)

    def clone(self) -> SetMap:
        twin = SetMap(self.maps, self.layer, self.channel, self.new, self.text())
        twin.old = self.old
        return twin

    @property
    def memory_bytes(self) -> int:
        return self.old.nbytes + self.new.nbytes


class PlaceSpecies(SetMap):
    """Grass types placed from a colour map: the species rules used and the density map they
    wrote, one step (core/species.py)."""

    def __init__(self, document: Document, species, density, text: str) -> None:
        super().__init__(document.maps, "density", None, density, text)
        self.document, self.species, self.old_species = document, species, document.species

    def apply(self) -> None:
        self.document.species = self.species
        super().apply()

    def revert(self) -> None:
        self.document.species = self.old_species
        super().revert()

    def clone(self) -> PlaceSpecies:
        twin = PlaceSpecies(self.document, self.species, self.new, self.text())
        twin.old, twin.old_species = self.old, self.old_species
        return twin
