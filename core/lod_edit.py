"""Editing LOD levels (the designer's LOD zone editor): edits of one grass type's levels that
give a valid LodConfig or raise ValueError with a message a person can act on (LodConfig checks
the thesis's overlap rules). The levels live in the document (core/document.py)."""

from __future__ import annotations

import dataclasses

from core.lod import LodConfig, LodLevel


def with_levels(config: LodConfig, levels: list[LodLevel]) -> LodConfig:
    return dataclasses.replace(config, levels=tuple(levels))


def set_field(config: LodConfig, index: int, name: str, value) -> LodConfig:
    """One field of one level (representation, begin, end, slices, macro)."""
    levels = list(config.levels)
    level = levels[index]
    changes = {name: value}
    if name == "representation" and value == "geometry":
        changes["macro"] = 1  # geometry draws single cells (thesis 6.2)
    levels[index] = dataclasses.replace(level, **changes)
    return with_levels(config, levels)


def set_view_height(config: LodConfig, pixels: float) -> LodConfig:
    """The view height the distances hold for (core/lod.py LodConfig.view_height); 0: none,
    the distances are world units."""
    return dataclasses.replace(config, view_height=float(pixels) if pixels else None)


def set_view_heights(lods: list[LodConfig], pixels: float) -> list[LodConfig]:
    """Every grass type's distances set to hold for one view height (0: world units): the
    view is one, whatever the type (the LOD dock, `--lod-view-height`)."""
    return [set_view_height(config, pixels) for config in lods]


def append_level(config: LodConfig) -> LodConfig:
    """A new last level beyond the current last one, which now ends where the new one has
    fully taken over; the new level draws what the last one drew."""
    levels = list(config.levels)
    last = levels[-1]
    before = levels[-2].end if len(levels) > 1 else 0.0
    assert before is not None  # only the last level runs to the horizon
    start = max(last.begin, before)
    span = max(0.5 * start, 4.0)
    begin = start + span
    levels[-1] = dataclasses.replace(last, end=begin + 0.5 * span)
    levels.append(dataclasses.replace(last, begin=begin, end=None))
    return with_levels(config, levels)


def remove_level(config: LodConfig, index: int) -> LodConfig:
    """Drop a level; its neighbours close the gap (the new first level begins at 0, the new
    last runs to the horizon, the level before reaches to the one after)."""
    levels = list(config.levels)
    if len(levels) == 1:
        raise ValueError("the only LOD level cannot be removed")
    del levels[index]
    if index == 0:
        levels[0] = dataclasses.replace(levels[0], begin=0.0)
    elif index == len(levels):
        levels[-1] = dataclasses.replace(levels[-1], end=None)
    else:
        before, after = levels[index - 1], levels[index]
        if before.end is not None and before.end < after.begin:
            levels[index - 1] = dataclasses.replace(before, end=after.begin)
    return with_levels(config, levels)


def move_level(config: LodConfig, index: int, step: int) -> LodConfig:
    """Swap what two neighbouring levels draw (representation, slices, macro-cells); the
    distance ranges stay where they are."""
    other = index + step
    levels = list(config.levels)
    if not 0 <= other < len(levels):
        raise ValueError("a level cannot move past the first or last place")
    a, b = levels[index], levels[other]

    def drawn(src: LodLevel, dst: LodLevel) -> LodLevel:
        macro = 1 if src.representation == "geometry" else src.macro
        return dataclasses.replace(
            dst, representation=src.representation, slices=src.slices, macro=macro
        )

    levels[index], levels[other] = drawn(b, a), drawn(a, b)
    return with_levels(config, levels)
