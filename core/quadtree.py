"""The terrain's quadtree (thesis 6.1.1), built bottom-up and kept as flat arrays.

Level 0 holds the cells (columns × rows, any sizes). Each level above groups 2 × 2 nodes of the
one below, so level k has ceil(columns / 2^k) × ceil(rows / 2^k) nodes and node (i, j) of
level k covers the cells [i·2^k, (i+1)·2^k) × [j·2^k, (j+1)·2^k) clipped to the terrain: its
children are implied by the indices and no pointers are stored. Per node only the height range
of its content is kept; its exact box, and the bounding sphere computed from that box (not by
merging the children's spheres, 6.1.1), follow from the indices when a traversal needs them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def depth_bound(columns: int, rows: int) -> int:
    """depth = ceil(log2(dim)) + 1 (eq. 6.1)."""
    return math.ceil(math.log2(max(columns, rows))) + 1


def node_bound(columns: int, rows: int) -> int:
    """nodes = ceil(4/3 · nextPowerOfTwo(dim)²) (eq. 6.1)."""
    dim = max(columns, rows)
    return math.ceil(4.0 / 3.0 * (1 << (dim - 1).bit_length()) ** 2)


@dataclass(frozen=True, eq=False)
class QuadTree:
    columns: int
    rows: int
    y_min: tuple[np.ndarray, ...]  # per level, (nx, nz) float16: lowest ground in the node
    y_max: tuple[np.ndarray, ...]  # per level, (nx, nz) float16: highest ground in the node

    @classmethod
    def build(
        cls, columns: int, rows: int, cell_min: np.ndarray | None = None, cell_max=None
    ) -> QuadTree:
        """A tree over columns × rows cells; cell_min / cell_max are the ground's height range
        per cell, (columns, rows) arrays (flat ground when omitted)."""
        if columns < 1 or rows < 1:
            raise ValueError(f"terrain size must be at least 1 × 1 cells, got {columns} × {rows}")
        lo = np.zeros((columns, rows), np.float32) if cell_min is None else cell_min
        hi = lo if cell_max is None else cell_max
        lo = np.asarray(lo, np.float32)
        hi = np.asarray(hi, np.float32)
        if lo.shape != (columns, rows) or hi.shape != (columns, rows):
            raise ValueError(f"cell height ranges must be {columns} × {rows} arrays")
        mins, maxs = [lo], [hi]
        while mins[-1].shape != (1, 1):
            mins.append(_reduce(mins[-1], np.minimum, np.inf))
            maxs.append(_reduce(maxs[-1], np.maximum, -np.inf))
        # half floats, rounded outwards: the ranges stay conservative at half the memory
        return cls(
            columns,
            rows,
            tuple(_half(a, down=True) for a in mins),
            tuple(_half(a, down=False) for a in maxs),
        )

    @property
    def depth(self) -> int:
        return len(self.y_min)

    @property
    def node_count(self) -> int:
        return int(sum(a.size for a in self.y_min))

    @property
    def memory_bytes(self) -> int:
        return int(sum(a.nbytes for a in self.y_min) + sum(a.nbytes for a in self.y_max))

    def shape(self, level: int) -> tuple[int, int]:
        rows, columns = self.y_min[level].shape
        return rows, columns

    def extent(self, level: int, ix: np.ndarray, iz: np.ndarray):
        """Cell ranges [x0, x1) × [z0, z1) of nodes (ix, iz) of a level, clipped at the edges."""
        step = 1 << level
        x0, z0 = ix * step, iz * step
        return x0, z0, np.minimum(x0 + step, self.columns), np.minimum(z0 + step, self.rows)

    def children(self, level: int, ix: np.ndarray, iz: np.ndarray):
        """Indices (at level - 1) of the existing children of nodes (ix, iz) of `level`, and
        for each child the position of its parent in the input."""
        nx, nz = self.shape(level - 1)
        cx = (2 * ix[:, None] + np.array([0, 1, 0, 1])).ravel()
        cz = (2 * iz[:, None] + np.array([0, 0, 1, 1])).ravel()
        parent = np.repeat(np.arange(ix.size), 4)
        keep = (cx < nx) & (cz < nz)
        return cx[keep], cz[keep], parent[keep]


def _reduce(a: np.ndarray, op, fill: float) -> np.ndarray:
    nx, nz = a.shape
    padded = np.full((nx + nx % 2, nz + nz % 2), fill, np.float32)
    padded[:nx, :nz] = a
    quads = padded.reshape(padded.shape[0] // 2, 2, padded.shape[1] // 2, 2)
    return op.reduce(op.reduce(quads, axis=3), axis=1)


def _half(a: np.ndarray, down: bool) -> np.ndarray:
    """float16 copy of `a`, each value rounded towards -inf (down) or +inf."""
    h = a.astype(np.float16)
    wrong = (h.astype(np.float32) > a) if down else (h.astype(np.float32) < a)
    h[wrong] = np.nextafter(h[wrong], np.float16(-np.inf if down else np.inf))
    return h
