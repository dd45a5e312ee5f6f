"""A frame's cost predicted from what the LOD query drew (`sward tune --workers/--ray`): when a
sweep's frames are drawn in several processes at once, their times tell little about one frame
on this machine, so the search predicts each candidate's time from its counts with a linear
model fitted to frames measured here one at a time.

    t ≈ a · blade triangles + b · volume instances × slices + c · image-based instances + d

Each term is work the renderer does per frame (thesis ch. 7 times the three techniques apart:
geometry by its triangles, the volume renderer by instances and ray steps through the slices,
one quad per image-based cell); d is the rest (ground, props, resolving). No coefficient may
be negative: a term that would fit below zero is dropped and the rest fitted again."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

FEATURES = ("triangles", "volume_slices", "c_i")


def features(counts: dict) -> list[float]:
    return [float(counts.get(name, 0)) for name in FEATURES] + [1.0]


@dataclass(frozen=True)
class CostModel:
    coefficients: tuple[float, ...]  # per FEATURES, then the constant (ms)
    loo_error: float  # mean |predicted - measured| / measured, each point left out of its fit
    points: int

    @classmethod
    def fit(cls, counts: list[dict], times_ms: list[float]) -> CostModel:
        """The model of these frames; needs at least two."""
        if len(counts) != len(times_ms) or len(counts) < 2:
            raise ValueError("a cost model needs at least two measured frames")
        x = np.array([features(c) for c in counts])
        y = np.asarray(times_ms, dtype=float)
        coefficients = _non_negative_fit(x, y)
        errors = []
        for i in range(len(y)):
            keep = np.arange(len(y)) != i
            c = _non_negative_fit(x[keep], y[keep])
            errors.append(abs(float(x[i] @ c) - y[i]) / max(y[i], 1e-9))
        return cls(tuple(float(v) for v in coefficients), float(np.mean(errors)), len(y))

    def predict(self, counts: dict) -> float:
        return float(np.dot(features(counts), self.coefficients))

    def to_dict(self) -> dict:
        return {
            "terms": [*FEATURES, "constant"],
            "coefficients_ms": list(self.coefficients),
            "leave_one_out_error": self.loo_error,
            "points": self.points,
        }


def _non_negative_fit(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Least squares with every coefficient ≥ 0: terms that fit negative leave, one at a
    time (the most negative first), until none does. Columns that never vary (a scene with no
    image-based level) get 0."""
    active = [j for j in range(x.shape[1]) if np.ptp(x[:, j]) > 0 or j == x.shape[1] - 1]
    while True:
        solution = np.zeros(x.shape[1])
        if active:
            # scaled columns: triangles run to millions where instances run to hundreds
            scale = np.maximum(np.abs(x[:, active]).max(axis=0), 1e-12)
            fitted, *_ = np.linalg.lstsq(x[:, active] / scale, y, rcond=None)
            solution[active] = fitted / scale
        negative = [j for j in active if solution[j] < 0]
        if not negative:
            return solution
        active.remove(min(negative, key=lambda j: solution[j]))
