"""Which cells can show grass of each type (thesis 6.4.1, 6.4.5): a cell whose density-map
samples are all zero draws nothing in any representation, so a grass type skips it — and any
macro-cell made only of such cells — before its instances reach the GPU. Bare paths and the
sparse clumps of a second grass type then cost nothing.

The map is sampled bilinearly (GL_LINEAR, clamp to edge): a sample inside a cell mixes the
texels whose centres lie within one texel of the cell, so a cell is occupied when the map
dilated by one texel has a non-zero value at a texel centre inside the cell (or, for a cell
narrower than a texel, at the nearest one). Edits update only the cells their rectangle can
reach and the quadtree nodes above them; a node is occupied when any of its cells is.
"""

from __future__ import annotations

import math

import numpy as np

from core.quadtree import layout, level_views, reduce_2x2

Rect = tuple[int, int, int, int]  # x (column), y (row), width, height in texels


def _dilate(a: np.ndarray) -> np.ndarray:
    """3 × 3 maximum over the first two axes, edges repeated (clamp to edge)."""
    p = np.pad(a, ((1, 1), (1, 1), (0, 0)), mode="edge")
    rows = np.maximum(np.maximum(p[:-2], p[1:-1]), p[2:])
    return np.maximum(np.maximum(rows[:, :-2], rows[:, 1:-1]), rows[:, 2:])


def _starts(cells: int, texels: int) -> np.ndarray:
    """First texel whose centre lies at or after each cell's start (cells + 1 entries)."""
    c = np.arange(cells + 1)
    return np.clip(np.ceil(c * texels / cells - 0.5).astype(np.int64), 0, texels)


class DensityOccupancy:
    """Per cell and per quadtree node (the terrain's layout, core/quadtree.py), one bit per
    density channel: whether the cell, or any cell of the node, can show grass of the type
    that grows by that channel. The traversal skips a node whose bit is clear, and with it its
    whole subtree. One byte per node: 22 MB for 4096² cells (a float32 and an int32
    integral-image entry per cell and channel needed 537 MB for four channels)."""

    def __init__(self, columns: int, rows: int, density: np.ndarray) -> None:
        """density: the density map (rows, columns, channels) of the design stack."""
        self.columns, self.rows = columns, rows
        self.channels = density.shape[2]
        if self.channels > 8:
            raise ValueError(f"at most 8 density channels, got {self.channels}")
        self.shapes, self.offsets = layout(columns, rows)
        self.packed = np.zeros(self.offsets[-1], np.uint8)
        self.levels = level_views(self.packed, self.shapes, self.offsets)
        self.update(density)

    def grows(self, channel: int) -> np.ndarray:
        """(columns, rows) bool: the cells that can show grass of `channel`."""
        return (self.levels[0] & np.uint8(1 << channel)) != 0

    def update(self, density: np.ndarray, rect: Rect | None = None) -> None:
        """Recompute the cells an edit of `rect` (the whole map if None) can reach, and the
        nodes above them."""
        h, w = density.shape[:2]
        sx, sz = _starts(self.columns, w), _starts(self.rows, h)
        if rect is None:
            c0, c1, r0, r1 = 0, self.columns, 0, self.rows
        else:
            x, y, rw, rh = rect  # texels reach cells up to 1.5 texels away (bilinear)
            c0 = max(math.floor((x - 1.5) * self.columns / w), 0)
            c1 = min(math.ceil((x + rw + 1.5) * self.columns / w), self.columns)
            r0 = max(math.floor((y - 1.5) * self.rows / h), 0)
            r1 = min(math.ceil((y + rh + 1.5) * self.rows / h), self.rows)
            if c1 <= c0 or r1 <= r0:
                return
        tx0, tx1 = max(sx[c0] - 1, 0), min(sx[c1] + 1, w)  # one texel margin for the dilation
        tz0, tz1 = max(sz[r0] - 1, 0), min(sz[r1] + 1, h)
        block = _dilate(np.asarray(density[tz0:tz1, tx0:tx1], np.float32))
        bits = np.zeros(block.shape[:2], np.uint8)
        for channel in range(self.channels):
            bits |= (block[..., channel] > 0.0).astype(np.uint8) << np.uint8(channel)
        ix = np.clip(sx[c0:c1] - tx0, 0, block.shape[1] - 1)
        iz = np.clip(sz[r0:r1] - tz0, 0, block.shape[0] - 1)
        # a cell's texels run from its start to the next cell's start; an empty range (a cell
        # narrower than a texel) gives the texel at its start, the nearest centre after it
        along_x = np.bitwise_or.reduceat(bits[:, : max(sx[c1] - tx0, 1)], ix, axis=1)
        cells = np.bitwise_or.reduceat(along_x[: max(sz[r1] - tz0, 1)], iz, axis=0)
        self.levels[0][c0:c1, r0:r1] = cells.T
        for level in range(1, len(self.levels)):  # each node: the OR of its children
            c0, r0, c1, r1 = c0 // 2, r0 // 2, (c1 + 1) // 2, (r1 + 1) // 2
            below = self.levels[level - 1][2 * c0 : 2 * c1, 2 * r0 : 2 * r1]
            self.levels[level][c0:c1, r0:r1] = reduce_2x2(below, np.bitwise_or, 0)

    def rects(self, channel: int, ix, iz, sx, sz) -> np.ndarray:
        """(n, 4) float32, per block of sx × sz cells from cell (ix, iz) (integer arrays): the
        rectangle (x0, z0, x1, z1), in cells from the block's corner, round the block's cells
        that can show grass of `channel`; the whole block where none can. A volume cuboid of
        a grass type that grows in clumps need not reach over the bare rest of its block."""
        ix, iz = (np.asarray(a, np.int64).reshape(-1) for a in (ix, iz))
        sx, sz = (np.broadcast_to(np.asarray(a, np.int64), ix.shape) for a in (sx, sz))
        out = np.zeros((ix.size, 4), np.float32)
        out[:, 2], out[:, 3] = sx, sz
        bit = np.uint8(1 << channel)
        cells = self.levels[0]
        for w, h in {(int(a), int(b)) for a, b in zip(sx, sz, strict=True)}:
            at = np.flatnonzero((sx == w) & (sz == h))
            cols = np.minimum(ix[at, None] + np.arange(w), self.columns - 1)
            rows = np.minimum(iz[at, None] + np.arange(h), self.rows - 1)
            grows = (cells[cols[:, :, None], rows[:, None, :]] & bit) != 0  # (k, w, h)
            along_x, along_z = grows.any(axis=2), grows.any(axis=1)
            some = along_x.any(axis=1)
            first_x, last_x = along_x.argmax(axis=1), w - 1 - along_x[:, ::-1].argmax(axis=1)
            first_z, last_z = along_z.argmax(axis=1), h - 1 - along_z[:, ::-1].argmax(axis=1)
            rect = np.stack([first_x, first_z, last_x + 1, last_z + 1], axis=1)
            out[at[some]] = rect[some]
        return out
