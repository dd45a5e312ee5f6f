"""The messages between the window (render/render_client.py) and its render processes
(render/render_server.py), as typed values sent through a pipe. This module imports no GL: the
window's process imports it and core/ alone.

A document change travels as one `Change`: the name of the document's event and its arguments,
as `Document.events.all` announced it, made again in the process by `Document.apply`. A new
document field therefore needs no new message.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from core.stats import FrameStats

# what a frame is for: the live view (a draft, then a full frame), a screenshot of any size
# (full frame only), or the Quality view (the LOD frame against all-geometry)
Purpose = Literal["live", "screenshot", "quality"]


# -- window → render process -----------------------------------------------------------------
@dataclass(frozen=True)
class Open:
    """A whole document: the plain data a project file holds, and the mapped design-map stack."""

    data: dict
    stack_path: str
    shape: tuple[int, ...]


@dataclass(frozen=True)
class Change:
    """One document event: `Document.apply(name, args)` makes it again."""

    name: str
    args: tuple = ()


@dataclass(frozen=True)
class MapsChanged:
    """A rectangle (x, y, w, h) of one design map, written into the mapped stack."""

    layer: str
    rect: tuple[int, int, int, int]


@dataclass(frozen=True)
class SetMode:
    mode: str  # a ViewMode


@dataclass(frozen=True)
class SetView:
    view: str  # shaded | techniques


@dataclass(frozen=True)
class SetOverlay:
    group: str  # brush | zones
    lines: list = field(default_factory=list)  # (points, rgba) per line


@dataclass(frozen=True)
class SetLodScale:
    factor: float  # every zone's distances times this (adaptive LOD, core/hold.py)


@dataclass(frozen=True)
class SetContinuous:
    on: bool  # full frames one after another (profiling)


@dataclass(frozen=True)
class FrameRequest:
    version: int
    camera: object  # core.camera.Camera
    size: tuple[int, int]
    purpose: Purpose = "live"
    time: float = 0.0  # the moment of the wind
    state_time: float = 0.0  # monotonic() when the state was asked for (latency figures)
    out_path: str = ""  # the mapped file the frame is written into
    out_bytes: int = 0
    again: bool = False  # a draft drawn again to show what the process made meanwhile


@dataclass(frozen=True)
class Ack:
    """The window has copied the last frame out of the mapped file."""


@dataclass(frozen=True)
class Query:
    token: int  # answered with Facts(token, …) once every earlier message is handled


@dataclass(frozen=True)
class Quit:
    pass


# -- render process → window -----------------------------------------------------------------
@dataclass(frozen=True)
class Hello:
    pid: int
    max_image_size: int
    gl: str


@dataclass(frozen=True)
class FrameReady:
    version: int
    purpose: Purpose
    size: tuple[int, int]
    stats: FrameStats
    figures: dict | None = None  # quality: LOD against all-geometry (core/quality.figures)


@dataclass(frozen=True)
class Mapped:
    """The process has mapped this file: its name may go."""

    path: str


@dataclass(frozen=True)
class Status:
    text: str  # what the process is doing ("" when done)


@dataclass(frozen=True)
class Facts:
    token: int
    facts: dict


@dataclass(frozen=True)
class Failed:
    traceback: str
