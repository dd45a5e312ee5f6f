"""The window's side of the render processes (render/render_server.py): starts them, sends them
the document and every change of it, asks for frames and takes them back. Qt-free: the viewport
watches `connections()` with its event loop and calls `receive` when one is readable.

The design-map stack reaches the processes through a memory-mapped file: the whole stack when a
document is opened, then only the rectangles edits changed (merged until the next frame)."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import subprocess
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from multiprocessing.connection import Connection
from time import monotonic

import numpy as np

from core.design_maps import LAYER_INDEX, LAYERS, union
from core.document import Document
from core.project_file import document_data
from core.stats import FrameStats
from render import derived_cache, process_start
from render import protocol as msg
from render.derived_cache import SHARED_DIR_ENV
from render.mapped import MappedArray
from render.process_start import FULL, ROLES

QUIT_WAIT_S = 1.0  # how long closing waits for the render processes to quit before killing


def _shared_folder() -> str:
    return "/dev/shm" if os.path.isdir("/dev/shm") else tempfile.gettempdir()


def _new_file(nbytes: int, prefix: str) -> str:
    fd, path = tempfile.mkstemp(prefix=prefix, dir=_shared_folder())
    os.ftruncate(fd, max(nbytes, 1))
    os.close(fd)
    return path


@dataclass
class Frame:
    version: int
    purpose: msg.Purpose
    image: np.ndarray  # (h, w, 4) uint8, top row first (quality: the difference heat map)
    stats: FrameStats
    figures: dict | None = None  # quality: LOD against all-geometry (core/quality.figures)


@dataclass
class _Process:
    role: str
    process: subprocess.Popen | process_start.Forked
    conn: Connection
    pid: int = 0
    max_image_size: int = 0
    out: MappedArray | None = None
    out_capacity: int = 0
    facts: dict = field(default_factory=dict)
    stack: MappedArray | None = None  # its own copy of the design-map stack
    # frame files outgrown by a larger screenshot: a request in flight may still name one
    old_outs: list = field(default_factory=list)
    named: set = field(default_factory=set)  # files made for it that still have a name

    def new_file(self, nbytes: int, prefix: str) -> str:
        path = _new_file(nbytes, prefix)
        self.named.add(path)
        return path

    def forget_name(self, path: str) -> None:
        """The process has mapped the file: its name is no longer needed (so nothing is left
        behind in /dev/shm if the window itself is killed later)."""
        if path in self.named:
            self.named.discard(path)
            with contextlib.suppress(OSError):
                os.unlink(path)

    def release_files(self) -> None:
        for mapped in [*self.old_outs, *(f for f in (self.out, self.stack) if f is not None)]:
            mapped.close()
        for path in list(self.named):
            self.forget_name(path)
        self.old_outs, self.out, self.stack = [], None, None


class RenderClient:
    def __init__(
        self,
        on_frame: Callable[[Frame], None],
        on_status: Callable[[str], None] = lambda text: None,
        on_restart: Callable[[str, str], None] = lambda role, why: None,
    ) -> None:
        self.on_frame = on_frame
        self.on_status = on_status
        self.on_restart = on_restart  # (role, what happened): a process died and was restarted
        self._document: Document | None = None
        self._dirty: dict[str, tuple[int, int, int, int]] = {}
        self._replay: dict[object, object] = {}  # view state a restarted process needs again
        self._last_request: msg.FrameRequest | None = None
        self._changed: Callable[[], None] = lambda: None
        self._closed = False
        # the folder the two processes hand each other the light tables' sums in (render/
        # derived_cache.py): the cache kept between runs, or one for this window's session
        kept = derived_cache.folder()
        self._session_folder = None if kept is not None else tempfile.mkdtemp(prefix="sward-sums-")
        self._shared = str(kept) if kept is not None else self._session_folder
        self.processes: dict[str, _Process] = {role: self._start(role) for role in ROLES}

    # -- processes ---------------------------------------------------------------------------
    def _start(self, role: str) -> _Process:
        """The process of `role` started early for this window (render/process_start.py), or
        a new one."""
        early = process_start.take(role, self._shared)
        process, mine = early or process_start.spawn(role, self._shared, SHARED_DIR_ENV)
        return _Process(role, process, Connection(mine.detach()))

    def connections(self) -> dict[str, object]:
        return {role: p.conn for role, p in self.processes.items()}

    @property
    def pids(self) -> dict[str, int]:
        return {role: p.process.pid for role, p in self.processes.items()}

    @property
    def max_image_size(self) -> int:
        return self.processes[FULL].max_image_size

    def _send(self, message: object, roles=ROLES) -> None:
        if self._closed:
            return
        for role in roles:
            try:
                self.processes[role].conn.send(message)
            except (BrokenPipeError, OSError):
                self._restart(role)

    def _restart(self, role: str) -> None:
        old = self.processes[role]
        with contextlib.suppress(OSError):
            old.conn.close()
        if old.process.poll() is None:
            old.process.kill()
        code = old.process.wait(timeout=10)
        why = f"killed by signal {-code}" if code < 0 else f"exit {code}"
        old.release_files()
        self.processes[role] = self._start(role)
        if self._document is not None:
            self._open_in(role)
        for message in self._replay.values():
            self._send(message, (role,))
        if self._last_request is not None:
            self._request_from(role, self._last_request)
        self.on_restart(role, why)

    def receive(self, role: str) -> None:
        """Handle what one process sent (call when its connection is readable)."""
        if self._closed:
            return
        p = self.processes[role]
        try:
            while p.conn.poll():
                self._handle(p, p.conn.recv())
        except (EOFError, OSError):
            self._restart(role)

    def _handle(self, p: _Process, message: object) -> None:
        match message:
            case msg.Hello(pid, size, _gl):
                p.pid, p.max_image_size = pid, size
            case msg.FrameReady(version, purpose, (w, h), stats, figures):
                image = p.out.array[: w * h * 4].reshape(h, w, 4).copy()
                p.conn.send(msg.Ack())
                self.on_frame(Frame(version, purpose, image, stats, figures))
            case msg.Mapped(path):
                p.forget_name(path)
            case msg.Status(text):
                self.on_status(text)
            case msg.Facts(token, facts):
                p.facts[token] = facts
            case msg.Failed(text):
                self.on_status(f"the {p.role} renderer failed: {text.strip().splitlines()[-1]}")

    # -- the document ------------------------------------------------------------------------
    def attach(self, document: Document, changed: Callable[[], None]) -> None:
        """Send `document` whole, then follow its events; `changed()` after each change."""
        self.detach()
        self.open(document)
        self._changed = changed
        document.events.all.connect(self._on_event)
        document.maps.changed.connect(self._on_maps_changed)

    def detach(self) -> None:
        if self._document is None:
            return
        self._document.events.all.disconnect(self._on_event)
        self._document.maps.changed.disconnect(self._on_maps_changed)

    def _on_event(self, info) -> None:
        """Any document event, as one Change (the rebuilt terrain is rebuilt there too)."""
        name = info.signal.name
        self.change(msg.Change(name, () if name == "terrain" else tuple(info.args)))
        self._changed()

    def _on_maps_changed(self, name: str, rect) -> None:
        self.maps_changed(name, rect)
        self._changed()

    def open(self, document: Document) -> None:
        """Send a whole document (a new one, or the first)."""
        self._document = document
        self._dirty.clear()
        for role in ROLES:
            self._open_in(role)

    def _open_in(self, role: str) -> None:
        """The document to one process, with a mapped copy of the stack of its own (a process
        started anew gets the stack as it is now)."""
        self._flush_maps()
        p = self.processes[role]
        if p.stack is not None:
            p.stack.close()
        stack = self._document.maps.stack
        p.stack = MappedArray(p.new_file(stack.nbytes, "sward-maps-"), stack.shape)
        p.stack.array[:] = stack
        # the same plain data a project file holds (JSON), so the replica is built as a load is
        data = json.loads(json.dumps(document_data(self._document)))
        self._send(msg.Open(data, p.stack.path, stack.shape), (role,))

    def change(self, change: msg.Change) -> None:
        """A change of the open document, after the map rectangles changed before it."""
        self._flush_maps()
        self._send(change)

    def maps_changed(self, name: str, rect: tuple[int, int, int, int]) -> None:
        self._dirty[name] = union(self._dirty.get(name), rect)

    def _flush_maps(self) -> None:
        if self._document is None:
            return
        stack = self._document.maps.stack
        for name, (x, y, w, h) in self._dirty.items():
            i = LAYER_INDEX[name]
            c = LAYERS[i].channels
            for p in self.processes.values():
                if p.stack is not None:
                    p.stack.array[i, y : y + h, x : x + w, :c] = stack[i, y : y + h, x : x + w, :c]
            self._send(msg.MapsChanged(name, (x, y, w, h)))
        self._dirty.clear()

    # -- view state and frames ---------------------------------------------------------------
    def set_view_state(
        self,
        message: msg.SetMode | msg.SetView | msg.SetOverlay | msg.SetContinuous | msg.SetLodScale,
    ) -> None:
        """How frames are drawn, kept for a restarted process (an overlay per group)."""
        key = (type(message), getattr(message, "group", None))
        self._replay[key] = message
        self._send(message)

    def request(
        self,
        version: int,
        camera,
        size: tuple[int, int],
        purpose: msg.Purpose = "live",
        time: float = 0.0,
        draft: bool = True,
    ) -> None:
        """Ask for a frame of the current state: a draft and a full frame (`live`; without
        `draft` the full one alone), or only a full one (`screenshot`: of any size;
        `quality`: the LOD frame against an all-geometry reference, a heat map and figures);
        `time`: the moment of the wind."""
        if self._closed:
            return
        self._flush_maps()
        request = msg.FrameRequest(
            version, camera, (int(size[0]), int(size[1])), purpose, float(time), monotonic()
        )
        if purpose == "live":
            self._last_request = request
        for role in ROLES if purpose == "live" and draft else (FULL,):
            self._request_from(role, request)

    def _request_from(self, role: str, request: msg.FrameRequest) -> None:
        p = self.processes[role]
        w, h = request.size
        need = w * h * 4
        if p.out is None or p.out_capacity < need:
            if p.out is not None:
                p.old_outs.append(p.out)
            capacity = max(need, 1920 * 1200 * 4)
            p.out = MappedArray(p.new_file(capacity, f"sward-{role}-"), (capacity,), np.uint8)
            p.out_capacity = capacity
        self._send(replace(request, out_path=p.out.path, out_bytes=p.out_capacity), (role,))

    def query(self, token: int, role: str = FULL) -> None:
        """Ask one renderer for facts about its pipeline and document (answered into
        `facts` once it has handled every message sent before)."""
        self._send(msg.Query(token), (role,))

    def facts(self, token: int, role: str = FULL) -> dict | None:
        return self.processes[role].facts.pop(token, None)

    def close(self) -> None:
        self.detach()
        self._closed = True
        for p in self.processes.values():
            with contextlib.suppress(BrokenPipeError, OSError):
                p.conn.send(msg.Quit())
        # a process in the middle of a long frame or light table is killed after a second:
        # it holds nothing of the document's (its derived files are written whole or not at
        # all), and the window closes without waiting for it
        deadline = monotonic() + QUIT_WAIT_S
        for p in self.processes.values():
            try:
                p.process.wait(timeout=max(deadline - monotonic(), 0.0))
            except subprocess.TimeoutExpired:
                p.process.kill()
                p.process.wait(timeout=5)
            with contextlib.suppress(OSError):
                p.conn.close()
            p.release_files()
        if self._session_folder is not None:
            shutil.rmtree(self._session_folder, ignore_errors=True)
