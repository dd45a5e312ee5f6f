"""Which frames the window asks for and shows (core/frame_schedule.py), driven by a fake clock:
draft before full, stale frames dropped, the wind's moments, the Quality view, screenshots."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from core.frame_schedule import ANIMATION_STEP_S, SHARP_STEP_S, FrameSchedule
from core.stats import FrameStats


class FakeClock:
    def __init__(self) -> None:
        self.t = 100.0
        self.calls: list[list] = []  # [due, callback, live]

    def now(self) -> float:
        return self.t

    def call_later(self, seconds, callback):
        call = [self.t + seconds, callback, True]
        self.calls.append(call)
        return call

    def cancel(self, handle) -> None:
        handle[2] = False

    def advance(self, seconds: float = 0.0) -> None:
        """Let `seconds` pass, running every call that falls due, in order."""
        end = self.t + seconds
        while True:
            due = [c for c in self.calls if c[2] and c[0] <= end]
            if not due:
                break
            call = min(due, key=lambda c: c[0])
            call[2] = False
            self.t = max(self.t, call[0])
            call[1]()
        self.t = end


@dataclass
class Frame:
    version: int
    purpose: str
    stats: FrameStats
    figures: dict | None = None
    image: object = None


@dataclass
class Renderer:
    asked: list = field(default_factory=list)

    def request(self, version, camera, size, purpose="live", time=0.0, draft=True) -> None:
        self.asked.append((version, purpose, round(time, 6), draft))


def make():
    clock, renderer, shown, quality = FakeClock(), Renderer(), [], []
    schedule = FrameSchedule(
        renderer,
        lambda: ("camera", (80, 60)),
        clock,
        on_show=shown.append,
        on_quality=quality.append,
    )
    return schedule, clock, renderer, shown, quality


def live(version: int, draft: bool, ms: float = 50.0) -> Frame:
    return Frame(version, "live", FrameStats(t_a_ms=ms, draft=draft))


def test_changes_in_one_turn_are_asked_for_once_and_stale_frames_are_dropped():
    s, clock, renderer, shown, _ = make()
    s.changed()
    s.changed()
    s.changed()
    assert renderer.asked == []  # asked on the next turn of the event loop
    clock.advance()
    assert renderer.asked == [(3, "live", 0.0, True)]
    s.arrived(live(3, draft=False))  # the full frame came before its draft
    s.arrived(live(3, draft=True))  # a draft of a state shown in full: dropped
    s.arrived(live(2, draft=False))  # older than what is on screen: dropped
    assert [(f.version, f.stats.draft) for f in shown] == [(3, False)]
    assert not s.settling
    s.changed()
    assert s.settling  # until the new state's full frame is shown
    clock.advance()
    s.arrived(live(4, draft=True))
    assert s.settling and shown[-1].version == 4
    s.arrived(live(4, draft=False))
    assert not s.settling


def test_the_wind_moves_on_after_each_full_frame_or_after_a_step():
    s, clock, renderer, _, _ = make()
    s.set_wind(True)
    s.changed()
    clock.advance()
    assert renderer.asked[-1] == (1, "live", 0.0, True)
    clock.advance(0.1)
    s.arrived(live(1, draft=True))  # a draft: the full frame is awaited
    clock.advance()
    assert len(renderer.asked) == 1
    s.arrived(live(1, draft=False))  # the full frame: the next moment at once
    clock.advance()
    assert renderer.asked[-1] == (2, "live", 0.1, True)
    clock.advance(ANIMATION_STEP_S)  # no frame comes: the wind moves on after a step
    assert renderer.asked[-1] == (3, "live", 0.1 + ANIMATION_STEP_S, True)
    s.set_wind(False)  # held still: no more moments
    held = s.wind_time
    clock.advance(5.0)
    assert len(renderer.asked) == 3 and s.wind_time == held
    s.set_wind(True)  # on from the moment it was held at
    s.changed()
    clock.advance()
    assert renderer.asked[-1][2] == pytest.approx(held)


def test_slow_full_frames_let_drafts_carry_the_wind_and_sharp_frames_wait_for_full_ones():
    s, clock, renderer, _, _ = make()
    s.set_wind(True)
    s.changed()
    clock.advance()
    s.arrived(live(1, draft=False, ms=1000.0 * ANIMATION_STEP_S + 400.0))  # a slow renderer
    clock.advance()
    assert s.wind_on_drafts  # the status line says no full frame follows the drafts
    s.arrived(live(2, draft=True))  # a draft is enough to move on
    s.sharp_wind = True
    assert not s.wind_on_drafts
    clock.advance()
    assert [a[0] for a in renderer.asked] == [1, 2, 3]
    s.arrived(live(3, draft=True))  # sharp frames: a draft moves nothing
    clock.advance(ANIMATION_STEP_S)
    assert len(renderer.asked) == 3
    s.arrived(live(3, draft=False))
    clock.advance()
    assert renderer.asked[-1][0] == 4 and renderer.asked[-1][3] is False  # asked with no draft
    clock.advance(SHARP_STEP_S)  # only a full frame that never comes moves it on
    assert renderer.asked[-1][0] == 5


def test_the_quality_view_asks_once_the_view_rests_and_holds_the_wind():
    s, clock, renderer, _, quality = make()
    s.set_wind(True)
    s.changed()
    clock.advance(0.1)
    s.set_quality(True)
    assert not s.animating  # held while the Quality view is on
    s.arrived(live(1, draft=False))
    assert renderer.asked[-1] == (1, "quality", 0.1, True)
    s.arrived(live(1, draft=False))  # asked once per state
    assert sum(a[1] == "quality" for a in renderer.asked) == 1
    s.arrived(Frame(1, "quality", FrameStats(), {"flip": 0.1}))
    assert quality[-1].figures == {"flip": 0.1} and s.quality_figures == {"flip": 0.1}
    s.changed()  # a new state: the old figures no longer describe the frame shown
    clock.advance()
    s.arrived(live(2, draft=False))
    assert s.quality_figures is None
    s.arrived(Frame(1, "quality", FrameStats(), {"flip": 0.2}))  # stale: dropped
    assert len(quality) == 1
    s.set_quality(False)
    assert s.animating  # the wind blows on


def test_screenshots_wait_under_their_own_token():
    s, _, renderer, shown, _ = make()
    token = s.ask_screenshot("camera", (4000, 3000))
    assert token < 0 and renderer.asked[-1][:2] == (token, "screenshot")
    s.arrived(Frame(token, "screenshot", FrameStats()))
    assert token in s.screenshots and shown == []
