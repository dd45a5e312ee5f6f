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

import numba
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
    # all levels' ranges in one array each, level 0 first, each level (nx, nz) in C order:
    # float16 bit patterns (uint16), so that the compiled traversal reads them directly
    packed_min: np.ndarray
    packed_max: np.ndarray
    offsets: np.ndarray  # (depth + 1,) int64: where each level starts in the packed arrays
    shapes: np.ndarray  # (depth, 2) int64: nodes per level along x and z

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
        shapes, offsets = layout(columns, rows)
        tree = cls(
            columns,
            rows,
            np.empty(offsets[-1], np.uint16),
            np.empty(offsets[-1], np.uint16),
            offsets,
            shapes,
        )
        # half floats, rounded outwards: the ranges stay conservative at half the memory
        for level in range(len(shapes)):
            tree.y_min[level][...] = half_outward(lo, down=True)
            tree.y_max[level][...] = half_outward(hi, down=False)
            if level + 1 < len(shapes):
                lo = reduce_2x2(lo, np.minimum, np.inf)
                hi = reduce_2x2(hi, np.maximum, -np.inf)
        return tree

    @property
    def y_min(self) -> tuple[np.ndarray, ...]:
        """Per level, (nx, nz) float16 views: the lowest ground in each node."""
        return self._levels(self.packed_min)

    @property
    def y_max(self) -> tuple[np.ndarray, ...]:
        """Per level, (nx, nz) float16 views: the highest ground in each node."""
        return self._levels(self.packed_max)

    def _levels(self, packed: np.ndarray) -> tuple[np.ndarray, ...]:
        return level_views(packed.view(np.float16), self.shapes, self.offsets)

    @property
    def depth(self) -> int:
        return len(self.shapes)

    @property
    def node_count(self) -> int:
        return int(self.offsets[-1])

    @property
    def memory_bytes(self) -> int:
        return int(self.packed_min.nbytes + self.packed_max.nbytes)

    def shape(self, level: int) -> tuple[int, int]:
        nx, nz = self.shapes[level].tolist()
        return nx, nz


def layout(columns: int, rows: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes per level along x and z, (depth, 2), level 0 the cells; and where each level
    starts when all levels are packed into one array, level 0 first, each in C order."""
    shapes = [(columns, rows)]
    while shapes[-1] != (1, 1):
        nx, nz = shapes[-1]
        shapes.append(((nx + 1) // 2, (nz + 1) // 2))
    offsets = np.concatenate([[0], np.cumsum([nx * nz for nx, nz in shapes])]).astype(np.int64)
    return np.array(shapes, np.int64), offsets


def level_views(packed: np.ndarray, shapes: np.ndarray, offsets: np.ndarray):
    """Per level, the (nx, nz) view of a packed array (see layout)."""
    return tuple(
        packed[offsets[k] : offsets[k + 1]].reshape(nx, nz)
        for k, (nx, nz) in enumerate(shapes.tolist())
    )


def reduce_2x2(a: np.ndarray, op, fill) -> np.ndarray:
    """op over each 2 × 2 block (a level's parents), an odd edge padded with `fill`: three
    element-wise ops over strided views (numpy's reduce over axes of length 2 is far slower)."""
    nx, nz = a.shape
    if nx % 2 or nz % 2:
        padded = np.full((nx + nx % 2, nz + nz % 2), fill, a.dtype)
        padded[:nx, :nz] = a
        a = padded
    return op(op(a[0::2, 0::2], a[1::2, 0::2]), op(a[0::2, 1::2], a[1::2, 1::2]))


def half_outward(a: np.ndarray, down: bool) -> np.ndarray:
    """float16 copy of `a`, each value rounded towards -inf (down) or +inf: the largest half
    float ≤ it or the smallest ≥ it, so that a bound stays a bound. One compiled pass (numpy
    rounds to float16 through an emulated conversion, and its nextafter is slower still)."""
    a = np.ascontiguousarray(a)
    if a.dtype not in (np.float32, np.float64):
        a = a.astype(np.float64)
    out = np.empty(a.shape, np.uint16)
    _half_outward(a.reshape(-1), down, out.reshape(-1))
    return out.view(np.float16)


@numba.njit(cache=True, parallel=True)
def _half_outward(values, down, out):
    for i in numba.prange(values.shape[0]):
        out[i] = _half_bits(values[i], down)


@numba.njit(cache=True, inline="always")
def _half_bits(value, down):
    """The bit pattern of the half float next to `value` towards -inf (down) or +inf. In
    float64, where a float32 and every half float and half-float step are exact: the magnitude
    counted in steps of its binade (2^-24 below the normal range), that count rounded down or
    up, and the count and binade written as a half float (a count of 2048 is the next binade's
    first value, 1024 below the normal range the smallest normal value)."""
    x = np.float64(value)
    if x != x:
        return np.uint16(0x7E00)
    sign = 0x8000 if (x < 0.0 or (x == 0.0 and math.copysign(1.0, x) < 0.0)) else 0
    magnitude = abs(x)
    larger = down == (sign != 0)  # the magnitude rounded up: towards the side of its sign
    if magnitude == math.inf:
        return np.uint16(sign | 0x7C00)
    _, e = math.frexp(magnitude)  # magnitude = m 2^e, 0.5 ≤ m < 1: its binade is 2^(e-1)
    binade = max(e - 1, -14)  # below 2^-14 the subnormal steps, 2^-24
    steps = magnitude / math.ldexp(1.0, binade - 10)
    n = np.int64(math.ceil(steps) if larger else math.floor(steps))
    if magnitude < 2.0**-14:
        return np.uint16(sign | n)
    if n == 2048:
        n, binade = 1024, binade + 1
    if binade > 15:
        return np.uint16(sign | (0x7C00 if larger else 0x7BFF))
    return np.uint16(sign | ((binade + 15) << 10) | (n - 1024))


@numba.njit(cache=True)
def half_value(bits):
    """The float32 value of a half float's bit pattern (numba reads no float16 arrays; a
    lookup table of all 65536 values was slower, a cache miss per node)."""
    b = np.int64(bits)
    exponent, mantissa = (b >> 10) & 0x1F, b & 0x3FF
    if exponent == 0:
        value = math.ldexp(float(mantissa), -24)
    elif exponent == 31:
        value = math.inf if mantissa == 0 else math.nan
    else:
        value = math.ldexp(float(mantissa + 1024), exponent - 25)
    return np.float32(-value if b >> 15 else value)
