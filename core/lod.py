"""Level-of-detail zones and seamless transitions (thesis 3.2, 5.4).

Zones by camera distance: geometry near, volume mid-range, image-based far. Around each zone
boundary b lies a transition zone [b − t/2, b + t/2] where a cell is drawn by BOTH
representations: the near one keeps the blades with threshold / ld ≤ w(d), the far one the rest
(eqs. 5.23-5.25), and a smoothstep window ε blends the few blades crossing over (eq. 5.26), so
every blade is visible exactly once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.grid import INSTANCE_DTYPE

REPRESENTATIONS = ("geometry", "volume", "image")
ALL_IN = 2.0  # w for a cell wholly inside one zone: every blade passes eq. 5.26's window


def linearstep(e1: float, e2: float, x):
    return np.clip((np.asarray(x, dtype=np.float64) - e1) / (e2 - e1), 0.0, 1.0)


def smoothstep(e1, e2, x):
    t = np.clip((np.asarray(x, dtype=np.float64) - e1) / (e2 - e1), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def weight_near(d, e1: float, e2: float):
    """w_1(d) = 1 − linearstep(e1, e2, d) (eq. 5.23); w_2 = 1 − w_1 (eq. 5.24)."""
    return 1.0 - linearstep(e1, e2, d)


def opacity(threshold, w, local_density: float, epsilon: float, far: bool):
    """opacity_s (eq. 5.26) for the near representation; 1 − that for the far one."""
    x = np.asarray(threshold, dtype=np.float64) / max(local_density, 1e-6)
    epsilon = max(epsilon, 1e-4)  # as the shader: smoothstep needs e1 < e2
    near = 1.0 - smoothstep(w - epsilon, w + epsilon, x)
    near = np.where(x <= 1.0, near, 0.0)  # above the local density: no representation
    return np.where(x <= 1.0, 1.0 - near, 0.0) if far else near


@dataclass(frozen=True)
class LodConfig:
    """Zone boundaries in world units (one cell = 1). A boundary of None leaves the level out."""

    geometry_end: float | None = 3.0
    volume_end: float | None = 6.0
    transition: float = 1.0
    epsilon: float = 0.05

    def __post_init__(self) -> None:
        ends = [e for e in (self.geometry_end, self.volume_end) if e is not None]
        if any(e <= 0 for e in ends) or ends != sorted(ends):
            raise ValueError("LOD zone ends must be positive and increasing")
        if self.transition < 0 or not 0 <= self.epsilon < 0.5:
            raise ValueError("transition must be >= 0 and epsilon in [0, 0.5)")

    def boundaries(self) -> list[tuple[str, str, float]]:
        """(near representation, far representation, boundary distance) in order."""
        levels = ["geometry"]
        ends = []
        if self.geometry_end is not None:
            ends.append(self.geometry_end)
            levels.append("volume")
        if self.volume_end is not None:
            ends.append(self.volume_end)
            levels.append("image")
        if self.geometry_end is None and self.volume_end is not None:
            levels = ["geometry", "image"]
        return [(levels[i], levels[i + 1], ends[i]) for i in range(len(ends))]


def select(instances: np.ndarray, eye, config: LodConfig) -> dict[str, np.ndarray]:
    """Split cell instances between the representations by the distance of each cell centre to
    the eye; cells in a transition zone go to both, with w and the side in `lod`."""
    centre = instances["origin"] + 0.5
    d = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
    out: dict[str, list[np.ndarray]] = {r: [] for r in REPRESENTATIONS}
    lower = np.full(d.shape, -np.inf)
    bounds = config.boundaries()
    for near, far, b in bounds:
        e1, e2 = b - config.transition / 2, b + config.transition / 2
        inside = (d >= lower) & (d < e1)
        out[near].append(_with_lod(instances[inside], ALL_IN, 0.0))
        band = (d >= e1) & (d < e2)
        w = weight_near(d[band], e1, e2) if config.transition > 0 else np.zeros(band.sum())
        out[near].append(_with_lod(instances[band], w, 0.0))
        out[far].append(_with_lod(instances[band], w, 1.0))
        lower = np.full(d.shape, e2)
    if bounds:  # beyond the last transition: the farthest representation alone
        out[bounds[-1][1]].append(_with_lod(instances[d >= lower], -1.0, 1.0))
    else:
        out["geometry"].append(_with_lod(instances, ALL_IN, 0.0))
    return {r: np.concatenate(v) if v else np.zeros(0, INSTANCE_DTYPE) for r, v in out.items()}


def _with_lod(instances: np.ndarray, w, side: float) -> np.ndarray:
    out = instances.copy()
    out["lod"][:, 0] = w
    out["lod"][:, 1] = side
    return out
