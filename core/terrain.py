"""A grassed terrain: columns × rows cells of one patch each, its quadtree, and the cell data the
renderers draw from (thesis 6.1-6.4): origin, size, mirror bits, config transform."""

from __future__ import annotations

from dataclasses import dataclass, field

import numba
import numpy as np

from core.grid import INSTANCE_DTYPE
from core.ground_planes import ground_planes
from core.heights import (
    block_maxima,
    blocks_max,
    cell_curvature,
    cell_ranges,
    corner_deviations,
)
from core.lod import ALL_IN
from core.quadtree import QuadTree, half_outward
from core.tiling import mirror_sign, noise_map

# A (macro-)cell to draw, one float64 row: first cell (x0, z0), size in cells, its ground's
# height range, its LOD level, and (w, side) of eqs. 5.23-5.26. The traversal makes these.
X0, Z0, SX, SZ, Y_LO, Y_HI, LEVEL, W, SIDE = range(9)
# where each field of an instance lies in its 15 float32s
_NAMES = ("origin", "density", "lod", "size", "mirror", "config", "ground")
_FIELDS = INSTANCE_DTYPE.fields
assert _FIELDS is not None and INSTANCE_DTYPE.itemsize == 15 * 4
assert all(INSTANCE_DTYPE[name].base == np.float32 for name in _NAMES)
_ORIGIN, _DENSITY, _LOD, _SIZE, _MIRROR, _CONFIG, _GROUND = (_FIELDS[n][1] // 4 for n in _NAMES)
_NO_NOISE = np.zeros((1, 1, 2), np.float32)
_NO_NOISE.flags.writeable = False  # read-only like noise_map's: one compiled type for both


@dataclass(frozen=True, eq=False)
class Terrain:
    columns: int
    rows: int
    origin: tuple[float, float] = (0.0, 0.0)  # world x, z of cell (0, 0)'s corner
    mirror_seed: int | None = None  # aperiodic tiling (6.3); None: every cell alike
    grass_height: float = 0.5  # added to the ground's height range in the bounding volumes
    # the design stack's height map (rows along z, values 0 … 1) times height_scale (6.4.4)
    heights: np.ndarray | None = None
    height_scale: float = 0.0
    # the ground's height range per node, the cells its level 0 (half floats rounded outward:
    # the ranges stay bounds, and a 4096² terrain keeps no float32 copy of them besides)
    tree: QuadTree = field(init=False)
    # a bound on the ground's bends, each cell's own (core/heights.py cell_curvature), and
    # their maxima over blocks of 2 × 2, 4 × 4, … cells up to the whole terrain
    bends: list[np.ndarray] = field(init=False)
    # the ground at every cell corner and how far each cell's ground strays below and above
    # the blend of its corners (core/heights.py corner_deviations); None on flat ground
    corner_heights: tuple[np.ndarray, np.ndarray, np.ndarray] | None = field(init=False)
    _planes: dict = field(init=False, repr=False)  # Terrain.planes_of's tables by block size

    def __post_init__(self) -> None:
        if self.height_scale < 0:
            raise ValueError(f"height scale {self.height_scale:g} must not be negative")
        if self.heights is not None and self.height_scale > 0:
            lo, hi = cell_ranges(self.heights, self.height_scale, self.columns, self.rows)
        else:
            lo = hi = np.zeros((self.columns, self.rows), np.float32)
        object.__setattr__(self, "tree", QuadTree.build(self.columns, self.rows, lo, hi))
        del lo, hi  # before the bends and corners are made: the first frame's peak is lower
        if self.heights is not None and self.height_scale > 0:
            bends = cell_curvature(self.heights, self.height_scale, self.columns, self.rows)
            corners = corner_deviations(self.heights, self.height_scale, self.columns, self.rows)
        else:
            corners = None
            bends = np.zeros((self.columns, self.rows), np.float32)
        # bounds, kept in half floats rounded up (their maxima are half floats too)
        object.__setattr__(self, "bends", block_maxima(half_outward(bends, down=False)))
        object.__setattr__(self, "corner_heights", corners)
        object.__setattr__(self, "_planes", {})

    @property
    def cell_min(self) -> np.ndarray:
        """(columns, rows) float32: each cell's lowest ground (made at each call)."""
        return self.tree.y_min[0].astype(np.float32)

    @property
    def cell_max(self) -> np.ndarray:
        """(columns, rows) float32: each cell's highest ground (made at each call)."""
        return self.tree.y_max[0].astype(np.float32)

    @property
    def ground_span(self) -> tuple[float, float]:
        """The lowest and the highest ground of the whole terrain (the quadtree's root)."""
        return float(self.tree.y_min[-1][0, 0]), float(self.tree.y_max[-1][0, 0])

    @classmethod
    def centred(cls, columns: int, rows: int, **kw) -> Terrain:
        """A terrain whose centre is the world origin (like core/grid.grid_instances)."""
        return cls(columns, rows, origin=(-columns / 2.0, -rows / 2.0), **kw)

    def cells(self, ix, iz, sx=1, sz=1, ground=None) -> np.ndarray:
        """Instances of (macro-)cells starting at cell (ix, iz), sx × sz cells large; `ground`
        is their (lowest, highest) ground, by default that of the single cells."""
        ix, iz = np.asarray(ix), np.asarray(iz)
        records = np.zeros((ix.size, 9))
        records[:, X0], records[:, Z0], records[:, SX], records[:, SZ] = ix, iz, sx, sz
        if ground is None:
            ground = (self.tree.y_min[0][ix, iz], self.tree.y_max[0][ix, iz])
        lo, hi = ground
        records[:, Y_LO], records[:, Y_HI] = lo, hi
        records[:, W] = ALL_IN
        return self.instances(records)

    def instances(self, records: np.ndarray) -> np.ndarray:
        """Instances (INSTANCE_DTYPE) of (n, 9) records: origin, size, mirror bits (6.3),
        config transform into the design maps (6.4), ground, (w, side)."""
        out = np.empty((records.shape[0], 15), np.float32)
        mirrored = self.mirror_seed is not None
        ox, oz = self.origin
        fill_instances(out, records, ox, oz, self.columns, self.rows, self.noise, mirrored)
        return out.view(INSTANCE_DTYPE).reshape(records.shape[0])

    @property
    def curvature(self) -> float:
        """The whole ground's bound (core/heights.py ground_curvature; 0: flat)."""
        return float(self.bends[-1].max())

    def blocks_of(self, instances: np.ndarray) -> tuple[np.ndarray, ...]:
        """Per instance (INSTANCE_DTYPE), its first cell and its extent in cells: (ix, iz, sx,
        sz) integer arrays, the first cell within the terrain, the extent at least one."""
        ix = np.rint(instances["origin"][:, 0] - self.origin[0]).astype(np.int64)
        iz = np.rint(instances["origin"][:, 1] - self.origin[1]).astype(np.int64)
        sx = np.maximum(np.rint(instances["size"][:, 0]).astype(np.int64), 1)
        sz = np.maximum(np.rint(instances["size"][:, 1]).astype(np.int64), 1)
        return np.clip(ix, 0, self.columns - 1), np.clip(iz, 0, self.rows - 1), sx, sz

    def curvature_of(self, instances: np.ndarray) -> np.ndarray:
        """Per instance (INSTANCE_DTYPE), a bound on the bends of the ground it covers (core/
        heights.py cell_curvature), for the grids its image-based slice is drawn with."""
        return blocks_max(self.bends, *self.blocks_of(instances))

    def planes_of(self, instances: np.ndarray) -> np.ndarray:
        """Per instance (INSTANCE_DTYPE), (n, 4) float32: the ground's slope along x and z per
        cell and the lowest and highest ground over that plane, relative to the instance's
        lowest ground (core/ground_planes.py), where the two planes lie closer than
        its height range; elsewhere (and on flat ground) (0, 0, 0, height range): the range.
        The planes of every block of a size at every position the quadtree puts one are made
        once, when a frame first draws a block of that size."""
        out = np.zeros((len(instances), 4), np.float32)
        out[:, 3] = instances["ground"][:, 1]
        if self.corner_heights is None or not len(instances):
            return out
        ix, iz, sx, sz = self.blocks_of(instances)
        planes = np.empty_like(out)
        sizes = sx * (self.rows + 1) + sz
        for key in np.unique(sizes):
            at = np.flatnonzero(sizes == key)
            w, h = int(sx[at[0]]), int(sz[at[0]])
            # a quadtree node starts at a multiple of the power of two its longer side rounds
            # up to (a node cut short by the terrain's edge keeps its level's start)
            step = 1 << int(np.ceil(np.log2(max(w, h))))
            if step < 8:  # small blocks: each frame's own (a table would hold every cell)
                planes[at] = ground_planes(*self.corner_heights, ix[at], iz[at], w, h, 0.0)
                continue
            table = self._block_planes(w, h, step)
            planes[at] = table[ix[at] // step, iz[at] // step]
        planes[:, 2:] -= instances["ground"][:, :1]
        thinner = planes[:, 3] - planes[:, 2] < out[:, 3]
        out[thinner] = planes[thinner]
        return out

    def _block_planes(self, w: int, h: int, step: int) -> np.ndarray:
        """ground_planes of the w × h blocks at every multiple of `step` (absolute heights),
        (columns / step, rows / step, 4), kept for the terrain's life."""
        table = self._planes.get((w, h, step))
        if table is None:
            assert self.corner_heights is not None
            ix, iz = np.meshgrid(np.arange(0, self.columns, step), np.arange(0, self.rows, step),
                                 indexing="ij")  # fmt: skip
            flat = ground_planes(*self.corner_heights, ix.ravel(), iz.ravel(), w, h, 0.0)
            table = flat.reshape(*ix.shape, 4)
            self._planes[(w, h, step)] = table
        return table

    def all_cells(self) -> np.ndarray:
        ix, iz = np.meshgrid(np.arange(self.columns), np.arange(self.rows), indexing="ij")
        return self.cells(ix.ravel(), iz.ravel())

    @property
    def noise(self) -> np.ndarray:
        """The aperiodic tiling's noise map (6.3); a dummy when the terrain has none."""
        return _NO_NOISE if self.mirror_seed is None else noise_map(self.mirror_seed)

    @property
    def rect(self) -> tuple[float, float, float, float]:
        """xmin, zmin, xmax, zmax in world units."""
        x0, z0 = self.origin
        return (x0, z0, x0 + self.columns, z0 + self.rows)


@numba.njit(cache=True)
def fill_instances(out, records, ox, oz, columns, rows, noise, mirrored):
    """Terrain.instances, row by row into the instances' float32s (the traversal calls it from
    its compiled walk)."""
    for k in range(records.shape[0]):
        x, z = np.float32(ox + records[k, X0]), np.float32(oz + records[k, Z0])
        out[k, _ORIGIN], out[k, _ORIGIN + 1] = x, z
        out[k, _DENSITY] = 1.0
        out[k, _LOD], out[k, _LOD + 1] = records[k, W], records[k, SIDE]
        out[k, _SIZE], out[k, _SIZE + 1] = records[k, SX], records[k, SZ]
        if mirrored:
            out[k, _MIRROR] = mirror_sign(noise, np.float64(x), np.float64(z), 1.0, 0)
            out[k, _MIRROR + 1] = mirror_sign(noise, np.float64(x), np.float64(z), 1.0, 1)
        else:
            out[k, _MIRROR], out[k, _MIRROR + 1] = 1.0, 1.0
        out[k, _CONFIG], out[k, _CONFIG + 1] = records[k, X0] / columns, records[k, Z0] / rows
        out[k, _CONFIG + 2], out[k, _CONFIG + 3] = 1.0 / columns, 1.0 / rows
        lo = np.float32(records[k, Y_LO])
        out[k, _GROUND], out[k, _GROUND + 1] = lo, np.float32(records[k, Y_HI]) - lo
