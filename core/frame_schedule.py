"""Which frames the window asks its render processes for, and which of those it shows: Qt-free,
driven by a clock it is given (the viewport passes Qt's timers, tests a fake clock).

- Every change of state counts one `version`; changes within one turn of the event loop are
  asked for once. A live frame comes as a draft first, then at full quality; a frame older than
  the one on screen, or a draft of a state already shown in full, is dropped.
- While the document's wind blows, each state asked for carries the moment of the wind (seconds
  of wind since it started blowing here), and the next moment is asked for as soon as the full
  frame of the last one is shown, or after ANIMATION_STEP_S when that frame is slower. Where a
  full frame takes longer than that (a CPU renderer), the wind moves on as soon as the draft of
  the last moment is shown: it moves as fast as drafts come. With `sharp_wind` a new moment
  waits for the full frame of the last one and is asked for without a draft. Switching the
  wind off holds the grass still, and so does the Quality view while it is on (its
  all-geometry reference takes seconds: the next moment would give it up).
- The Quality view: once a full frame of the newest state is shown, the full-quality process
  draws the LOD frame against an all-geometry reference of the same camera; any change gives
  it up, and it is asked for again when the view rests.
- Screenshots are full frames of any size, asked for under a negative token.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

ANIMATION_STEP_S = 0.25  # the longest wait for a full frame before the wind moves on
SHARP_STEP_S = 10.0  # with sharp wind frames: moves on only if a full frame never comes


class Clock(Protocol):
    def now(self) -> float: ...

    def call_later(self, seconds: float, callback: Callable[[], None]) -> object:
        """Call `callback` once after `seconds` (0: on the next turn); a handle for `cancel`."""
        ...

    def cancel(self, handle: object) -> None: ...


Frame = Any  # render/render_client.py Frame: version, purpose, image, stats, figures


class Requests(Protocol):
    """The render processes' side the schedule asks (render/render_client.py RenderClient)."""

    def request(self, version, camera, size, purpose="live", time=0.0, draft=True) -> None: ...


class FrameSchedule:
    def __init__(
        self,
        requests: Requests,
        view: Callable[[], tuple[object, tuple[int, int]]],
        clock: Clock,
        *,
        on_show: Callable[[Frame], None] = lambda frame: None,
        on_quality: Callable[[Frame], None] = lambda frame: None,
        on_quality_asked: Callable[[], None] = lambda: None,
        before_request: Callable[[], None] = lambda: None,
    ) -> None:
        self.requests = requests
        self.view = view  # () -> (camera, size in pixels) of the view now
        self.clock = clock
        self.on_show = on_show  # a live frame to paint
        self.on_quality = on_quality  # the Quality view's heat map and figures of the newest state
        self.on_quality_asked = on_quality_asked  # its reference is being drawn
        self.before_request = before_request  # the viewport's overlays, just before asking
        self.version = 0  # the states asked for
        self.shown = (0, True)  # (version, draft) of the frame on screen
        self._draft = False  # whether the state asked for next needs a draft first
        self._pending = False
        self.wind_time = 0.0  # the moment of the wind drawn
        self._wind_clock: float | None = None  # clock time at wind_time 0; None: held still
        self._wind_blows = False
        self._step: object | None = None  # the call that moves the wind on if no frame comes
        self.sharp_wind = False
        self._full_ms = 0.0  # how long the last full-quality frame took
        self.quality = False
        self.quality_frame: Frame | None = None  # the newest Quality view frame
        self._quality_asked = 0  # the version a quality frame was last asked for
        self._token = 0  # screenshots (negative: never a live version)
        self.screenshots: dict[int, Frame] = {}

    # -- state -------------------------------------------------------------------------------
    @property
    def settling(self) -> bool:
        """True until a full-quality frame of the newest state is shown."""
        return self.shown != (self.version, False)

    @property
    def animating(self) -> bool:
        """True while the wind blows and the view follows it."""
        return self._wind_clock is not None

    @property
    def wind_on_drafts(self) -> bool:
        """True while the wind moves on with drafts alone: full frames are too slow to follow
        it (and sharp wind frames are off)."""
        return self.animating and not self.sharp_wind and self._full_ms > 1000.0 * ANIMATION_STEP_S

    @property
    def quality_figures(self) -> dict | None:
        """The Quality view's figures for the frame shown (None until they are drawn)."""
        frame = self.quality_frame
        return frame.figures if frame is not None and frame.version == self.shown[0] else None

    # -- what changes ------------------------------------------------------------------------
    def changed(self, draft: bool = True) -> None:
        """The state changed: ask for a frame of it (once per turn of the event loop); a draft
        comes first unless only the wind moved on with sharp wind frames."""
        self.version += 1
        self._draft = self._draft or draft
        if not self._pending:
            self._pending = True
            self.clock.call_later(0.0, self._send)

    def set_wind(self, blows: bool) -> None:
        """The document's wind was switched on or off."""
        self._wind_blows = blows
        self._follow_wind()

    def set_quality(self, on: bool) -> None:
        """The Quality view on or off: it holds the wind at its moment while on."""
        self.quality = on
        self.quality_frame, self._quality_asked = None, 0
        blew = self.animating
        self._follow_wind()
        if self.animating and not blew:
            self.changed()  # on again from the moment it was held at
        self._ask_quality()

    def _follow_wind(self) -> None:
        blows = self._wind_blows and not self.quality
        if blows and self._wind_clock is None:
            self._wind_clock = self.clock.now() - self.wind_time  # on from where it stopped
        elif not blows and self._wind_clock is not None:
            self.wind_time = self.clock.now() - self._wind_clock
            self._wind_clock = None
            self._cancel_step()

    def _cancel_step(self) -> None:
        if self._step is not None:
            self.clock.cancel(self._step)
            self._step = None

    def _next_moment(self) -> None:
        self._step = None
        if self.animating:
            self.changed(draft=not self.sharp_wind)

    def stop(self) -> None:
        """The window closes: no more moments."""
        self._cancel_step()
        self._wind_clock = None

    # -- asking ------------------------------------------------------------------------------
    def _send(self) -> None:
        self._pending = False
        self.before_request()
        if self._wind_clock is not None:
            self.wind_time = self.clock.now() - self._wind_clock
            self._cancel_step()  # the next moment, unless the frame comes first
            wait = SHARP_STEP_S if self.sharp_wind else ANIMATION_STEP_S
            self._step = self.clock.call_later(wait, self._next_moment)
        draft, self._draft = self._draft, False
        camera, size = self.view()
        self.requests.request(self.version, camera, size, time=self.wind_time, draft=draft)

    def _ask_quality(self) -> None:
        if self.quality and not self.settling and self._quality_asked != self.version:
            self._quality_asked = self.version
            self.on_quality_asked()
            camera, size = self.view()
            self.requests.request(
                self.version, camera, size, purpose="quality", time=self.wind_time
            )

    def ask_screenshot(self, camera, size: tuple[int, int]) -> int:
        """A full frame of the current state at any size; its token for `screenshots`."""
        self._token -= 1
        self.requests.request(self._token, camera, size, purpose="screenshot", time=self.wind_time)
        return self._token

    def new_token(self) -> int:
        self._token -= 1
        return self._token

    # -- what arrives ------------------------------------------------------------------------
    def arrived(self, frame: Frame) -> None:
        """A frame from a render process: kept, shown, or dropped."""
        if frame.purpose == "screenshot":
            self.screenshots[frame.version] = frame
            return
        if frame.purpose == "quality":
            if self.quality and frame.version == self.version:
                self.quality_frame = frame
                self.on_quality(frame)
            return
        key = (frame.version, frame.stats.draft)
        if frame.version < self.shown[0] or (key[0] == self.shown[0] and key[1] > self.shown[1]):
            return  # older than what is on screen, or a draft of a state shown in full
        self.shown = key
        if not frame.stats.draft:
            self._full_ms = frame.stats.t_a_ms
        self.on_show(frame)
        # the full frame is shown, or a draft where full frames are too slow to follow the
        # wind: the next moment now
        if (
            frame.version == self.version
            and self.animating
            and (not frame.stats.draft or self.wind_on_drafts)
        ):
            self._cancel_step()
            self._step = self.clock.call_later(0.0, self._next_moment)
        self._ask_quality()
