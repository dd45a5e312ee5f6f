"""Painting by rule: a brush mask by the ground's slope and height (the placement rules terrain
tools offer: tall grass below 20° and above the river). Each texel of the design maps gets a
weight 0 … 1, how far the rule holds there, with a soft edge; a stroke's dabs and "fill by rule"
are scaled by it (core/brush.py), and the Map dock shows it.

Slope and height are the ground's at the texel: the height map times the terrain's height
scale (world units), its slope from the differences to the neighbouring texels over their
distance on the ground (a cell is one world unit; the maps span the whole terrain)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PaintRule:
    """Where painting takes: slope between `slope` degrees, height between `height` world units
    (None: anywhere), each edge softened over `soft_slope` degrees and `soft_height` units."""

    slope: tuple[float, float] | None = None
    height: tuple[float, float] | None = None
    soft_slope: float = 2.0
    soft_height: float = 0.1

    def __post_init__(self) -> None:
        if self.slope is not None:
            lo, hi = self.slope
            if not 0.0 <= lo <= hi <= 90.0:
                raise ValueError(f"slope {lo:g} … {hi:g}°: from 0 to 90°, the least first")
        if self.height is not None:
            lo, hi = self.height
            if not (np.isfinite(lo) and np.isfinite(hi) and lo <= hi):
                raise ValueError(f"height {lo:g} … {hi:g}: the least first")
        if not 0.0 <= self.soft_slope <= 45.0:
            raise ValueError(f"soft slope edge {self.soft_slope:g}° out of range; 0 … 45°")
        if not 0.0 <= self.soft_height <= 1.0e4:
            raise ValueError(f"soft height edge {self.soft_height:g} out of range; 0 … 10000")

    @property
    def active(self) -> bool:
        return self.slope is not None or self.height is not None

    def to_dict(self) -> dict:
        return {
            "slope": None if self.slope is None else list(self.slope),
            "height": None if self.height is None else list(self.height),
            "soft_slope": self.soft_slope,
            "soft_height": self.soft_height,
        }

    @classmethod
    def from_dict(cls, data: dict) -> PaintRule:
        def pair(value) -> tuple[float, float] | None:
            return None if value is None else (float(value[0]), float(value[1]))

        return cls(
            pair(data.get("slope")),
            pair(data.get("height")),
            float(data.get("soft_slope", 2.0)),
            float(data.get("soft_height", 0.1)),
        )


def ground_slope(heights: np.ndarray, spacing: tuple[float, float]) -> np.ndarray:
    """Slope in degrees at each texel of a (rows, columns) height field in world units, texels
    `spacing` (x, z) world units apart (central differences, one-sided at the border)."""
    h = np.asarray(heights, np.float64)
    dz = np.gradient(h, spacing[1], axis=0) if h.shape[0] > 1 else np.zeros_like(h)
    dx = np.gradient(h, spacing[0], axis=1) if h.shape[1] > 1 else np.zeros_like(h)
    return np.degrees(np.arctan(np.hypot(dx, dz)))


def _band(values: np.ndarray, lo: float, hi: float, soft: float) -> np.ndarray:
    """1 inside lo … hi, falling smoothly to 0 over `soft` outside it."""
    if soft <= 0:
        return ((values >= lo) & (values <= hi)).astype(np.float64)
    outside = np.maximum(lo - values, values - hi) / soft  # ≤ 0 inside
    x = np.clip(1.0 - outside, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def rule_mask(
    rule: PaintRule, height01: np.ndarray, height_scale: float, terrain: tuple[int, int]
) -> np.ndarray:
    """(rows, columns) float32 weights of the rule over the maps: `height01` the height map
    (0 … 1), `terrain` its (columns, rows) of cells."""
    rows, columns = height01.shape
    out = np.ones((rows, columns))
    heights = np.asarray(height01, np.float64) * height_scale
    if rule.slope is not None:
        spacing = (terrain[0] / columns, terrain[1] / rows)
        out *= _band(ground_slope(heights, spacing), *rule.slope, rule.soft_slope)
    if rule.height is not None:
        out *= _band(heights, *rule.height, rule.soft_height)
    return out.astype(np.float32)
