"""The one hand-off from selection to drawing: for one grass type and one view, the cells each
renderer draws, grouped by (representation, slices), with the bare-cell filter applied. A pure
query on arrays (no GL): render/ uploads what it returns (STYLE.md: a query does not upload).

In LOD mode the cells of every level are selected by distance (the quadtree traversal on a
terrain, core/traversal.py; a plain distance test on a fixed set of cells), and levels that share
a renderer are drawn in one call; in a single-representation mode every cell is drawn by it,
without macro-cells (the thesis's Table 7.1 comparisons)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from core.frustum import Frustum
from core.lod import LodConfig, LodLevel
from core.lod import fades as lod_fades
from core.lod import select as lod_select
from core.occupancy import DensityOccupancy
from core.terrain import Terrain
from core.traversal import traverse
from core.view_mode import ViewMode

Key = tuple[str, int]  # (representation, slices per direction; 0 unless volume)


@dataclass
class DrawList:
    """(representation, slices) -> the cells to draw (macro-cells have size > 1)."""

    batches: dict[Key, np.ndarray] = field(default_factory=dict)
    # per key, the transitions' distances a shader weighs each blade by (core/lod.py fades)
    fades: dict[Key, tuple[float, float, float, float]] = field(default_factory=dict)
    # where the geometry draws blades: (begin, end) of its levels, None where it has none (the
    # ground casts the other blades' shadows, render/shadows.py)
    blades: tuple[float, float] | None = None

    def counts(self) -> dict[Key, int]:
        return {key: int(cells.size) for key, cells in self.batches.items()}


def draw_list(
    mode: str,
    lod: LodConfig,
    eye,
    terrain: Terrain | None,
    instances: np.ndarray,
    frustum: Frustum | None,
    slices: int,
    occupancy: DensityOccupancy | None = None,
    channel: int = 0,
) -> DrawList:
    """What one grass type draws for one view. `mode` a ViewMode; `slices` the slice count a
    single-representation volume view uses; `occupancy` drops (macro-)cells where the type's
    density channel is zero everywhere."""
    if mode == ViewMode.LOD:
        config = lod
    else:
        config = LodConfig((LodLevel(mode, 0.0, None, slices=slices),))
    if terrain is not None:
        parts = traverse(terrain, eye, config, frustum, occupancy, channel).levels
    elif mode == ViewMode.LOD:
        parts = lod_select(instances, eye, config)
    else:
        parts = [instances]
    grouped: dict[Key, list[np.ndarray]] = {}
    for level, part in zip(config.levels, parts, strict=True):
        grouped.setdefault(level.key, []).append(part)
    out = DrawList(fades=lod_fades(config))
    geometry = [level for level in config.levels if level.representation == "geometry"]
    if geometry:
        ends = [math.inf if level.end is None else level.end for level in geometry]
        out.blades = (min(level.begin for level in geometry), max(ends))
    for key, chunks in grouped.items():
        cells = np.concatenate(chunks) if len(chunks) > 1 else chunks[0]
        out.batches[key] = back_to_front(cells, eye) if key[0] == "volume" else cells
    return out


def back_to_front(cells: np.ndarray, eye) -> np.ndarray:
    """Volume cells ordered farthest first (by their centres' distance from the eye in xz).
    A volume fragment blends its partly covered grass over what is drawn already, and writes
    the depth of where its ray became opaque, or, faint, of how far it got: a cuboid behind
    drawn after it failed the depth test there and let the soil show through."""
    if cells.size < 2:
        return cells
    centre = cells["origin"] + 0.5 * cells["size"]
    d2 = (centre[:, 0] - eye[0]) ** 2 + (centre[:, 1] - eye[2]) ** 2
    return cells[np.argsort(-d2, kind="stable")]
