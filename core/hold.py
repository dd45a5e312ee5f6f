"""Adaptive LOD (thesis ch. 8, "Adaptive Rendering System"): one factor on every zone's
distances, turned to hold the full-quality frame time at a target.

The controller looks at the median of the last few frames (one slow frame is not a trend),
does nothing while that is within BAND of the target (hysteresis: the zones do not breathe
with the machine's noise), and otherwise moves the factor towards the target by a step that
grows with the miss but never more than STEP_MAX at once, so a zone boundary slides instead of
jumping (popping). Frame cost grows with the geometry zone's area on the ground, about the
square of the factor, hence the square root in the step."""

from __future__ import annotations

import math
import statistics
from collections import deque
from dataclasses import dataclass, field

BAND = 0.08  # no change while the frame time is within this share of the target
STEP_MAX = 1.15  # the factor changes by at most this ratio a frame
FACTOR_LIMITS = (0.1, 4.0)
WINDOW = 3  # frames in the median the controller looks at


@dataclass
class HoldFrameTime:
    target_ms: float
    factor: float = 1.0
    recent: deque = field(default_factory=lambda: deque(maxlen=WINDOW))

    def __post_init__(self) -> None:
        if not (math.isfinite(self.target_ms) and self.target_ms > 0):
            raise ValueError(f"target frame time {self.target_ms:g} ms must be above 0")

    def update(self, frame_ms: float) -> bool:
        """A full-quality frame took `frame_ms` at the current factor: move the factor if the
        frames are off the target. True when it changed (the next frame draws with it)."""
        self.recent.append(frame_ms)
        ratio = statistics.median(self.recent) / self.target_ms
        if abs(ratio - 1.0) <= BAND:
            return False
        step = min(max(ratio**-0.5, 1.0 / STEP_MAX), STEP_MAX)
        low, high = FACTOR_LIMITS
        factor = min(max(self.factor * step, low), high)
        if factor == self.factor:
            return False
        self.factor = factor
        self.recent.clear()  # frames at the old factor say nothing of the new one
        return True
