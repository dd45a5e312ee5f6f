"""Adaptive LOD in the designer (View → Hold frame rate…): the viewport's full-quality frames
feed core/hold.py's controller, and the one factor it turns on every zone's distances goes to
both render processes (so drafts draw the same zones) and to the zone rings."""

from __future__ import annotations

from core.hold import HoldFrameTime
from core.stats import FrameStats
from render import protocol as msg


class ZoneScale:
    def __init__(self, viewport) -> None:
        self.viewport = viewport
        self.hold: HoldFrameTime | None = None

    @property
    def factor(self) -> float:
        return 1.0 if self.hold is None else self.hold.factor

    def set_target(self, target_ms: float | None) -> None:
        """Hold full frames at `target_ms` from now on; None: the zones as set."""
        self.hold = None if target_ms is None else HoldFrameTime(target_ms)
        self._send()

    def shown(self, stats: FrameStats) -> None:
        """A frame is on screen: a full-quality one moves the factor when it is off target."""
        if self.hold is not None and not stats.draft and self.hold.update(stats.t_a_ms):
            self._send()

    def describe(self) -> str:
        if self.hold is None:
            return ""
        return f"holding {self.hold.target_ms:.0f} ms: zones ×{self.hold.factor:.2f}"

    def _send(self) -> None:
        vp = self.viewport
        vp.renderer.set_view_state(msg.SetLodScale(self.factor))
        vp.request_frame(draft=False)  # the zones slid a little: no draft first
