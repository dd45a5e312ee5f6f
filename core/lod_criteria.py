"""The LOD tests of the quadtree traversal (thesis 6.1.2, 6.2, 6.4.4), each a small function
over the nodes of one tree level: it returns a (nodes × LOD levels) mask. A new kind of test is
one more function here and one line in core/traversal.py."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.lod import LodConfig

MARGIN = 1e-4  # node-level distance decisions are conservative by this much; leaves decide


@dataclass(frozen=True)
class Levels:
    """The LOD configuration as arrays, one entry per level."""

    begin: np.ndarray
    end: np.ndarray
    macro: np.ndarray
    max_unplanarity: np.ndarray

    @classmethod
    def of(cls, config: LodConfig) -> Levels:
        lv = config.levels
        return cls(
            np.array([x.begin for x in lv]),
            np.array([np.inf if x.end is None else x.end for x in lv]),
            np.array([x.macro for x in lv]),
            np.array([np.inf if x.max_unplanarity is None else x.max_unplanarity for x in lv]),
        )

    @property
    def count(self) -> int:
        return len(self.begin)


@dataclass(frozen=True)
class Nodes:
    """The nodes of one tree level still in play: the horizontal distance range from the eye
    to their cell centres, their edge in cells and their ground's height range."""

    dmin: np.ndarray  # (n, 1)
    dmax: np.ndarray  # (n, 1)
    span: int
    y_lo: np.ndarray  # (n,)
    y_hi: np.ndarray


def distance(nodes: Nodes, lv: Levels) -> np.ndarray:
    """Draw or split where the node reaches into the level's range; discard elsewhere."""
    return (nodes.dmax >= lv.begin - MARGIN) & (nodes.dmin < lv.end + MARGIN)


def flat(nodes: Nodes, lv: Levels) -> np.ndarray:
    """The unplanarity test (6.4.4): a node may be a macro-cell only on nearly flat ground."""
    return (nodes.y_hi - nodes.y_lo)[:, None] <= lv.max_unplanarity


def macro_cell(nodes: Nodes, lv: Levels) -> np.ndarray:
    """The macro-cell test (6.2): no larger than the level's limit and wholly in its own zone,
    where no neighbouring level draws."""
    prev_end = np.concatenate([[-np.inf], lv.end[:-1]])
    next_begin = np.concatenate([lv.begin[1:], [np.inf]])
    core_lo = np.maximum(lv.begin, prev_end) + MARGIN
    core_hi = np.minimum(lv.end, next_begin) - MARGIN
    return (nodes.span <= lv.macro) & (nodes.dmin >= core_lo) & (nodes.dmax < core_hi)


def shared(nodes: Nodes, lv: Levels) -> np.ndarray:
    """(nodes × level pairs t, t+1): a node within the reach of levels t and t+1 only and
    within both macro-cell limits, drawn by both with one w (core/traversal.py)."""
    if lv.count < 2:
        return np.zeros((nodes.dmin.shape[0], 0), bool)
    lo = np.concatenate([[-np.inf], lv.end[:-2] + MARGIN])  # no cell back in level t-1
    hi = np.concatenate([lv.begin[2:] - MARGIN, [np.inf]])  # nor on in level t+2
    limit = np.minimum(lv.macro[:-1], lv.macro[1:])
    return (nodes.span <= limit) & (nodes.dmin >= lo) & (nodes.dmax < hi)
