"""A grassed terrain: columns × rows cells of one patch each, its quadtree, and the cell data the
renderers draw from (thesis 6.1-6.4): origin, size, mirror bits, config transform."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core.grid import INSTANCE_DTYPE
from core.heights import cell_ranges
from core.lod import ALL_IN
from core.quadtree import QuadTree
from core.tiling import mirror_bits


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
    tree: QuadTree = field(init=False)
    cell_min: np.ndarray = field(init=False)  # (columns, rows) lowest ground per cell
    cell_max: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        if self.height_scale < 0:
            raise ValueError(f"height scale {self.height_scale:g} must not be negative")
        if self.heights is not None and self.height_scale > 0:
            lo, hi = cell_ranges(self.heights, self.height_scale, self.columns, self.rows)
        else:
            lo = hi = np.zeros((self.columns, self.rows), np.float32)
        object.__setattr__(self, "cell_min", lo)
        object.__setattr__(self, "cell_max", hi)
        object.__setattr__(self, "tree", QuadTree.build(self.columns, self.rows, lo, hi))

    @classmethod
    def centred(cls, columns: int, rows: int, **kw) -> Terrain:
        """A terrain whose centre is the world origin (like core/grid.grid_instances)."""
        return cls(columns, rows, origin=(-columns / 2.0, -rows / 2.0), **kw)

    def cells(self, ix, iz, sx=1, sz=1, ground=None) -> np.ndarray:
        """Instances of (macro-)cells starting at cell (ix, iz), sx × sz cells large; `ground`
        is their (lowest, highest) ground, by default that of the single cells."""
        ix = np.asarray(ix)
        out = np.zeros(ix.size, INSTANCE_DTYPE)
        out["origin"][:, 0] = self.origin[0] + ix
        out["origin"][:, 1] = self.origin[1] + np.asarray(iz)
        out["density"] = 1.0
        out["lod"] = (ALL_IN, 0.0)
        out["size"][:, 0] = sx
        out["size"][:, 1] = sz
        if self.mirror_seed is None:
            out["mirror"] = 1.0
        else:
            out["mirror"] = mirror_bits(out["origin"], self.mirror_seed)
        out["config"][:, 0] = ix / self.columns
        out["config"][:, 1] = np.asarray(iz) / self.rows
        out["config"][:, 2] = 1.0 / self.columns
        out["config"][:, 3] = 1.0 / self.rows
        lo, hi = ground if ground is not None else (self.cell_min[ix, iz], self.cell_max[ix, iz])
        out["ground"][:, 0] = lo
        out["ground"][:, 1] = np.asarray(hi, np.float32) - np.asarray(lo, np.float32)
        return out

    def all_cells(self) -> np.ndarray:
        ix, iz = np.meshgrid(np.arange(self.columns), np.arange(self.rows), indexing="ij")
        return self.cells(ix.ravel(), iz.ravel())

    @property
    def rect(self) -> tuple[float, float, float, float]:
        """xmin, zmin, xmax, zmax in world units."""
        x0, z0 = self.origin
        return (x0, z0, x0 + self.columns, z0 + self.rows)
