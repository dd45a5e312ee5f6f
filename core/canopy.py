"""What a view at a low elevation meets of a grass patch (issue: the LOD image matches
all-geometry). The image-based grass is one slice seen from above; far away it is seen nearly
level, where the blades hide one another's lower parts, and how deep a view reaches depends on
its elevation and on how densely the blades stand at each height.

Per row y of the patch (rows run upward, row 0 at the ground), what a ray descending through
the row meets: the blades' area seen from the side, s(y) per patch length of a level ray, and
seen from above, t(y) per patch area, counted on the blades' triangles (BladeDepths; from the
vertical slices' rows where the blades are not known). A ray at elevation θ descending Δy
travels Δy / tan θ across: Campbell's ellipsoidal leaf-angle model gives its optical depth in
the row as τ(y, θ) = √(t(y)² + (s(y) / tan θ)²) — the blades' side area for level rays, their
area from above for vertical ones, and for randomly turned blades the two agree. The share the
ray gives row y is w(y) = T(y) · (1 − exp(−τ(y, θ))), T the transmittance of the rows above,
and with the slices' colour of the row, c(y) (alpha-weighted over a family's slices), the table
holds per elevation Σ w c / Σ w: the colour met; and the same mean of AO_blade's height term
(shade_met), and the share of a view that reaches a height (transmittance), which weighs the
blades' diffuse factor (core/facing.py)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

ELEVATIONS = 8  # table entries: θ_j = 90° · ((j + 0.5) / 8)², dense near the horizon


def elevations(count: int = ELEVATIONS) -> np.ndarray:
    """The table's elevations in radians (the shaders invert this: shaders/image.glsl)."""
    return 0.5 * np.pi * ((np.arange(count) + 0.5) / count) ** 2


def _profile(color: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Of one family of vertical slices ((n, rows, w, 4), rows running upward): the extinction
    per patch length σ(y) and the alpha-weighted colour c(y) of each row."""
    a = color[..., 3]
    alpha = np.clip(a.mean(axis=2), 0.0, 1.0)  # (n, rows)
    through = 1.0 - np.prod(1.0 - alpha, axis=0)  # (rows,)
    sigma = -np.log(np.maximum(1.0 - through, 1e-6))  # per patch length
    n, rows, w = a.shape
    # per row, the colour weighted by alpha (one batched product over the columns)
    sums = np.matmul(a.reshape(n * rows, 1, w), color[..., :3].reshape(n * rows, w, 3))
    c = sums.reshape(n, rows, 3).sum(axis=0) / np.maximum(a.sum(axis=(0, 2)), 1e-9)[:, None]
    return sigma, c


def _met(depth, c, other=None) -> tuple[float, np.ndarray]:
    """A ray entering the rows from above, with optical depth `depth` in each row ((rows,),
    running upward) and their colours c ((rows, k)): the share of it their blades stop, and
    the colour they show it. `other`: the depth per row of another type's blades standing
    among them, which stop the ray too and take their own share of it."""
    t_own = np.asarray(depth, np.float64)[::-1]  # the rows from the top down
    t_all = t_own if other is None else t_own + np.asarray(other, np.float64)[::-1]
    stopped = np.exp(-np.concatenate([[0.0], np.cumsum(t_all)[:-1]])) * (1.0 - np.exp(-t_all))
    w = stopped * t_own / np.maximum(t_all, 1e-12)  # of what a row stops, these blades' share
    return float(w.sum()), (w[:, None] * c[::-1]).sum(axis=0) / max(float(w.sum()), 1e-9)


@dataclass(frozen=True)
class BladeDepths:
    """What a ray meets of a patch's blades, from their triangles, up from each height: each
    triangle gives a level ray crossing the patch the optical depth of its area seen along the
    ray, averaged over the horizontal directions (2/π |n_xz| of it), and a vertical ray its
    area seen from above (|n_y| of it, per patch area), times the share of it the blade's
    texture keeps. A slice's mean alpha saturates where a slab's blades overlap (dense turf in
    few slices: a row all but opaque says little of how many blades stand in it), and vertical
    slices show nothing of the blades' area from above, so both are counted on the blades."""

    heights: np.ndarray  # the triangles' centroid heights, rising
    side: np.ndarray  # the side depth of the triangles from each of those up
    top: np.ndarray  # their depth from above, the same way

    @classmethod
    def of(cls, positions: np.ndarray, uv: np.ndarray, triangles: np.ndarray) -> BladeDepths:
        """From a patch's vertex positions (m, 3), uv (m, 2) and triangle indices (t, 3)."""
        from core.patch import blade_fill

        p = np.asarray(positions, np.float64)
        a, b, c = p[triangles[:, 0]], p[triangles[:, 1]], p[triangles[:, 2]]
        cross = np.cross(b - a, c - a)  # twice the area along the normal
        fill = blade_fill(np.asarray(uv)[triangles, 1].mean(axis=1))
        side = 0.5 * np.hypot(cross[:, 0], cross[:, 2]) * (2.0 / np.pi) * fill
        top = 0.5 * np.abs(cross[:, 1]) * fill
        centroid = (a[:, 1] + b[:, 1] + c[:, 1]) / 3.0
        order = np.argsort(centroid)

        def up(depth: np.ndarray) -> np.ndarray:
            return np.cumsum(depth[order][::-1])[::-1]

        return cls(centroid[order], up(side), up(top))

    def _from(self, cumulative: np.ndarray, above) -> np.ndarray:
        i = np.searchsorted(self.heights, np.asarray(above, np.float64))
        return np.where(i < len(cumulative), cumulative[np.minimum(i, len(cumulative) - 1)], 0.0)

    def column(self, above: float = 0.0) -> float:
        """The depth of the blades from height `above` up, per patch length of a level ray."""
        return float(self._from(self.side, above))

    def rows(self, height: float, count: int) -> tuple[np.ndarray, np.ndarray]:
        """Side and top depth of each of `count` rows over 0 … height ((count,) each, rising);
        the highest row takes any blade above `height`."""
        bounds = np.linspace(0.0, height, count + 1)
        side, top = self._from(self.side, bounds), self._from(self.top, bounds)
        side[-1] = top[-1] = 0.0
        return side[:-1] - side[1:], top[:-1] - top[1:]


@dataclass(frozen=True)
class Canopy:
    """The rows' extinction and colour of each family of a patch's vertical slices, and the
    blades' own depths where known (what the tables here are computed from), kept small enough
    to keep beside the slices' textures."""

    profiles: tuple[tuple[np.ndarray, np.ndarray], ...]  # per family: σ (rows,), c (rows, 3)
    height: float
    blades: BladeDepths | None = None  # the blades' own depths, where known
    # what the top view shows: per row of heights (rising, over 0 … height), the share of its
    # cover there (its alpha-weighted histogram of the heights it shows)
    top_heights: np.ndarray | None = None

    @classmethod
    def of(
        cls,
        families: list[np.ndarray],
        height: float,
        blades: BladeDepths | None = None,
        top: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> Canopy:
        """`top`: the top view's alpha and the heights its texels show (equal shapes)."""
        profiles = tuple(_profile(color) for color in families)
        shown = None
        if top is not None:
            alpha, heights = (np.asarray(a, np.float64).ravel() for a in top)
            rows = len(profiles[0][0])
            shown, _ = np.histogram(heights, rows, (0.0, float(height)), weights=alpha)
            shown = shown / max(float(shown.sum()), 1e-12)
        return cls(profiles, float(height), blades, shown)

    def top_shade(self, ao_height: float) -> float:
        """The mean of 1 − smoothstep(0, B_height, y) over the heights y the top view shows
        (weighted by its cover): AO_blade (eq. 6.11) of what it shows is 1 − B_impact ·
        density · this. Without a top view, that of a view from straight above."""
        if self.top_heights is None:
            return float(self.shade_met(ao_height)[-1])
        y = (np.arange(self.rows) + 0.5) * self.dy
        t = np.clip(y / max(ao_height, 1e-6), 0.0, 1.0)
        return float((self.top_heights * (1.0 - t * t * (3.0 - 2.0 * t))).sum())

    @property
    def rows(self) -> int:
        return len(self.profiles[0][0])

    @property
    def dy(self) -> float:
        return self.height / self.rows

    @cached_property
    def _parts(self) -> tuple[np.ndarray, np.ndarray]:
        """Each row's depth from the side (per patch length of a level ray) and from above:
        the blades', else the slices' (the families' mean; nothing from above)."""
        if self.blades is not None:
            return self.blades.rows(self.height, self.rows)
        sigma = np.mean([profile[0] for profile in self.profiles], axis=0)
        return sigma * self.dy, np.zeros_like(sigma)

    def row_depths(self, theta, top: bool = True) -> np.ndarray:
        """The optical depth a ray at elevation θ (radians; (m,) or a scalar) meets descending
        through each row: (rows, m) or (rows,). `top`: with the blades' area seen from above
        (Campbell's ellipse); else their side alone."""
        side, up = self._parts
        tan = np.maximum(np.tan(np.asarray(theta, np.float64)), 1e-3)
        across = side.reshape(-1, *([1] * tan.ndim)) / tan
        if not top:
            return across
        return np.sqrt(up.reshape(across.shape[0], *([1] * tan.ndim)) ** 2 + across**2)

    def depth_at(self, y: np.ndarray, theta: float, top: bool = True) -> np.ndarray:
        """The optical depth per unit of height of these blades at heights y (world units) for
        a ray at elevation θ (`top` as in row_depths); 0 above the grass."""
        rows = np.floor(np.asarray(y) / self.dy).astype(np.int64)
        inside = (rows >= 0) & (rows < self.rows)
        per = self.row_depths(theta, top) / self.dy
        return np.where(inside, per[np.clip(rows, 0, self.rows - 1)], 0.0)

    def transmittance(self, y: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The share of a view from elevation θ (radians, (m,)) that reaches height y (world
        units, (k,)) through the rows above it: (k, m), half of y's own row counted."""
        through = np.exp(-self.cumulative(np.asarray(theta)))  # (rows + 1, m)
        return through[self.row_index(np.asarray(y))]

    def cumulative(self, theta: np.ndarray) -> np.ndarray:
        """((rows + 1, m)) the optical depth from the middle of each row to the top for rays
        at the elevations θ ((m,)), the last 0: above the grass. transmittance(y, θ) is
        exp(−cumulative(θ))[row_index(y)]; a caller with many y per θ takes the exponential
        once per value and θ."""
        depth = self.row_depths(np.atleast_1d(theta))  # (rows, m)
        above = np.cumsum(depth[::-1], axis=0)[::-1] - depth  # the rows above each
        return np.concatenate([above + 0.5 * depth, np.zeros((1, depth.shape[1]))])

    def row_index(self, y: np.ndarray) -> np.ndarray:
        """Each height's row (y's shape), `rows` above the grass (cumulative's last entry)."""
        y = np.asarray(y)
        rows = np.clip(np.floor(y / self.dy).astype(np.int64), 0, self.rows - 1)
        return np.where(y >= self.height, self.rows, rows)

    def side_column(self, above: float = 0.0) -> float:
        """The optical depth of the grass a level ray meets per patch length, summed over the
        heights from `above` (world units) to the top: Σ s(y). From the blades themselves
        where known, else from the rows of the slices (the families' mean, as their mean alpha
        says it). A ray at elevation θ crosses those heights over 1 / tan θ patch lengths for
        each unit of height, so its depth through them from the side is this / tan θ (the
        image-based grass's coverage, shaders/image.glsl; the volume's floor)."""
        if self.blades is not None:
            return self.blades.column(above)
        side, _ = self._parts
        lows = np.arange(self.rows) * self.dy
        part = np.clip((lows + self.dy - above) / self.dy, 0.0, 1.0)  # of each row, the share above
        return float((side * part).sum())

    def _met_each(self, values, theta: float, under: Canopy | None, top: bool = True):
        """_met at elevation θ for each family with its `values(c)` per row (`top` as in
        row_depths)."""
        depth = self.row_depths(theta, top)
        y = (np.arange(self.rows) + 0.5) * self.dy
        other = None if under is None else under.depth_at(y, theta, top) * self.dy
        return [_met(depth, values(c), other) for _sigma, c in self.profiles]

    def level_colors(self, count: int = ELEVATIONS, top: bool = True) -> np.ndarray:
        """(count, 3) colours met at each table elevation, the families' mean (`top` as in
        row_depths)."""
        return np.mean(
            [[m[1] for m in self._met_each(lambda c: c, t, None, top)] for t in elevations(count)],
            axis=1,
        ).astype(np.float32)

    @cached_property
    def side_colors(self) -> np.ndarray:
        """level_colors of what a ray meets of the blades' side alone: what the volume's
        crossings miss of its path (shaders/volume.glsl missed_blades) is their side."""
        return self.level_colors(top=False)

    def shade_met(
        self, ao_height: float, under: Canopy | None = None, count: int = ELEVATIONS
    ) -> np.ndarray:
        """Per table elevation, the mean of 1 − smoothstep(0, B_height, y) over the heights y a
        view from there meets of these blades (weighted as the colour is): AO_blade (eq. 6.11)
        of what the view meets is 1 − B_impact · density · this ((count,), the families' mean).
        `under`: another type's blades standing among these (as in `over`), which take the
        rays they stop."""
        y = (np.arange(self.rows) + 0.5) * self.dy
        t = np.clip(y / max(ao_height, 1e-6), 0.0, 1.0)
        dark = (1.0 - t * t * (3.0 - 2.0 * t))[:, None]
        return np.array(
            [np.mean([m[1][0] for m in self._met_each(lambda _c: dark, theta, under)])
             for theta in elevations(count)],
            np.float32,
        )  # fmt: skip

    def over(self, under: Canopy, count: int = ELEVATIONS) -> tuple[np.ndarray, np.ndarray]:
        """Of this grass standing in another type's (`under`, the shorter): per table
        elevation, the share of a ray these blades stop before anything else does, the other
        type's blades standing among them where both reach, and the colour they show it
        ((count,), (count, 3)). What the other type stops, or nothing, the other type's
        slice beneath draws."""
        met = [self._met_each(lambda c: c, theta, under) for theta in elevations(count)]
        return (
            np.array([np.mean([m[0] for m in each]) for each in met], np.float32),
            np.array([np.mean([m[1] for m in each], axis=0) for each in met], np.float32),
        )
