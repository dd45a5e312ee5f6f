"""The render process: its own standalone EGL context and frame pipeline, running the same
render/ code as `sward render`, fed the document and its changes over a pipe, drawing the newest
camera and handing frames back through a memory-mapped file (render/render_client.py starts it).

The designer runs two of these (DESIGN.md: the window's thread never draws GL):
- `draft`: a cheap frame for every change — a quarter of the resolution, no multisampling,
  slices made after the first draft that needs them (the draft after a blade edit shows the new
  blades at once and the new slices one draft later);
- `full`: full-quality frames at a lower scheduling priority (nice 10), so drafts win the CPU;
  a full frame that newer input has made stale is abandoned between its passes. It also draws
  the Quality view's frames: the LOD frame against an all-geometry reference of the same
  camera (core/quality.py), the difference as a heat map, given up like a stale frame.

Every message a process has not yet handled is applied before it draws, so requests coalesce:
only the newest camera is drawn, never the positions in between.
"""

from __future__ import annotations

import contextlib
import os
import time
import traceback
from dataclasses import replace

import numpy as np
from threadpoolctl import threadpool_limits

from core.design_maps import LAYER_INDEX, LAYERS
from core.project_file import document_data, document_from_data
from core.view_mode import ViewMode
from render import context
from render import protocol as msg
from render.binding import DocumentBinding
from render.comparison import lod_against_geometry
from render.frame import FramePipeline
from render.frame_draw import FrameAborted
from render.mapped import MappedArray
from render.process_start import DRAFT, FULL
from render.slices import SliceTextures

DRAFT_SCALE = 4  # drafts are drawn at 1 / 4 of the width and height
FULL_NICE = 10
# The draft process makes what a draft lacked (slices, light sums) once the window has asked
# for no frame this long: the full-quality process makes the same for its frame at a lower priority, and
# on a CPU renderer the two shared the cores, so the full frame after a blade edit (and the
# first one after start) waited for both.
REFINE_IDLE_S = 1.0
REFINE_WAIT_S = 3.0  # but no longer than this after the draft that lacked them (the wind asks on)
RETRY_S = 0.1  # how often the draft process looks for sums the full process is building


def _yield_to_others() -> None:
    """Every thread of this process (llvmpipe's too) runs only when no other process wants a
    core (SCHED_IDLE, Linux): the full process after its first frame, so that a full frame
    made stale by new input takes nothing from the draft that answers it (nice 10 alone still
    left it a share). Before its first frame it keeps nice 10: the window building its
    widgets must not hold back the start."""
    if not hasattr(os, "sched_setscheduler"):
        return
    with contextlib.suppress(OSError):
        for task in os.listdir("/proc/self/task"):
            with contextlib.suppress(OSError):
                os.sched_setscheduler(int(task), os.SCHED_IDLE, os.sched_param(0))


class RenderServer:
    def __init__(self, conn, role: str) -> None:
        self.conn = conn
        self.role = role
        self.ctx = context.standalone()
        self.pipeline = FramePipeline(self.ctx, samples=0 if role == DRAFT else 4)
        self.pipeline.auto_convert = role == FULL
        self.pipeline.set_mode(ViewMode.LOD)
        self.document = None
        self.binding: DocumentBinding | None = None
        self.stack: MappedArray | None = None
        self.out: MappedArray | None = None
        self.request: msg.FrameRequest | None = None  # the newest frame asked for
        # screenshots asked for, in order: a newer live frame does not replace one (the window
        # waits for each)
        self.shots: list[msg.FrameRequest] = []
        self.last: msg.FrameRequest | None = None
        self.continuous = False
        self.waiting_ack = False
        self.refine = False  # a draft that lacked slices: convert, then draw it again
        self._asked_at = 0.0  # monotonic() when the window last asked for a frame
        self._lacked_at = 0.0  # monotonic() when a draft first lacked what refine_one makes
        self._retry_at = 0.0  # monotonic() before which refine_one waits for the other process
        self._converting: tuple | None = None  # (what, its conversion's steps) under way
        self._idle = False  # the full process yields the cores to others (_yield_to_others)
        self._targets: dict[tuple[int, int], object] = {}

    # -- messages ----------------------------------------------------------------------------
    def handle(self, message: object) -> bool:
        """Apply one message from the window; False when it says quit."""
        match message:
            case msg.Quit():
                return False
            case msg.Open(data, stack_path, shape):
                self._on_open(data, stack_path, shape)
            case msg.Change(name, args):
                self.document.apply(name, args)
            case msg.MapsChanged(layer, rect):
                self._on_maps(layer, rect)
            case msg.SetMode(mode):
                self.pipeline.set_mode(mode)
            case msg.SetView(view):
                self.pipeline.view = view
            case msg.SetOverlay(group, lines):
                self.pipeline.overlay.set_lines(group, lines)
            case msg.SetLodScale(factor):
                self.pipeline.lod_scale = float(factor)
            case msg.SetContinuous(on):
                self.continuous = bool(on) and self.role == FULL
            case msg.FrameRequest(purpose="screenshot"):
                self.shots.append(message)
            case msg.FrameRequest():
                self.request = message
                self._asked_at = time.monotonic()
            case msg.Ack():
                self.waiting_ack = False
            case msg.Query(token):
                self._on_query(token)
            case _:
                raise ValueError(f"unknown message {message!r}")
        return True

    def _on_open(self, data: dict, stack_path: str, shape: tuple) -> None:
        if self.binding is not None:
            self.binding.detach()
        if self.stack is not None:
            self.stack.close()
        self.stack = MappedArray(stack_path, shape)
        self.conn.send(msg.Mapped(stack_path))
        self.document = document_from_data(data, self.stack.array)
        self.binding = DocumentBinding(self.pipeline, self.document)

    def _on_maps(self, name: str, rect: tuple[int, int, int, int]) -> None:
        if self.document is None:
            return  # the document that follows reads the whole stack
        x, y, w, h = rect
        i = LAYER_INDEX[name]
        values = self.stack.array[i, y : y + h, x : x + w, : LAYERS[i].channels]
        self.document.maps.write(name, x, y, np.array(values))

    def _on_query(self, token: int) -> None:
        p = self.pipeline
        terrain = p.terrain
        facts = {
            "role": self.role,
            "volume_slices": p.slice_params.slices,
            "needs_slices": p.needs_slices,
            "light": p.light,
            "wind": p.wind,
            "lod_scale": p.lod_scale,
            "patch_params": [g.patch.params if g.patch else None for g in p.grass_types],
            "height_scale": terrain.height_scale if terrain is not None else 0.0,
            "terrain_top": terrain.ground_span[1] if terrain is not None else 0.0,
            "prop_boxes": p.props.boxes.copy(),
            # the document this process draws, as a project file holds it
            "document": document_data(self.document) if self.document is not None else None,
        }
        self.conn.send(msg.Facts(token, facts))

    # -- drawing -----------------------------------------------------------------------------
    def _target(self, size: tuple[int, int]):
        if size not in self._targets:
            for old in list(self._targets):
                context.release_framebuffer(self._targets.pop(old))
            self._targets[size] = self.ctx.framebuffer(self.ctx.renderbuffer(size, 4))
        return self._targets[size]

    def _quality(self, camera, fbo, size: tuple[int, int], abort):
        """The frame against an all-geometry reference (render/comparison.py): the heat map of
        their difference (RGBA) and the figures."""
        compared = lod_against_geometry(
            self.pipeline, camera, fbo, size, abort, document=self.document
        )
        heat = compared.heat_map()
        image = np.zeros((size[1], size[0], 4), np.uint8)
        image[: heat.shape[0], : heat.shape[1], :3] = heat
        image[..., 3] = 255
        return image, compared.lod_stats, compared.found

    def draw(self, request: msg.FrameRequest) -> None:
        self.pipeline.time = request.time  # the moment of the wind (viewport.py)
        if request.purpose == "quality":
            self._draw_quality(request)
            return
        w, h = request.size
        draft = self.role == DRAFT and request.purpose == "live"
        if draft:
            w, h = max(1, w // DRAFT_SCALE), max(1, h // DRAFT_SCALE)
        # a full frame, or a draft drawn again to show what refine_one made, gives way to any
        # message between its passes: input waits for no frame it would make stale
        stoppable = self.role == FULL or request.again
        abort = self.conn.poll if stoppable and request.purpose == "live" else None
        fbo = self._target((w, h))
        try:
            # a draft is timed only as a whole: no ctx.finish() bubbles between its passes
            stats = self.pipeline.render(
                request.camera, fbo, (w, h), not draft, False, abort, draft=draft
            )
        except FrameAborted:
            if request.again and self.request is None:
                self.request = request  # after the message, unless a newer frame is asked for
            return
        stats.draft = draft
        stats.state_time = request.state_time
        self._send_frame(request, context.read_rgb(fbo, (w, h), 4), stats)
        if draft and (self.pipeline.missing() or self.pipeline.stale_light_sums()):
            if not self.refine:
                self._lacked_at = time.monotonic()
            self.refine = True

    def _draw_quality(self, request: msg.FrameRequest) -> None:
        size = request.size
        fbo = self._target(size)
        try:
            image, stats, found = self._quality(request.camera, fbo, size, self.conn.poll)
        except FrameAborted:
            # drawn again once the message that stopped it is handled, unless that message
            # asks for a newer frame (which then takes its place)
            if self.request is None:
                self.request = request
            return
        stats.state_time = request.state_time
        self._send_frame(request, image, stats, found)

    def _send_frame(self, request: msg.FrameRequest, image: np.ndarray, stats, extra=None) -> None:
        h, w = image.shape[:2]
        if self.out is None or self.out.path != request.out_path:
            if self.out is not None:
                self.out.close()
            self.out = MappedArray(request.out_path, (request.out_bytes,), np.uint8)
            self.conn.send(msg.Mapped(self.out.path))
        self.out.array[: image.size] = image.reshape(-1)
        self.waiting_ack = True
        self.conn.send(msg.FrameReady(request.version, request.purpose, (w, h), stats, extra))
        if self.role == FULL and not self._idle:
            _yield_to_others()
            self._idle = True

    def refine_one(self) -> bool:
        """The draft process makes what a draft lacked one piece at a time: the slices (a
        capture a call), then the light sums of a patch it drew with those of the patch before
        an edit (or with none). Sums the full process is building are not built twice: they
        are read once it has written them (render/derived_cache.py). Whether a draft would
        now show more."""
        p = self.pipeline
        if not p.missing():
            p.refresh_light_sums(wait=False)
            self.refine = p.stale_light_sums()
            if self.refine:  # the other process builds them: look again a little later
                self._retry_at = time.monotonic() + RETRY_S
                return False
            self.conn.send(msg.Status(""))
            return True
        grass_type, n = p.missing()[0]
        patch = p.grass_types[grass_type].patch
        sp = p.slice_params
        what = (grass_type, n, patch, sp)
        if self._converting is None or self._converting[0] != what:
            self.conn.send(msg.Status(f"converting slices of grass type {grass_type + 1}"))
            steps = p.converter.steps(patch, n, (sp.width, sp.height), sp.top)
            self._converting = (what, steps)
        try:  # one capture at a time: input that comes meanwhile waits for one, not for all
            next(self._converting[1])
            return False
        except StopIteration as done:
            sliced = done.value
        self._converting = None
        p.set_slice_textures(
            SliceTextures.upload(self.ctx, sliced), patch, sp.replace(slices=n), grass_type
        )
        if not p.missing() and not p.stale_light_sums():
            self.refine = False
            self.conn.send(msg.Status(""))
        return True

    def next_request(self) -> msg.FrameRequest:
        """The next frame to draw: the screenshots asked for, in order, then the newest frame
        asked for."""
        if self.shots:
            return self.shots.pop(0)
        request, self.request = self.request, None
        assert request is not None
        return request

    def loop(self) -> None:
        while True:
            asked = self.request is not None or bool(self.shots)
            busy = (asked or self.refine) and not self.waiting_ack
            if not busy or self.conn.poll():
                if not self.handle(self.conn.recv()):
                    return
                while self.conn.poll():
                    if not self.handle(self.conn.recv()):
                        return
                continue
            if self.document is None:
                self.request, self.shots = None, []
                continue
            if asked:
                request = self.next_request()
                if request.purpose != "screenshot":
                    self.last = request
                self.draw(request)
                if self.continuous and request.purpose == "live":
                    self.request = request  # frame after frame, the same state
            elif self.refine:
                now = time.monotonic()
                wait = max(
                    min(
                        REFINE_IDLE_S - (now - self._asked_at),
                        REFINE_WAIT_S - (now - self._lacked_at),
                    ),
                    self._retry_at - now,
                )
                if wait > 0.0 and self.conn.poll(wait):
                    continue  # a message first (a new frame asked for waits for no refinement)
                if self.refine_one() and self.last is not None and self.request is None:
                    self.request = replace(self.last, again=True)


def serve(conn, role: str) -> None:
    """The process's work: answer `conn` until the window quits or goes away."""
    if role == FULL:
        os.nice(FULL_NICE)  # before the GL context: llvmpipe's threads inherit it
    # The designer runs two render processes side by side: each keeps its BLAS (the light sums'
    # matrix products) to half the cores. With every core each, the draft's products took the
    # cores from the niced full process while it built the sums its first frame waits for.
    threadpool_limits(limits=max(1, (os.cpu_count() or 2) // 2), user_api="blas")
    try:
        server = RenderServer(conn, role)
        size = int(server.ctx.info["GL_MAX_RENDERBUFFER_SIZE"])
        conn.send(msg.Hello(os.getpid(), size, context.describe(server.ctx)))
        server.loop()
    except (EOFError, BrokenPipeError, ConnectionResetError, KeyboardInterrupt):
        return  # the window went away
    except Exception:
        try:
            conn.send(msg.Failed(traceback.format_exc(limit=4)))
        except (BrokenPipeError, OSError):
            pass
        raise


if __name__ == "__main__":  # python -m render.render_server ROLE FD (render/render_client.py)
    import sys
    from multiprocessing.connection import Connection

    serve(Connection(int(sys.argv[2])), sys.argv[1])
