"""Level-of-detail zones and seamless transitions (thesis 3.2, 5.4).

Zones by camera distance: geometry near, volume mid-range, image-based far. Around each zone
boundary b lies a transition zone [b − t/2, b + t/2] where a cell is drawn by BOTH
representations: the near one keeps the blades with threshold / ld ≤ w(d), the far one the rest
(eqs. 5.23-5.25), and a smoothstep window ε blends the few blades crossing over (eq. 5.26), so
every blade is visible exactly once.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass

import numpy as np

from core.segments import TOLERANCE_PX

REPRESENTATIONS = ("geometry", "volume", "image")
REFERENCE_FOV = 50.0  # degrees: the field of view a LodConfig's view_height is taken at
ALL_IN = 2.0  # w for a cell wholly inside one zone: every blade passes eq. 5.26's window


def linearstep(e1: float, e2: float, x):
    """0 below e1, 1 above e2, linear between; with e1 = e2 (a level ending where the next
    begins: no transition) a step at e1."""
    x = np.asarray(x, dtype=np.float64)
    if e2 <= e1:
        return np.where(x < e1, 0.0, 1.0)
    return np.clip((x - e1) / (e2 - e1), 0.0, 1.0)


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


def shown_thresholds(density, lod, epsilon: float) -> tuple[np.ndarray, np.ndarray]:
    """Per cell (`density` its local density, `lod` its (w, far) pair), the thresholds lo … hi
    outside which `opacity` is 0: the blades a representation can show there. The bounds
    reach a little beyond the exact ones, for a shader computing in float32."""
    d = np.asarray(density, dtype=np.float64)
    lod = np.asarray(lod, dtype=np.float64).reshape(-1, 2)
    w, far = lod[:, 0], lod[:, 1] >= 0.5
    epsilon = max(epsilon, 1e-4)
    near_hi = d * np.clip(w + epsilon, 0.0, 1.0)
    lo = np.where(far, d * np.clip(w - epsilon, 0.0, 1.0), 0.0)
    hi = np.where(far, d, near_hi)
    return lo * (1.0 - 1e-5) - 1e-7, hi * (1.0 + 1e-5) + 1e-7


SPREAD_WIDTH = 12.0**0.5  # a uniform distribution's width over its standard deviation


def share(threshold, spread, w, local_density: float, epsilon: float, far: bool):
    """The share of a slice texel's blades that a representation keeps (eq. 5.26 over many
    blades): a texel of a reduced mip level stands for blades whose thresholds have the mean
    `threshold` and the standard deviation `spread` (render/slices.py), taken as uniform over
    an interval of width √12 · spread, clipped to the thresholds' range 0 … 1 (so a bare cell
    keeps none). Of them the texel keeps those below the local density, the near
    representation those below w · density as well (the window ε widening the crossover), the
    far one the rest; near + far = kept. A spread of 0 is `opacity`: one blade."""
    d = max(local_density, 1e-6)
    t = np.asarray(threshold, dtype=np.float64)
    half = 0.5 * SPREAD_WIDTH * np.asarray(spread, dtype=np.float64)
    lo, hi = np.maximum(t - half, 0.0), np.minimum(t + half, 1.0)
    width = np.maximum(hi - lo, 1e-4)
    kept = np.clip((d - lo) / width, 0.0, 1.0)
    window = max(epsilon, 1e-4) * d  # eq. 5.26's ε, in thresholds
    reach = np.sqrt((0.5 * width) ** 2 + window**2)
    r = np.clip((0.5 * (lo + hi) - (w * d - reach)) / (2.0 * reach), 0.0, 1.0)
    linear = width / (width + 2.0 * window)  # uniform thresholds: a ramp; one blade: the window
    near = np.minimum(1.0 - (linear * r + (1.0 - linear) * r * r * (3.0 - 2.0 * r)), kept)
    return kept - near if far else near


@dataclass(frozen=True)
class LodLevel:
    """One level of detail: a representation drawn from `begin` to `end` (world units from the
    eye). Consecutive levels overlap: between the next level's begin and this level's end lies
    their transition zone (thesis 5.4 and ch. 7: "geometry to 20, volume 5-80, ...")."""

    representation: str
    begin: float = 0.0
    end: float | None = None  # None: to the horizon
    slices: int = 8  # vertical slices per direction (volume)
    macro: int = 1  # largest macro-cell edge in cells (volume, image-based; thesis 6.2)
    # macro-cells only where the ground's height range is at most this (6.4.4); None: anywhere
    max_unplanarity: float | None = None

    def __post_init__(self) -> None:
        if self.representation not in REPRESENTATIONS:
            raise ValueError(
                f"LOD representation {self.representation!r} is not one of "
                f"{', '.join(REPRESENTATIONS)}"
            )
        if self.begin < 0 or (self.end is not None and self.end <= self.begin):
            raise ValueError(f"LOD level {self.representation}: needs 0 <= begin < end")
        if self.macro < 1 or self.macro & (self.macro - 1):
            raise ValueError(f"LOD level {self.representation}: macro-cell size must be 1, 2, 4, …")
        if self.representation == "geometry" and self.macro != 1:
            raise ValueError("geometry draws no macro-cells (thesis 6.2)")

    @property
    def key(self) -> tuple[str, int]:
        """What a renderer needs to draw the level: volume levels differ in their slices."""
        return (self.representation, self.slices if self.representation == "volume" else 0)


# with the wind's blade_reach: the blades run on at least this share of the distance past the
# next representation's begin (core/wind.py)
HAND_OVER_BAND = 0.05


def _called(index: int, level: LodLevel) -> str:
    """A level as the LOD dock names it: its representation (a volume level's slices too)
    and its place, e.g. "volume zone (8 slices, level 2)"."""
    slices = f"{level.slices} slices, " if level.representation == "volume" else ""
    return f"{level.representation} zone ({slices}level {index + 1})"


@dataclass(frozen=True)
class LodConfig:
    """Levels ordered by distance. Level i+1 begins before level i ends (or where it ends);
    no distance lies in three levels; the last level runs to the horizon."""

    levels: tuple[LodLevel, ...] = (
        LodLevel("geometry", 0.0, 3.5),
        LodLevel("volume", 2.5, 6.5),
        LodLevel("image", 5.5, None),
    )
    epsilon: float = 0.05
    # thesis 6.4.6: image-based cells whose grass reaches above the eye are drawn by the last
    # volume level as well, so hilltops keep their silhouette
    silhouettes: bool = False
    # None: the distances are world units for any view. A number: they hold for a view this
    # many pixels tall at REFERENCE_FOV; a view with more pixels per radian (taller, or
    # zoomed in) draws every zone farther out in proportion (`for_view`), so a representation
    # is used where its detail is as many pixels wide as the level was tuned for.
    view_height: float | None = None
    # blades far away drawn with fewer segments while their curve strays from its chords by at
    # most this many pixels (core/segments.py); 0: every blade with all its segments
    segment_tolerance: float = TOLERANCE_PX

    def __post_init__(self) -> None:
        levels = self.levels
        if not 0.0 <= self.segment_tolerance <= 8.0:
            raise ValueError("the blade segments' tolerance must be 0 … 8 pixels")
        if self.view_height is not None and not 16 <= self.view_height <= 16384:
            raise ValueError("LOD view height must be 16 … 16384 pixels (or none)")
        if not levels:
            raise ValueError("a LOD configuration needs at least one level")
        if not 0 <= self.epsilon < 0.5:
            raise ValueError("epsilon must be in [0, 0.5)")
        if levels[0].begin != 0:
            raise ValueError("the first LOD level must begin at distance 0")
        if levels[-1].end is not None:
            raise ValueError("the last LOD level must run to the horizon (end = None)")
        for i, (a, b) in enumerate(itertools.pairwise(levels)):
            if a.end is None or not a.begin < b.begin <= a.end:
                raise ValueError(
                    f"the {_called(i + 1, b)} must begin after the {_called(i, a)} begins and "
                    "no later than it ends"
                )
            if b.end is not None and b.end <= a.end:
                raise ValueError(f"the {_called(i + 1, b)} must end after the {_called(i, a)}")
        for i in range(len(levels) - 2):
            if levels[i + 2].begin < levels[i].end:  # type: ignore[operator]
                raise ValueError(
                    f"the {_called(i, levels[i])} and the {_called(i + 2, levels[i + 2])} "
                    "overlap: at most two zones may"
                )

    @classmethod
    def zones(
        cls,
        geometry_end: float | None = 3.0,
        volume_end: float | None = 6.0,
        transition: float = 1.0,
        epsilon: float = 0.05,
    ) -> LodConfig:
        """Geometry, volume, image-based with boundaries at the given distances, each blended
        over a transition zone of that width centred on the boundary."""
        ends = [e for e in (geometry_end, volume_end) if e is not None]
        if any(e <= 0 for e in ends) or ends != sorted(ends):
            raise ValueError("LOD zone ends must be positive and increasing")
        if transition < 0:
            raise ValueError("transition must be >= 0")
        names = ["geometry"]
        if geometry_end is not None:
            names.append("volume")
        if volume_end is not None:
            names.append("image")
        half = transition / 2.0
        levels = []
        for i, name in enumerate(names):
            begin = 0.0 if i == 0 else max(ends[i - 1] - half, 1e-3)
            end = ends[i] + half if i < len(ends) else None
            levels.append(LodLevel(name, begin, end))
        return cls(tuple(levels), epsilon)

    def representations(self) -> list[str]:
        return [level.representation for level in self.levels]

    def view_scale(self, viewport_height: float, fov_y: float) -> float:
        """How much farther every zone lies in a view `viewport_height` pixels tall with a
        vertical field of view `fov_y` (degrees): its pixels per radian over those of the
        view the distances were set for; 1 where the distances are world units."""
        if self.view_height is None:
            return 1.0
        focal = viewport_height / math.tan(math.radians(fov_y) / 2.0)
        return focal / (self.view_height / math.tan(math.radians(REFERENCE_FOV) / 2.0))

    def for_view(self, viewport_height: float, fov_y: float) -> LodConfig:
        """The levels with world-unit distances for this view (`view_scale`); macro-cell
        limits, slices and unplanarity stay as they are."""
        if self.view_height is None:
            return self
        return dataclasses.replace(
            self.scaled(self.view_scale(viewport_height, fov_y)), view_height=None
        )

    def scaled(self, factor: float) -> LodConfig:
        """Every level's begin and end times `factor` (adaptive LOD's one factor, a view's
        scale); macro-cell limits, slices and unplanarity stay as they are."""
        if factor == 1.0:
            return self
        levels = tuple(
            dataclasses.replace(
                level,
                begin=level.begin * factor,
                end=None if level.end is None else level.end * factor,
            )
            for level in self.levels
        )
        return dataclasses.replace(self, levels=levels)

    def with_blade_reach(self, reach: float) -> LodConfig:
        """The hand-over from the blades moved out (the wind's `blade_reach`): the level after
        each geometry level begins `reach` times as far out, and the geometry level runs on to
        at least HAND_OVER_BAND past that begin, so that the two still blend. The slices hold
        the grass at rest, and the bent blades' light is the volume's largest miss where it
        begins, nearest the eye (docs/wind.md). Held inside the levels after it: the next
        level keeps part of its own zone and no three levels overlap."""
        if reach == 1.0:
            return self
        levels = list(self.levels)
        for i, level in enumerate(levels[:-1]):
            if level.representation != "geometry" or levels[i + 1].representation == "geometry":
                continue
            assert level.end is not None  # only the last level runs to the horizon
            nxt = levels[i + 1]
            begin = nxt.begin * reach
            end = max(level.end, begin * (1.0 + HAND_OVER_BAND))
            if nxt.end is not None:
                end = min(end, 0.5 * (level.end + nxt.end))
            if i + 2 < len(levels):
                after = levels[i + 2].begin
                end = min(end, after)
                begin = min(begin, 0.5 * (nxt.begin + after))  # begins before the level after
            end = max(end, level.end)
            begin = max(min(begin, end), nxt.begin)
            levels[i] = dataclasses.replace(level, end=end)
            levels[i + 1] = dataclasses.replace(nxt, begin=begin)
        return dataclasses.replace(self, levels=tuple(levels))


NO_FADE = (0.0, 0.0, 0.0, 0.0)  # fades: no transition on that side (e2 <= e1)


def fades(config: LodConfig) -> dict[tuple[str, int], tuple[float, float, float, float]]:
    """Per renderer key (representation, slices), the distances (e1, e2) of eq. 5.23 for its
    level's transition from the previous level and for its transition to the next one, so that
    a shader can weigh each blade, ray sample or texel by its own distance where the cell's
    (w, side) says it lies in a transition; both levels of a pair then split the blades at the
    same place, pixel by pixel, and no cell or macro-cell shows as a block. A key that draws
    more than one level gets NO_FADE (the cells' own w)."""
    levels = config.levels
    out: dict[tuple[str, int], tuple[float, float, float, float]] = {}
    seen: set[tuple[str, int]] = set()
    for i, level in enumerate(levels):
        key = level.key
        fade = list(NO_FADE)
        previous_end = levels[i - 1].end if i > 0 else None
        if previous_end is not None:  # only the last level runs to the horizon
            fade[0:2] = level.begin, previous_end
        if i + 1 < len(levels) and level.end is not None:
            fade[2:4] = levels[i + 1].begin, level.end
        out[key] = NO_FADE if key in seen else (fade[0], fade[1], fade[2], fade[3])
        seen.add(key)
    return out


def classify(d: np.ndarray, config: LodConfig) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per level: which distances it draws (mask) and their (w, side) per eq. 5.23-5.26."""
    levels = config.levels
    out = []
    for i, level in enumerate(levels):
        end = np.inf if level.end is None else level.end
        inside = (d >= level.begin) & (d < end)
        lod = np.empty((d.size, 2), np.float32)
        lod[:] = (ALL_IN, 0.0)
        if i > 0:  # the far side of the transition from the previous level
            prev_end = levels[i - 1].end
            assert prev_end is not None  # only the last level runs to the horizon
            band = d < prev_end
            lod[band, 0] = weight_near(d[band], level.begin, prev_end)
            lod[band, 1] = 1.0
        if i + 1 < len(levels):  # the near side of the transition to the next level
            nxt = levels[i + 1].begin
            band = d >= nxt
            lod[band, 0] = weight_near(d[band], nxt, end)
            lod[band, 1] = 0.0
        out.append((inside, lod))
    return out


def select(instances: np.ndarray, eye, config: LodConfig) -> list[np.ndarray]:
    """Split cell instances between the LOD levels by the distance of each cell centre to the
    eye (brute force, every cell); cells in a transition zone go to both levels, with w and the
    side in `lod`. The quadtree traversal (core/traversal.py) must give the same answer."""
    centre = instances["origin"] + 0.5 * instances["size"]
    d = np.hypot(centre[:, 0] - eye[0], centre[:, 1] - eye[2])
    out = []
    for inside, lod in classify(d, config):
        part = instances[inside].copy()
        part["lod"] = lod[inside]
        out.append(part)
    return out
