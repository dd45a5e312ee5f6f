"""The search space and the choice of `sward tune` (thesis ch. 8, "Adaptive Rendering System"):
LOD settings as a few knobs applied to a grass type's levels, the front of frame cost against
quality, and which setting a budget or a quality target picks. No GL: app/tune.py renders.

A candidate is the shipped levels of every grass type with the same knobs turned:
- `near`: the first hand-over (the geometry zone's end and the next level's begin) moved out
  or in by this factor;
- `far`: the hand-overs after it, by this factor;
- `transition`: every transition zone's width, by this factor (centred where it was);
- `slices`: every volume level's slices per direction, steps up or down SLICE_COUNTS;
- `macro`: every level's largest macro-cell, doublings (+) or halvings (-).
Quality is quarter-resolution FLIP against all-geometry: over the frame, over each technique's
region of the shipped setting's frame (the same pixels for every candidate, so their figures
compare), and popping along a path. Lower is better in every figure."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from core.lod import LodConfig
from core.params import SLICE_COUNTS

MACRO_LARGEST = 64  # the largest macro-cell edge a candidate may use
# a choice pops no more than the shipped setting or this, whichever is more (popping: the
# largest change from frame to frame over the reference's, core/quality.py)
POPPING_LIMIT = 1.2


@dataclass(frozen=True)
class Knobs:
    near: float = 1.0
    far: float = 1.0
    transition: float = 1.0
    slices: int = 0
    macro: int = 0

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)

    def label(self) -> str:
        return (
            f"near ×{self.near:.3g} far ×{self.far:.3g} transitions ×{self.transition:.3g} "
            f"slices {self.slices:+d} macro {self.macro:+d}"
        )


SHIPPED = Knobs()
# one step of each knob: factors for the distances, steps for slices and macro-cells
STEPS = {"near": 1.25, "far": 1.25, "transition": 1.5, "slices": 1, "macro": 1}
LIMITS = {"near": (0.25, 4.0), "far": (0.25, 4.0), "transition": (0.1, 4.0)}


def tuned(config: LodConfig, knobs: Knobs) -> LodConfig | None:
    """The levels with the knobs turned, or None where they make no valid setting (zones out of
    order, three overlapping)."""
    if knobs == SHIPPED:
        return config
    levels = list(config.levels)
    try:
        changed = [_turned(levels, i, knobs) for i in range(len(levels))]
        return dataclasses.replace(config, levels=tuple(changed))
    except ValueError:  # the hand-overs out of order, a level ending before it begins
        return None


def _turned(levels, i: int, knobs: Knobs):
    level = levels[i]
    begin, end = level.begin, level.end
    if i > 0:  # this level's begin belongs to the hand-over before it
        begin = _hand_over(levels, i - 1, knobs)[0]
    if end is not None:
        end = _hand_over(levels, i, knobs)[1]
    slices = level.slices
    if level.representation == "volume" and knobs.slices:
        k = SLICE_COUNTS.index(level.slices) if level.slices in SLICE_COUNTS else 3
        slices = SLICE_COUNTS[min(max(k + knobs.slices, 0), len(SLICE_COUNTS) - 1)]
    macro = level.macro
    if level.representation != "geometry" and knobs.macro:
        macro = int(min(max(level.macro * 2.0**knobs.macro, 1), MACRO_LARGEST))
    return dataclasses.replace(level, begin=begin, end=end, slices=slices, macro=macro)


def _hand_over(levels, i: int, knobs: Knobs) -> tuple[float, float]:
    """Where level i+1 begins and level i ends with the knobs turned: the centre of their
    transition scaled by `near` (the first) or `far` (the others), its width by `transition`."""
    a, b = levels[i], levels[i + 1]
    centre = 0.5 * (a.end + b.begin)
    half = 0.5 * (a.end - b.begin) * knobs.transition
    centre *= knobs.near if i == 0 else knobs.far
    return round(max(centre - half, 1e-3), 4), round(centre + half, 4)


def neighbours(knobs: Knobs) -> list[Knobs]:
    """Each knob one step up and one step down (within LIMITS)."""
    found = []
    for name, step in STEPS.items():
        value = getattr(knobs, name)
        for moved in (
            (value * step, value / step)
            if isinstance(step, float)
            else (
                value + step,
                value - step,
            )
        ):
            low, high = LIMITS.get(name, (-3, 3))
            if low <= moved <= high:
                if isinstance(moved, float):  # a whole number of steps: no near-duplicates
                    moved = float(f"{step ** round(math.log(moved, step)):.4g}")
                found.append(dataclasses.replace(knobs, **{name: moved}))
    return found


def first_candidates() -> list[Knobs]:
    """The shipped setting and each knob a step either way: where the search starts."""
    return [SHIPPED, *neighbours(SHIPPED)]


@dataclass
class Candidate:
    knobs: Knobs
    cost_ms: float  # median full-quality frame time over the cameras' frames
    flip: float  # quarter-resolution FLIP over the frame, mean over the cameras
    regions: dict[str, float] = field(default_factory=dict)  # technique -> mean FLIP there
    popping: float | None = None  # along the path: largest change over the reference's
    counts: dict = field(default_factory=dict)  # instances and triangles per frame
    predicted: bool = False  # cost_ms from the cost model (core/cost_model.py), not measured

    def to_dict(self) -> dict:
        return {
            "knobs": self.knobs.to_dict(),
            "cost_ms": self.cost_ms,
            "flip_quarter": self.flip,
            "regions": self.regions,
            "popping": self.popping,
            "counts": self.counts,
            "predicted": self.predicted,
        }


def at_least_as_good(a: Candidate, b: Candidate) -> bool:
    """`a`'s quality is no worse than `b`'s in the frame and in every region `b` has, and it
    pops no more than `b` does or than POPPING_LIMIT (below which a change from frame to frame
    is no more than the grass's own)."""
    if a.flip > b.flip:
        return False
    for name, figure in b.regions.items():
        if a.regions.get(name, 0.0) > figure:
            return False
    limit = popping_limit(b)
    return not (a.popping is not None and limit is not None and a.popping > limit)


def front(candidates: list[Candidate]) -> list[Candidate]:
    """The candidates no other beats in both cost and frame FLIP, cheapest first."""
    best: list[Candidate] = []
    for c in sorted(candidates, key=lambda c: (c.cost_ms, c.flip)):
        if not best or c.flip < best[-1].flip:
            best.append(c)
    return best


def choose(
    candidates: list[Candidate],
    budget_ms: float | None = None,
    quality: float | None = None,
    popping_limit: float | None = None,
) -> Candidate | None:
    """Within a budget: the best frame FLIP costing at most `budget_ms` (the shipped setting
    wins ties: it is what the person knows). For a quality: the cheapest candidate whose frame
    FLIP is at most `quality`. Either popping no more than `popping_limit`. None when nothing
    meets the target."""
    found = ranked(candidates, budget_ms, quality, popping_limit)
    return found[0] if found else None


def as_good_as_shipped(
    candidates: list[Candidate], shipped: Candidate, budget_ms: float
) -> list[Candidate]:
    """The candidates at least as good as the shipped setting in every figure within the
    budget, cheapest first."""
    found = [
        c
        for c in candidates
        if c.knobs != shipped.knobs and c.cost_ms <= budget_ms and at_least_as_good(c, shipped)
    ]
    return sorted(found, key=lambda c: (c.cost_ms, c.flip))


def ranked(
    candidates: list[Candidate],
    budget_ms: float | None = None,
    quality: float | None = None,
    popping_limit: float | None = None,
) -> list[Candidate]:
    """The candidates that meet the target and pop no more than `popping_limit`, best first
    (`choose` takes the first)."""
    if popping_limit is not None:
        candidates = [c for c in candidates if c.popping is None or c.popping <= popping_limit]
    if budget_ms is not None:
        within = [c for c in candidates if c.cost_ms <= budget_ms]
        return sorted(within, key=lambda c: (c.flip, c.knobs != SHIPPED, c.cost_ms))
    assert quality is not None
    return sorted((c for c in candidates if c.flip <= quality), key=lambda c: (c.cost_ms, c.flip))


def popping_limit(shipped: Candidate) -> float | None:
    """How much a chosen setting may pop: as the shipped one does, at least POPPING_LIMIT."""
    return None if shipped.popping is None else max(shipped.popping, POPPING_LIMIT)


def nearest_miss(
    candidates: list[Candidate], budget_ms: float | None = None, quality: float | None = None
) -> Candidate:
    """Where to search on when nothing meets the target: the cheapest candidate for a budget,
    the best for a quality."""
    if budget_ms is not None:
        return min(candidates, key=lambda c: (c.cost_ms, c.flip))
    return min(candidates, key=lambda c: (c.flip, c.cost_ms))


def proposals(
    candidates: list[Candidate], seen: set[Knobs], target: Candidate | None
) -> list[Knobs]:
    """The next knobs to try: the unseen neighbours of the front's members and of the current
    choice (nearest the choice first)."""
    around = front(candidates)
    if target is not None and target not in around:
        around = [target, *around]
    out: list[Knobs] = []
    for c in around:
        for k in neighbours(c.knobs):
            if k not in seen and k not in out:
                out.append(k)
    if target is not None:
        out.sort(key=lambda k: _distance(k, target.knobs))
    return out


def _distance(a: Knobs, b: Knobs) -> float:
    return (
        abs(math.log(a.near / b.near))
        + abs(math.log(a.far / b.far))
        + abs(math.log(a.transition / b.transition))
        + abs(a.slices - b.slices)
        + abs(a.macro - b.macro)
    )
