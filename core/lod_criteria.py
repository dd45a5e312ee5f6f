"""The LOD tests of the quadtree traversal (thesis 6.1.2, 6.2, 6.4.4), each a small compiled
function of one node and one LOD level (or pair of levels): the traversal (core/traversal.py)
calls them per node inside its compiled walk. The per-level bounds they compare against are
worked out once per frame into one table (`Levels.table`). A new kind of test is one more
function here and one line in the walk.

Compiled with numba: the per-frame traversal visits a few hundred nodes over a dozen tree
levels, and numpy's per-call overhead (~50 array operations a level) cost 4-6 ms of it."""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numba
import numpy as np

from core.lod import LodConfig

MARGIN = 1e-4  # node-level distance decisions are conservative by this much; leaves decide

# columns of Levels.table
BEGIN, END, MACRO, MAX_UNPLANARITY, CORE_LO, CORE_HI, PAIR_LO, PAIR_HI, PAIR_LIMIT = range(9)


@dataclass(frozen=True)
class Levels:
    """The LOD configuration as one (levels × 9) float64 table: each level's range, macro-cell
    limit and unplanarity limit, the zone where it alone draws (macro-cells), and for the pair
    (t, t + 1) the distances within which a node may be shared by both."""

    table: np.ndarray

    @classmethod
    @functools.lru_cache(maxsize=32)  # per frame and grass type: configurations are few, frozen
    def of(cls, config: LodConfig) -> Levels:
        lv = config.levels
        begin = np.array([x.begin for x in lv], np.float64)
        end = np.array([np.inf if x.end is None else x.end for x in lv])
        macro = np.array([x.macro for x in lv], np.float64)
        table = np.empty((len(lv), 9))
        table[:, BEGIN] = begin
        table[:, END] = end
        table[:, MACRO] = macro
        table[:, MAX_UNPLANARITY] = [
            np.inf if x.max_unplanarity is None else x.max_unplanarity for x in lv
        ]
        # macro-cells (6.2): wholly in the level's own zone, where no neighbouring level draws
        prev_end = np.concatenate([[-np.inf], end[:-1]])
        next_begin = np.concatenate([begin[1:], [np.inf]])
        table[:, CORE_LO] = np.maximum(begin, prev_end) + MARGIN
        table[:, CORE_HI] = np.minimum(end, next_begin) - MARGIN
        # a pair t, t+1: no cell back in level t-1, nor on in level t+2, both limits kept
        table[:, PAIR_LO] = np.concatenate([[-np.inf], end[:-1] + MARGIN])
        table[:, PAIR_HI] = np.concatenate([begin[2:] - MARGIN, [np.inf, np.inf]])[: len(lv)]
        table[:, PAIR_LIMIT] = np.minimum(macro, np.concatenate([macro[1:], [0.0]]))
        table.flags.writeable = False
        return cls(table)

    @property
    def count(self) -> int:
        return self.table.shape[0]


@numba.njit(cache=True)
def distance(table, t, dmin, dmax) -> bool:
    """Draw or split where the node reaches into level t's range; discard elsewhere. dmin and
    dmax: the horizontal distances from the eye to the node's nearest and farthest cell centre."""
    return dmax >= table[t, BEGIN] - MARGIN and dmin < table[t, END] + MARGIN


@numba.njit(cache=True)
def flat(table, t, y_lo, y_hi) -> bool:
    """The unplanarity test (6.4.4): a node may be a macro-cell only on nearly flat ground."""
    return (y_hi - y_lo) <= table[t, MAX_UNPLANARITY]


@numba.njit(cache=True)
def macro_cell(table, t, dmin, dmax, span) -> bool:
    """The macro-cell test (6.2): no larger than level t's limit (span: the node's edge in
    cells) and wholly in its own zone, where no neighbouring level draws."""
    return span <= table[t, MACRO] and dmin >= table[t, CORE_LO] and dmax < table[t, CORE_HI]


@numba.njit(cache=True)
def shared(table, t, dmin, dmax, span) -> bool:
    """A node within the reach of levels t and t+1 only and within both macro-cell limits,
    drawn by both with one w (core/traversal.py). Never for the last level."""
    if t + 1 >= table.shape[0]:
        return False
    return span <= table[t, PAIR_LIMIT] and dmin >= table[t, PAIR_LO] and dmax < table[t, PAIR_HI]
