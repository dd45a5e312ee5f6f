"""A value of an evented model declared once (core/document.py): how it is checked, the signal
it announces a change on (`owner.events.<name>`, only when the value changed), and a copy
handed out for dictionaries, so that a change always goes through the setter."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Generic, TypeVar, overload

T = TypeVar("T")


def check_type(kind: type[T]) -> Callable[[Any, Any], T]:
    def check(_doc: Any, value: Any) -> T:
        if not isinstance(value, kind):
            raise TypeError(f"expected a {kind.__name__}, got {type(value).__name__}")
        return value

    return check


class Field(Generic[T]):
    """A document value declared once: how it is checked, its event (`events.<name>`, sent
    only when the value changed) and its place in `Document.apply`. Dictionaries are handed
    out as copies, so a change always goes through the setter."""

    def __init__(self, check: Callable[[Any, Any], T], doc: str = "") -> None:
        self.check = check
        self.__doc__ = doc

    def __set_name__(self, owner: type, name: str) -> None:
        self.name, self.slot = name, f"_{name}"

    @overload
    def __get__(self, doc: None, owner: type) -> Field[T]: ...

    @overload
    def __get__(self, doc: Any, owner: type) -> T: ...

    def __get__(self, doc: Any, owner: type) -> Field[T] | T:
        if doc is None:
            return self
        value = getattr(doc, self.slot)
        return dict(value) if isinstance(value, dict) else value  # type: ignore[return-value]

    def __set__(self, doc: Any, value: T) -> None:
        value = self.check(doc, value)
        if not hasattr(doc, self.slot):
            setattr(doc, self.slot, value)  # the first value: nobody listens yet
        elif value != getattr(doc, self.slot):
            setattr(doc, self.slot, value)
            getattr(doc.events, self.name).emit(dict(value) if isinstance(value, dict) else value)
