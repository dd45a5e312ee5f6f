"""How the render process (render/render_server.py) orders its work around input: a draft
asked for is drawn whole; a draft drawn again only to show what the process made meanwhile
(slices, light sums) gives way to any message between its passes and is drawn after it,
unless a newer frame is asked for."""

from __future__ import annotations

import numpy as np

from core.stats import FrameStats
from render import render_server
from render.frame_draw import FrameAborted
from render.protocol import FrameRequest
from render.render_server import DRAFT, RenderServer


class _Conn:
    def __init__(self) -> None:
        self.waiting = False  # a message has arrived
        self.sent: list = []

    def poll(self, _timeout: float = 0.0) -> bool:
        return self.waiting

    def send(self, message) -> None:
        self.sent.append(message)


class _Pipeline:
    """Asks `abort` before its one pass, as render/frame.py does before each."""

    def __init__(self) -> None:
        self.drawn = 0

    def render(self, camera, fbo, size, measure, half_resolution, abort, draft=False) -> FrameStats:
        if abort is not None and abort():
            raise FrameAborted
        self.drawn += 1
        return FrameStats(width=size[0], height=size[1])

    def missing(self) -> list:
        return []

    def stale_light_sums(self) -> bool:
        return False


def _server(monkeypatch) -> RenderServer:
    server = RenderServer.__new__(RenderServer)  # no GL context: the order of work alone
    server.conn, server.role, server.pipeline = _Conn(), DRAFT, _Pipeline()
    server.request, server.refine, server.waiting_ack = None, False, False
    server.shots = []
    server._target = lambda size: None
    server._send_frame = lambda request, image, stats, extra=None: server.conn.send(request)
    monkeypatch.setattr(render_server.context, "read_rgb", lambda fbo, size, n: np.zeros(1))
    return server


def _request(**extra) -> FrameRequest:
    return FrameRequest(0, None, (80, 60), **extra)


def test_a_draft_asked_for_is_drawn_whole_while_messages_wait(monkeypatch):
    server = _server(monkeypatch)
    server.conn.waiting = True
    server.draw(_request())
    assert server.pipeline.drawn == 1 and len(server.conn.sent) == 1


def test_a_draft_drawn_again_gives_way_to_input_and_comes_back(monkeypatch):
    server = _server(monkeypatch)
    again = _request(again=True)
    server.conn.waiting = True  # input arrived as it began
    server.draw(again)
    assert server.pipeline.drawn == 0 and not server.conn.sent
    assert server.request is again  # drawn after the message …
    server.request = None
    newer = _request()
    server.request = newer
    server.draw(again)
    assert server.request is newer  # … unless the message asked for a newer frame
    server.conn.waiting = False
    server.draw(again)
    assert server.pipeline.drawn == 1


def test_a_screenshot_is_not_replaced_by_a_live_frame_asked_for_after_it(monkeypatch):
    """Save image waits for its screenshot: a live frame asked for before the process got to
    it (the overlay put back, the camera moved) used to take its place, and the window waited
    ten minutes."""
    server = _server(monkeypatch)
    shot = _request(purpose="screenshot")
    live, newer = _request(), _request(again=True)
    for message in (shot, live, newer):
        server.handle(message)
    assert server.next_request() is shot
    assert server.next_request() is newer  # live frames: the newest only
    assert not server.shots and server.request is None
